//! REPORT.md is generated, never hand-edited: its deterministic part must be
//! what the current code produces, and writing it must never lose the old one.

use stepladder_lab::report::{deterministic, deterministic_part, write_atomically};

#[test]
fn committed_report_is_up_to_date() {
    let path = crate::common::root().join("REPORT.md");
    let committed = std::fs::read_to_string(&path).expect("REPORT.md is committed");
    let fresh = deterministic(super::common::suite());
    assert!(
        deterministic_part(&committed) == fresh,
        "REPORT.md is stale: regenerate it with `cargo run --release`"
    );
}

/// Records do not depend on the thread count or on what ran beside them:
/// every fifth case and every tenth corpus entry, run again alone on this
/// thread, give the records the suite got on every core. A shift in the
/// parallel map's output order or state shared between cases would show
/// here; rerunning a sample instead of the whole suite keeps that evidence
/// at a tenth of the suite's cost.
#[test]
fn records_do_not_depend_on_the_thread_count() {
    use stepladder_lab::corpus::{entries, judge};
    use stepladder_lab::suite::{all_cases, run_case};
    let suite = super::common::suite();
    let cases = all_cases();
    assert_eq!(cases.len(), suite.cases.len());
    for (i, case) in cases.iter().enumerate().step_by(5) {
        let alone = run_case(case.as_ref()).expect("the case ran in the suite");
        let shared = &suite.cases[i];
        let what = format!("{} on {}", case.scheme().id, case.scene().id);
        assert_eq!(alone.order, shared.order, "order of {what}");
        assert_eq!(
            alone.hidden_order, shared.hidden_order,
            "hidden order of {what}"
        );
        assert_eq!(alone.energy, shared.energy, "energy of {what}");
        assert_eq!(
            alone.symplectic, shared.symplectic,
            "symplecticity of {what}"
        );
        assert_eq!(alone.reverse, shared.reverse, "reversibility of {what}");
    }
    let entries = entries();
    assert_eq!(entries.len(), suite.corpus.len());
    for (i, entry) in entries.iter().enumerate().step_by(10) {
        let alone = judge(entry).expect("the entry was judged in the suite");
        assert_eq!(alone, suite.corpus[i], "corpus entry {i}");
    }
}

/// The files committed in `dir` are `fresh`, file for file, with none
/// missing and none left over.
fn assert_folder_is(dir: &std::path::Path, fresh: &[(String, String)], what: &str) {
    let mut stale = Vec::new();
    for (name, text) in fresh {
        match std::fs::read_to_string(dir.join(name)) {
            Ok(committed) if committed == *text => {}
            Ok(_) => stale.push(format!("{name} differs")),
            Err(_) => stale.push(format!("{name} is missing")),
        }
    }
    let mut committed: Vec<String> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("the {what} are committed in {}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    committed.retain(|n| !fresh.iter().any(|(f, _)| f == n));
    stale.extend(
        committed
            .into_iter()
            .map(|n| format!("{n} is not written any more")),
    );
    assert!(
        stale.is_empty(),
        "{what} are stale ({}): regenerate them with `cargo run --release`",
        stale.join(", ")
    );
}

/// The figures committed beside REPORT.md are the ones the current code
/// draws from the suite's records. They show errors, force evaluations and
/// energies, never wall time, so they are the same on every machine and
/// thread count.
#[test]
fn committed_figures_are_up_to_date() {
    let fresh = stepladder_lab::report::figures::deterministic_figures(super::common::suite())
        .expect("the figures draw");
    let dir = crate::common::root().join(stepladder_lab::report::figures::FOLDER);
    assert_folder_is(&dir, &fresh, "figures");
}

/// The detail pages committed beside REPORT.md are the ones the current
/// code writes; like the report's deterministic part, they hold no timing.
#[test]
fn committed_detail_pages_are_up_to_date() {
    let fresh = stepladder_lab::report::pages::detail_pages(super::common::suite());
    let dir = crate::common::root().join(stepladder_lab::report::pages::FOLDER);
    assert_folder_is(&dir, &fresh, "detail pages");
}

#[test]
fn a_failed_write_leaves_the_previous_report_intact() {
    let dir = std::env::temp_dir().join(format!("stepladder-report-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("REPORT.md");
    write_atomically(&path, "old").unwrap();
    // a directory where the temporary file would go makes the write fail
    let blocker = dir.join(format!(".REPORT.md.tmp-{}", std::process::id()));
    std::fs::create_dir_all(&blocker).unwrap();
    assert!(write_atomically(&path, "new").is_err());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
    std::fs::remove_dir_all(&blocker).unwrap();
    write_atomically(&path, "new").unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
    std::fs::remove_dir_all(&dir).unwrap();
}

//! The committed audit of published crates (audit/AUDIT.md) is made by its
//! own command, outside CI (it builds five other crates and needs system
//! BLAS, LAPACK, MUMPS and SuiteSparse for one of them): these tests make a
//! table made from other sources fail instead of going stale.

use std::path::PathBuf;
use stepladder_lab::fingerprint::fingerprint;

#[test]
fn the_committed_audit_was_made_from_these_sources() {
    let root = crate::common::root();
    let root = root.as_path();
    let text = std::fs::read_to_string(root.join("audit/AUDIT.md")).expect("audit/AUDIT.md");
    let recorded = text
        .split("fingerprint `")
        .nth(1)
        .and_then(|rest| rest.split('`').next())
        .expect("AUDIT.md records the fingerprint of its sources");
    let now = fingerprint(root).expect("the sources can be read");
    assert_eq!(
        recorded, now,
        "audit/AUDIT.md was made from other sources (fingerprint {recorded}; this tree's is {now}): \
         make it again with `cargo run --release` in audit/ (README, \"Auditing published crates\") \
         and commit it"
    );
}

/// A scratch tree with the files the fingerprint reads.
fn scratch_tree(name: &str) -> PathBuf {
    let root = std::env::temp_dir().join(format!("stepladder-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    for (file, text) in [
        ("src/lib.rs", "pub mod scheme;"),
        ("src/scheme/mod.rs", "pub fn step() {}"),
        ("lab/src/cli/mod.rs", "fn main() {}"),
        ("lab/src/report/mod.rs", "fn report() {}"),
        ("audit/src/lib.rs", "fn audit() {}"),
        ("audit/tests/audit.rs", "#[test] fn t() {}"),
        ("audit/Cargo.toml", "[package]"),
        ("audit/Cargo.lock", "version = 4"),
        ("lab/references/pleiades.json", "{}"),
        ("lab/references/outer-solar-system.json", "{}"),
    ] {
        let path = root.join(file);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    root
}

#[test]
fn the_fingerprint_follows_what_the_audit_is_made_from_and_nothing_else() {
    let root = scratch_tree("fingerprint");
    let before = fingerprint(&root).unwrap();
    assert_eq!(before.len(), 16);
    assert_eq!(fingerprint(&root).unwrap(), before, "deterministic");
    // the lab (command line, report) is not what the audit runs
    std::fs::write(
        root.join("lab/src/cli/mod.rs"),
        "fn main() { /* changed */ }",
    )
    .unwrap();
    std::fs::write(root.join("lab/src/report/extra.rs"), "fn more() {}").unwrap();
    assert_eq!(fingerprint(&root).unwrap(), before);
    // a file outside the inputs (not Rust) changes nothing either
    std::fs::write(root.join("src/notes.txt"), "text").unwrap();
    assert_eq!(fingerprint(&root).unwrap(), before);
    // the library's studies, the audit's sources, its pinned versions and
    // the race references it reads do
    for (file, text) in [
        ("src/scheme/mod.rs", "pub fn step() { }"),
        ("audit/tests/audit.rs", "#[test] fn u() {}"),
        ("audit/Cargo.lock", "version = 4\n"),
        ("src/scheme/new.rs", ""),
        ("lab/references/outer-solar-system.json", "{ }"),
    ] {
        let was = fingerprint(&root).unwrap();
        std::fs::write(root.join(file), text).unwrap();
        assert_ne!(fingerprint(&root).unwrap(), was, "{file}");
    }
    std::fs::remove_dir_all(&root).unwrap();
}

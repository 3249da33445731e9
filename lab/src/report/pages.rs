//! The detail pages beside REPORT.md (in `details/`): every rung, every
//! tolerance and every corpus entry, the tables a reader opens to check one
//! figure of the report, kept out of the report so that it reads in one
//! scroll. Deterministic like the report, and checked for staleness alike.

use super::adaptive::ladder_table;
use super::hard_cases::following_rungs;
use super::markdown::wrap_prose;
use super::round_off::pair_rungs;
use super::{corpus_entries, rung_table, twin_table, work_precision, write_atomically};
use crate::suite::SuiteRecords;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use stepladder::error::Error;
use stepladder::scene::AnyScene;

/// The name of the pages' folder, relative to the report.
pub const FOLDER: &str = "details";

/// One page: its file name, its title and what the report says it holds.
struct Page {
    file: &'static str,
    title: &'static str,
    holds: &'static str,
    body: fn(&SuiteRecords) -> String,
}

const PAGES: [Page; 7] = [
    Page {
        file: "order-rungs.md",
        title: "Error against step size",
        holds: "every rung of every order ladder: error, final error, local order, \
                round-off bound and why a rung was left out of the fit",
        body: order_rungs,
    },
    Page {
        file: "exact-solution-withheld.md",
        title: "Exact solution withheld",
        holds: "every case again with the exact solution hidden, errors against the run \
                with half the step: the verdict must be the same",
        body: |r| {
            format!(
                "Every case again with the scene's exact solution hidden from the harness, \
                 errors measured against the run with half the step: the verdict must be the \
                 same and the order inside the exact run's interval.\n\n{}",
                twin_table(&r.cases)
            )
        },
    },
    Page {
        file: "corpus.md",
        title: "Every corpus entry",
        holds: "each correct and broken scheme and scene of the verdict corpus, with the \
                verdict it must get and the one it got",
        body: |r| corpus_entries(&r.corpus),
    },
    Page {
        file: "work-evaluations.md",
        title: "Force evaluations to reach each target",
        holds: "the numbers behind the work-precision figures, scheme by scheme and each \
                peer tolerance by tolerance",
        body: |r| work_precision::evaluations_by_target(&r.work),
    },
    Page {
        file: "adaptive-tolerances.md",
        title: "Adaptive integrators, tolerance by tolerance",
        holds: "every tolerance of every adaptive ladder: error, steps, rejections, cost",
        body: |r| {
            let mut out = String::new();
            for l in &r.adaptive.ladders {
                let _ = writeln!(out, "\n## {} on `{}`\n", l.integrator, l.scene);
                out.push_str(&ladder_table(l));
            }
            out
        },
    },
    Page {
        file: "separatrix-rungs.md",
        title: "Following the separatrix, rung by rung",
        holds: "every rung of every separatrix ladder: energy offset, following and \
                departure times",
        body: |r| r.hard.following.iter().map(following_rungs).collect(),
    },
    Page {
        file: "round-off-rungs.md",
        title: "Round-off floors, rung by rung",
        holds: "each plain Verlet form beside its compensated variant, rung by rung",
        body: |r| {
            r.roundoff
                .floors
                .iter()
                .flat_map(|f| &f.pairs)
                .map(pair_rungs)
                .collect()
        },
    },
];

fn order_rungs(records: &SuiteRecords) -> String {
    let mut out = String::from(
        "`error` is the largest phase-space error over the trajectory, `final` the error at \
         `t_end`, `local` the local order against the previous rung.\n",
    );
    let order = records.order();
    for scene in AnyScene::all() {
        let id = scene.meta().id;
        let _ = writeln!(out, "\n## {id}\n");
        for r in order.iter().filter(|r| r.scene == id) {
            out.push_str(&rung_table(r));
        }
    }
    out
}

/// Every page, as `(file name, Markdown)`.
pub fn detail_pages(records: &SuiteRecords) -> Vec<(String, String)> {
    PAGES
        .iter()
        .map(|p| {
            let text = format!(
                "# {}\n\n[Back to the report](../REPORT.md)\n\n{}",
                p.title,
                (p.body)(records)
            );
            (p.file.to_string(), wrap_prose(&text))
        })
        .collect()
}

/// The report's list of the pages, with what each holds.
pub fn index() -> String {
    let mut out = String::from("\n## Detail pages\n\n");
    for p in &PAGES {
        let _ = writeln!(out, "- [{}]({FOLDER}/{}): {}.", p.title, p.file, p.holds);
    }
    out
}

/// The folder of pages beside a report written to `report`.
pub fn beside(report: &Path) -> PathBuf {
    report
        .parent()
        .map_or_else(|| PathBuf::from(FOLDER), |d| d.join(FOLDER))
}

/// Writes every page into `dir` (created if missing), each atomically; the
/// files written.
pub fn write_pages(dir: &Path, records: &SuiteRecords) -> Result<Vec<PathBuf>, Error> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut written = Vec::new();
    for (name, text) in detail_pages(records) {
        let path = dir.join(name);
        write_atomically(&path, &text)?;
        written.push(path);
    }
    Ok(written)
}

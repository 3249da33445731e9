//! The report's first screen: what passed, the orders at a glance, the
//! verdict corpus, and the figures.

use super::figures::FOLDER;
use super::markdown::{Table, order};
use crate::corpus::Confusion;
use crate::suite::SuiteRecords;
use std::fmt::Write as _;
use stepladder::scene::scene_ids;
use stepladder::scheme::catalogue;
use stepladder::study::Verdict;

/// The summary section.
pub fn summary(records: &SuiteRecords) -> String {
    let mut out = String::from("## Summary\n\n");
    out.push_str(
        "[Method](#method) · [Schemes](#schemes) · [Scenes](#scenes) · \
         [Order of accuracy](#order-of-accuracy) · [Geometry](#geometry) · \
         [Verdict corpus](#verdict-corpus) · [Linear stability](#linear-stability) · \
         [Earth-Sun](#the-earth-sun-experiments) · [Hard cases](#hard-cases) · \
         [Speed against error](#speed-against-error) · [Round-off](#round-off-floors) · \
         [Detail pages](#detail-pages)\n\n",
    );
    out.push_str(
        "Integrators from published crates (utsuroi, differential-equations, ode_solvers, \
         peroxide, russell_ode, brahe), audited through the same black-box adapters a user \
         writes, each refuted claim confirmed independently of the harness: \
         [audit/AUDIT.md](audit/AUDIT.md).\n\n",
    );
    out.push_str(
        "What a green guard rules out: every coefficient of every catalogue table moved in \
         turn (by 1e-1 down to 1e-15, and in sign) or swapped with each other stage of its \
         kind, with the smallest change each claim rejects: \
         [lab/SENSITIVITY.md](lab/SENSITIVITY.md).\n\n",
    );
    out.push_str(&verdict_counts(records));
    out.push_str("\n### Orders at a glance\n\n");
    out.push_str(
        "The measured global order of every scheme on every scene (exact solution \
         known); **bold** where the verdict is not a pass.\n\n",
    );
    out.push_str(&orders_at_a_glance(records));
    out.push_str("\n### Verdict corpus\n\n");
    out.push_str(&confusion_table(&Confusion::of(&records.corpus)));
    out.push_str("\n### Figures\n\n");
    out.push_str(&figure_grid(records));
    out
}

/// Verdicts passed per study.
fn verdict_counts(records: &SuiteRecords) -> String {
    let count = |verdicts: Vec<Verdict>| {
        let pass = verdicts.iter().filter(|v| **v == Verdict::Pass).count();
        format!("{pass} of {}", verdicts.len())
    };
    let cases = &records.cases;
    let twins = cases
        .iter()
        .filter(|c| {
            let inside = match (c.order.ci95, c.hidden_order.measured_order) {
                (Some([lo, hi]), Some(p)) => lo <= p && p <= hi,
                (None, None) => true,
                _ => false,
            };
            c.order.verdict == c.hidden_order.verdict && inside
        })
        .count();
    let right = records.corpus.iter().filter(|o| o.right()).count();
    let mut t = Table::new(&["study", "passed"]);
    let rows = [
        (
            "global order, exact solution",
            count(cases.iter().map(|c| c.order.verdict).collect()),
        ),
        (
            "global order, exact solution withheld: same verdict, order inside the interval",
            format!("{twins} of {}", cases.len()),
        ),
        (
            "energy over 10^4 periods",
            count(cases.iter().map(|c| c.energy.verdict).collect()),
        ),
        (
            "symplecticity of the tangent map",
            count(cases.iter().map(|c| c.symplectic.verdict).collect()),
        ),
        (
            "reversibility",
            count(cases.iter().map(|c| c.reverse.verdict).collect()),
        ),
        (
            "phase error on the oscillator",
            count(records.phase.iter().filter_map(|p| p.verdict).collect()),
        ),
        (
            "scene checks",
            count(records.scenes.iter().map(|s| s.verdict).collect()),
        ),
        (
            "verdict corpus: entries judged right",
            format!("{right} of {}", records.corpus.len()),
        ),
    ];
    for (study, passed) in rows {
        t.row(vec![study.to_string(), passed]);
    }
    t.render()
}

/// Scheme rows, scene columns, measured orders.
fn orders_at_a_glance(records: &SuiteRecords) -> String {
    let scenes = scene_ids();
    let mut header = vec!["scheme", "claimed"];
    header.extend(scenes.iter().copied());
    let mut t = Table::new(&header);
    for meta in catalogue() {
        let mut row = vec![format!("`{}`", meta.id), meta.order.to_string()];
        for scene in &scenes {
            let cell = records
                .cases
                .iter()
                .map(|c| &c.order)
                .find(|o| o.scheme == meta.id && o.scene == *scene)
                .map_or("-".to_string(), |o| {
                    let p = o.measured_order.map_or("-".to_string(), order);
                    if o.verdict == Verdict::Pass {
                        p
                    } else {
                        format!("**{p} {}**", o.verdict.name())
                    }
                });
            row.push(cell);
        }
        t.row(row);
    }
    t.render()
}

/// The corpus' confusion matrix.
pub fn confusion_table(c: &Confusion) -> String {
    let mut m = Table::new(&["", "judged right", "judged wrong"]);
    m.row(vec![
        "correct pairs".into(),
        format!("{} pass", c.correct_pass),
        format!("{} false alarms", c.false_alarm),
    ]);
    m.row(vec![
        "broken pairs".into(),
        format!("{} caught", c.broken_caught),
        format!("{} missed", c.missed),
    ]);
    m.render()
}

/// The figures two abreast, each linked to its SVG.
fn figure_grid(records: &SuiteRecords) -> String {
    let mut out = String::new();
    let image = |name: &str, alt: &str, width: &str| {
        format!(
            "<a href=\"{FOLDER}/{name}\"><img src=\"{FOLDER}/{name}\" alt=\"{alt}\" width=\"{width}\"></a>"
        )
    };
    // one scene shown in full, the hardest (the eccentric orbit), the others linked
    const SHOWN: &str = "kepler-eccentric";
    let per_scene = |caption: &str, prefix: &str, scenes: &[&str]| {
        let others: Vec<String> = scenes
            .iter()
            .filter(|s| **s != SHOWN)
            .map(|s| format!("[{s}]({FOLDER}/{prefix}-{s}.svg)"))
            .collect();
        format!(
            "**{caption}**, on `{SHOWN}` (other scenes: {})\n\n<p>\n{}\n</p>\n\n",
            others.join(" · "),
            image(
                &format!("{prefix}-{SHOWN}.svg"),
                &format!("{caption}, {SHOWN}"),
                "100%"
            )
        )
    };
    let scenes = scene_ids();
    let work_scenes: Vec<&str> = records.work.iter().map(|w| w.scene).collect();
    out.push_str(&per_scene(
        "Global error against step, a panel a family, the fitted window solid",
        "convergence",
        &scenes,
    ));
    out.push_str(&per_scene(
        "Energy error against time, running maximum over 10^4 periods",
        "energy",
        &scenes,
    ));
    out.push_str(&per_scene(
        "Work against precision: force evaluations against global error, the adaptive \
         integrators in their own panel",
        "work",
        &work_scenes,
    ));
    let _ = writeln!(
        out,
        "**Linear stability limit per force evaluation; the Earth-Sun orbit of the course \
         notes**\n\n<p>\n{}\n{}\n</p>\n",
        image("stability.svg", "stability limits", "60%"),
        image("earth-sun-orbit.svg", "Earth-Sun orbits", "38%")
    );
    out
}

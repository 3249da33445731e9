//! Figures from the suite's records: SVG files written beside REPORT.md by
//! the report command (into `figures/`, or `--figures DIR`) and embedded in
//! it, and Mermaid charts that Markdown viewers render inline. Every figure
//! here is deterministic (errors, force evaluations, energies; never wall
//! time), so the committed copies can be checked for staleness like the
//! report. Nothing is computed here beyond choosing axes.

use super::plot::{Panel, Point, Series, colour, drawing, log_log_panels};
use crate::suite::SuiteRecords;
use crate::suite::work_precision::WorkRecord;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use stepladder::error::Error;
use stepladder::internals::accuracy::order::OrderRecord;
use stepladder::internals::accuracy::trajectory::TrajectoryRecord;
use stepladder::internals::geometry::energy::EnergyRecord;
use stepladder::internals::stability::StabilityRecord;
use stepladder::study::ToleranceLadderRecord;

/// The catalogue in panels of at most [`super::plot::MAX_SERIES`] schemes, by family,
/// so that every series of a panel has a colour and a marker of its own.
pub const FAMILIES: [(&str, &[&str]); 3] = [
    (
        "first and second order",
        &[
            "euler",
            "euler-cromer",
            "stormer-verlet",
            "leapfrog",
            "velocity-verlet",
            "position-verlet",
            "implicit-midpoint",
        ],
    ),
    (
        "splittings and compositions",
        &[
            "forest-ruth",
            "pefrl",
            "mclachlan-sb3a4",
            "mclachlan-sb3a5",
            "yoshida6",
            "kahan-li8",
        ],
    ),
    (
        "Nyström splittings and Runge-Kutta",
        &[
            "rk4",
            "rkn4-nystrom",
            "mclachlan-atela4",
            "blanes-moan-srkn11b",
            "rkn6-dormand-prince",
        ],
    ),
];

/// One panel per family of the series `of` gives for each scheme (in the
/// family's order; a scheme without a series is left out).
fn family_panels(of: impl Fn(&str) -> Option<Series>) -> Vec<Panel> {
    FAMILIES
        .iter()
        .map(|(family, ids)| Panel {
            title: family.to_string(),
            series: ids.iter().filter_map(|id| of(id)).collect(),
        })
        .collect()
}

/// Error against step for every scheme on one scene, a panel a family; the
/// rungs of the fitted window are solid, the others faded.
pub fn convergence(scene: &str, records: &[&OrderRecord]) -> Result<String, std::io::Error> {
    let panels = family_panels(|id| {
        let r = records
            .iter()
            .find(|r| r.scene == scene && r.scheme == id)?;
        Some(Series {
            name: match r.measured_order {
                Some(p) => format!("{id} (p = {p:.2})"),
                None => format!("{id} (no fit)"),
            },
            points: r
                .rungs
                .iter()
                .filter_map(|g| {
                    Some(Point {
                        x: g.h,
                        y: g.error?,
                        used: g.used,
                    })
                })
                .collect(),
        })
    });
    log_log_panels(
        &format!("global error against step, {scene} (solid markers: the fitted window)"),
        "h",
        "max phase-space error",
        &panels,
    )
}

/// Work against precision on one scene: the largest global error each
/// scheme reaches against the force evaluations it spends, a panel a family,
/// and the adaptive integrators (the crate's pairs over their tolerance
/// ladders, the peers over theirs) in a panel of their own.
pub fn work_precision(
    work: &WorkRecord,
    adaptive: &[ToleranceLadderRecord],
) -> Result<String, std::io::Error> {
    let mut panels = family_panels(|id| {
        let w = work.schemes.iter().find(|w| w.scheme == id)?;
        Some(Series::plain(
            id,
            w.global
                .iter()
                .filter_map(|p| Some((p.evaluations as f64, p.error?))),
        ))
    });
    let mut adaptive_series: Vec<Series> = adaptive
        .iter()
        .filter(|r| r.scene == work.scene)
        .map(|r| {
            Series::plain(
                r.integrator,
                r.points
                    .iter()
                    .filter_map(|p| Some((p.evaluations as f64, p.error?))),
            )
        })
        .collect();
    // a peer's own tolerance ladder, when the suite ran one, is already there
    for peer in work
        .peers
        .iter()
        .filter(|p| !adaptive.iter().any(|r| r.integrator == p.peer))
    {
        adaptive_series.push(Series::plain(
            format!("{} (peer)", peer.peer),
            peer.global
                .iter()
                .filter_map(|p| Some((p.evaluations as f64, p.error?))),
        ));
    }
    panels.push(Panel {
        title: "adaptive".to_string(),
        series: adaptive_series,
    });
    log_log_panels(
        &format!("work against precision, {}", work.scene),
        "force evaluations",
        "max phase-space error",
        &panels,
    )
}

/// Running maximum of the relative energy error against time, one scene, a
/// panel a family.
pub fn energy(scene: &str, records: &[&EnergyRecord]) -> Result<String, std::io::Error> {
    let panels = family_panels(|id| {
        let r = records
            .iter()
            .find(|r| r.scene == scene && r.scheme == id)?;
        Some(Series::plain(id, r.samples.iter().map(|&[t, m]| (t, m))))
    });
    log_log_panels(
        &format!("energy error over 10^4 periods, {scene}"),
        "t",
        "max |E - E0| / |E0| so far",
        &panels,
    )
}

/// The stability limit per force evaluation, one horizontal bar per scheme
/// (names stay readable however many there are). A scheme stable at every
/// step has no finite bar: an arrow runs past every bar, marked "unbounded";
/// one stable at no step draws a cross on zero, marked "0 (unstable at
/// every step)", so neither is mistaken for the other or for a short bar.
pub fn stability(records: &[StabilityRecord]) -> Result<String, std::io::Error> {
    let finite = records
        .iter()
        .filter_map(|r| r.limit_per_force_evaluation)
        .fold(1.0, f64::max);
    // room to the right of the longest bar for the arrow of an unbounded
    // interval and its label, so that neither touches a bar
    let top = finite * 1.9;
    let rows = records.len();
    let mut svg = String::new();
    {
        let size = (900, 80 + 28 * rows as u32);
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "linear stability limit per force evaluation (h w0 / evaluations)",
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(170)
            .build_cartesian_2d(0.0..top, (0..rows).into_segmented())
            .map_err(drawing)?;
        chart
            .configure_mesh()
            .disable_y_mesh()
            .y_labels(rows)
            .y_label_formatter(&|y| match y {
                SegmentValue::CenterOf(i) => rows
                    .checked_sub(i + 1)
                    .and_then(|k| records.get(k))
                    .map_or(String::new(), |r| r.scheme.to_string()),
                _ => String::new(),
            })
            .x_desc("largest stable h w0 per force evaluation")
            .draw()
            .map_err(drawing)?;
        // the catalogue reads from the top down
        let row = |k: usize| rows - 1 - k;
        let at = |k: usize| SegmentValue::CenterOf(row(k));
        for (i, r) in records.iter().enumerate() {
            let c = colour(0);
            match r.limit_per_force_evaluation {
                Some(v) if v > 0.0 => {
                    chart
                        .draw_series(std::iter::once(Rectangle::new(
                            [
                                (0.0, SegmentValue::Exact(row(i))),
                                (v, SegmentValue::Exact(row(i) + 1)),
                            ],
                            colour(5).mix(0.8).filled(),
                        )))
                        .map_err(drawing)?;
                    chart
                        .draw_series(std::iter::once(Text::new(
                            format!("{v:.3}"),
                            (v + 0.01 * top, at(i)),
                            ("sans-serif", 12).into_font().color(&c),
                        )))
                        .map_err(drawing)?;
                }
                Some(_) => {
                    chart
                        .draw_series(std::iter::once(
                            EmptyElement::at((0.0, at(i)))
                                + PathElement::new(
                                    vec![(-5, -5), (5, 5)],
                                    colour(6).stroke_width(2),
                                )
                                + PathElement::new(
                                    vec![(-5, 5), (5, -5)],
                                    colour(6).stroke_width(2),
                                )
                                + Text::new(
                                    "0 (unstable at every step)",
                                    (10, -6),
                                    ("sans-serif", 12).into_font().color(&colour(6)),
                                ),
                        ))
                        .map_err(drawing)?;
                }
                None => {
                    chart
                        .draw_series(std::iter::once(PathElement::new(
                            vec![(0.0, at(i)), (finite * 1.15, at(i))],
                            colour(3).stroke_width(3),
                        )))
                        .map_err(drawing)?;
                    chart
                        .draw_series(std::iter::once(
                            EmptyElement::at((finite * 1.15, at(i)))
                                + Polygon::new(vec![(0, -6), (10, 0), (0, 6)], colour(3).filled())
                                + Text::new(
                                    "unbounded (stable at every step)",
                                    (16, -6),
                                    ("sans-serif", 12).into_font().color(&colour(3)),
                                ),
                        ))
                        .map_err(drawing)?;
                }
            }
        }
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}

/// The Earth-Sun orbits in the x-y plane.
pub fn earth_sun_orbit(runs: &[TrajectoryRecord]) -> Result<String, std::io::Error> {
    let reach = runs
        .iter()
        .flat_map(|r| r.positions.iter().flat_map(|p| p.iter().map(|x| x.abs())))
        .fold(1.0, f64::max)
        .min(50.0)
        * 1.05;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (700, 700)).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let mut chart = ChartBuilder::on(&root)
            .caption("Earth-Sun, 10 years: orbit", ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(-reach..reach, -reach..reach)
            .map_err(drawing)?;
        chart
            .configure_mesh()
            .x_desc("x (AU)")
            .y_desc("y (AU)")
            .draw()
            .map_err(drawing)?;
        for (i, r) in runs.iter().enumerate() {
            let c = colour(i);
            let pts = r.positions.iter().map(|p| (p[0], p[1]));
            chart
                .draw_series(LineSeries::new(pts, c.stroke_width(1)))
                .map_err(drawing)?
                .label(format!("{} (dt = {})", r.scheme, r.h))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            // the orbits are round: the corner is the one place free of data
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(drawing)?;
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}

/// The Earth-Sun relative energy error against time, log scale.
pub fn earth_sun_energy(runs: &[TrajectoryRecord]) -> Result<String, std::io::Error> {
    let series: Vec<Series> = runs
        .iter()
        .map(|r| {
            Series::plain(
                format!("{} (dt = {})", r.scheme, r.h),
                r.times
                    .iter()
                    .zip(&r.relative_energy_error)
                    .map(|(&t, &e)| (t, e.abs())),
            )
        })
        .collect();
    log_log_panels(
        "Earth-Sun, 10 years: |E - E0| / |E0|",
        "t (years)",
        "relative energy error",
        &[Panel {
            title: String::new(),
            series,
        }],
    )
}

/// Every deterministic figure of the suite, as `(file name, SVG)`: error
/// against step, energy error against time and work against precision per
/// scene, the stability limits, the Earth-Sun experiments.
pub fn deterministic_figures(records: &SuiteRecords) -> Result<Vec<(String, String)>, Error> {
    let order = records.order();
    let energies: Vec<&EnergyRecord> = records.cases.iter().map(|c| &c.energy).collect();
    let mut figures: Vec<(String, Result<String, std::io::Error>)> = Vec::new();
    for scene in stepladder::scene::scene_ids() {
        figures.push((
            format!("convergence-{scene}.svg"),
            convergence(scene, &order),
        ));
        figures.push((format!("energy-{scene}.svg"), energy(scene, &energies)));
    }
    for w in &records.work {
        figures.push((
            format!("work-{}.svg", w.scene),
            work_precision(w, &records.adaptive.ladders),
        ));
    }
    figures.push(("stability.svg".into(), stability(&records.stability)));
    figures.push((
        "earth-sun-orbit.svg".into(),
        earth_sun_orbit(&records.earth_sun),
    ));
    figures.push((
        "earth-sun-energy.svg".into(),
        earth_sun_energy(&records.earth_sun),
    ));
    figures
        .into_iter()
        .map(|(name, svg)| {
            svg.map(|svg| (name.clone(), svg))
                .map_err(|source| Error::Io {
                    path: PathBuf::from(name),
                    source,
                })
        })
        .collect()
}

/// The folder of figures beside a report written to `report`.
pub fn beside(report: &Path) -> PathBuf {
    report
        .parent()
        .map_or_else(|| PathBuf::from(FOLDER), |d| d.join(FOLDER))
}

/// The name of the figures' folder, relative to the report.
pub const FOLDER: &str = "figures";

/// Writes every figure into `dir` (created if missing), each atomically;
/// the files written.
pub fn write_figures(dir: &Path, records: &SuiteRecords) -> Result<Vec<PathBuf>, Error> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut written = Vec::new();
    for (name, svg) in deterministic_figures(records)? {
        let path = dir.join(name);
        super::write_atomically(&path, &svg)?;
        written.push(path);
    }
    Ok(written)
}

/// A Mermaid line chart (rendered by GitHub and most Markdown viewers) of
/// `log10 |y|` against shared x labels, one line per series; the legend is
/// written beneath it, since the chart type has none.
pub fn mermaid_lines(
    title: &str,
    x_label: &str,
    xs: &[f64],
    y_label: &str,
    series: &[(String, Vec<f64>)],
) -> String {
    let logs: Vec<Vec<f64>> = series
        .iter()
        .map(|(_, ys)| {
            ys.iter()
                .map(|y| {
                    if *y > 0.0 {
                        (y.log10() * 100.0).round() / 100.0
                    } else {
                        -17.0
                    }
                })
                .collect()
        })
        .collect();
    // (+ 0.0 turns a -0 into 0)
    let lo = logs
        .iter()
        .flatten()
        .copied()
        .fold(f64::MAX, f64::min)
        .floor()
        + 0.0;
    let hi = logs
        .iter()
        .flatten()
        .copied()
        .fold(f64::MIN, f64::max)
        .ceil()
        + 0.0;
    let mut out = String::from("```mermaid\nxychart-beta\n");
    let _ = writeln!(out, "    title \"{title}\"");
    let labels: Vec<String> = xs.iter().map(|x| format!("{x}")).collect();
    let _ = writeln!(out, "    x-axis \"{x_label}\" [{}]", labels.join(", "));
    let _ = writeln!(out, "    y-axis \"log10 {y_label}\" {lo} --> {hi}");
    for line in &logs {
        let values: Vec<String> = line.iter().map(|v| format!("{v}")).collect();
        let _ = writeln!(out, "    line [{}]", values.join(", "));
    }
    out.push_str("```\n\n");
    let legend: Vec<String> = series
        .iter()
        .enumerate()
        .map(|(i, (name, _))| format!("line {}: {name}", i + 1))
        .collect();
    let _ = writeln!(out, "{}.\n", legend.join("; "));
    out
}

/// A Mermaid bar chart of `values` by label.
pub fn mermaid_bars(title: &str, labels: &[&str], y_label: &str, values: &[f64]) -> String {
    let hi = values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max)
        * 1.1;
    let mut out = String::from("```mermaid\nxychart-beta\n");
    let _ = writeln!(out, "    title \"{title}\"");
    let _ = writeln!(
        out,
        "    x-axis [{}]",
        labels
            .iter()
            .map(|l| format!("\"{l}\""))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(out, "    y-axis \"{y_label}\" 0 --> {:.2}", hi.max(0.01));
    let v: Vec<String> = values
        .iter()
        .map(|v| {
            if v.is_finite() {
                format!("{v:.3}")
            } else {
                "0".into()
            }
        })
        .collect();
    let _ = writeln!(out, "    bar [{}]", v.join(", "));
    out.push_str("```\n\n");
    out
}

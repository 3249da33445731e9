//! Figures from the suite's records: SVG files written beside REPORT.md by
//! the report command (into `figures/`, or `--figures DIR`) and embedded in
//! it, and Mermaid charts that Markdown viewers render inline. Every figure
//! here is deterministic (errors, force evaluations, energies; never wall
//! time), so the committed copies can be checked for staleness like the
//! report. Nothing is computed here beyond choosing axes.

use crate::suite::SuiteRecords;
use crate::suite::work_precision::WorkRecord;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use stepladder::error::Error;
use stepladder::study::accuracy::order::OrderRecord;
use stepladder::study::accuracy::trajectory::TrajectoryRecord;
use stepladder::study::geometry::energy::EnergyRecord;
use stepladder::study::stability::StabilityRecord;

const SIZE: (u32, u32) = (900, 560);

/// A distinct colour for the `i`-th series.
fn colour(i: usize) -> RGBColor {
    const PALETTE: [RGBColor; 13] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
        RGBColor(0, 0, 128),
        RGBColor(128, 0, 0),
        RGBColor(0, 100, 0),
    ];
    PALETTE[i % PALETTE.len()]
}

/// The plotting library's error as text: figures are best effort for the
/// caller, who reports a failure as an I/O problem of the figure file.
fn drawing<E: std::fmt::Debug>(e: E) -> std::io::Error {
    std::io::Error::other(format!("{e:?}"))
}

/// Log-log lines `(x, y)` with a legend; non-positive points are skipped.
fn log_log(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[(String, Vec<(f64, f64)>)],
    legend: SeriesLabelPosition,
) -> Result<String, std::io::Error> {
    let points = series
        .iter()
        .flat_map(|(_, p)| p)
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in points {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if x0 >= x1 || y0 >= y1 {
        (x0, x1, y0, y1) = (1e-3, 1.0, 1e-3, 1.0);
    }
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (x0 / 1.5..x1 * 1.5).log_scale(),
                (y0 / 3.0..y1 * 3.0).log_scale(),
            )
            .map_err(drawing)?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(y_desc)
            .x_label_formatter(&|x| format!("{x:.0e}"))
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .draw()
            .map_err(drawing)?;
        for (i, (name, pts)) in series.iter().enumerate() {
            let c = colour(i);
            let good: Vec<(f64, f64)> = pts
                .iter()
                .copied()
                .filter(|(x, y)| *x > 0.0 && *y > 0.0)
                .collect();
            chart
                .draw_series(LineSeries::new(good, c.stroke_width(2)))
                .map_err(drawing)?
                .label(name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(legend)
            .draw()
            .map_err(drawing)?;
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}

/// Error against step for every scheme on one scene.
pub fn convergence(scene: &str, records: &[&OrderRecord]) -> Result<String, std::io::Error> {
    let series: Vec<(String, Vec<(f64, f64)>)> = records
        .iter()
        .filter(|r| r.scene == scene)
        .map(|r| {
            (
                match r.measured_order {
                    Some(p) => format!("{} (fitted p = {p:.2})", r.scheme),
                    None => format!("{} (no fit)", r.scheme),
                },
                r.rungs
                    .iter()
                    .filter_map(|g| Some((g.h, g.error?)))
                    .collect(),
            )
        })
        .collect();
    log_log(
        &format!("global error against step: {scene}"),
        "h",
        "max phase-space error",
        &series,
        // errors fall to the right: small steps with large errors never occur
        SeriesLabelPosition::UpperLeft,
    )
}

/// Work against precision on one scene: the largest global error each
/// scheme (and the peer, over its tolerances) reaches against the force
/// evaluations it spends, both axes logarithmic.
pub fn work_precision(work: &WorkRecord) -> Result<String, std::io::Error> {
    let mut series: Vec<(String, Vec<(f64, f64)>)> = work
        .schemes
        .iter()
        .map(|w| {
            (
                w.scheme.to_string(),
                w.global
                    .iter()
                    .filter_map(|p| Some((p.evaluations as f64, p.error?)))
                    .collect(),
            )
        })
        .collect();
    if let Some(peer) = &work.peer {
        series.push((
            format!("{} (adaptive)", peer.peer),
            peer.global
                .iter()
                .filter_map(|p| Some((p.evaluations as f64, p.error?)))
                .collect(),
        ));
    }
    log_log(
        &format!("work against precision: {}", work.scene),
        "force evaluations",
        "max phase-space error",
        &series,
        // much work for a large error never occurs
        SeriesLabelPosition::UpperRight,
    )
}

/// Running maximum of the relative energy error against time, one scene.
pub fn energy(scene: &str, records: &[&EnergyRecord]) -> Result<String, std::io::Error> {
    let series: Vec<(String, Vec<(f64, f64)>)> = records
        .iter()
        .filter(|r| r.scene == scene)
        .map(|r| {
            (
                r.scheme.to_string(),
                r.samples.iter().map(|&[t, m]| (t, m)).collect(),
            )
        })
        .collect();
    log_log(
        &format!("energy error over 10^4 periods: {scene}"),
        "t",
        "max |E - E0| / |E0| so far",
        &series,
        SeriesLabelPosition::LowerLeft,
    )
}

/// The stability limit per force evaluation, one bar per scheme; where there
/// is no bar, a word says whether the scheme is stable at every step (`no
/// limit`) or at none (`0`).
pub fn stability(records: &[StabilityRecord]) -> Result<String, std::io::Error> {
    let bars: Vec<(&str, f64)> = records
        .iter()
        .map(|r| (r.scheme, r.limit_per_force_evaluation.unwrap_or(f64::NAN)))
        .collect();
    let top = bars
        .iter()
        .map(|b| b.1)
        .filter(|v| v.is_finite())
        .fold(1.0, f64::max)
        * 1.15;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "linear stability limit per force evaluation (h w0)",
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(90)
            .y_label_area_size(60)
            .build_cartesian_2d(0..bars.len(), 0.0..top)
            .map_err(drawing)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(bars.len())
            .x_label_formatter(&|i| bars.get(*i).map_or(String::new(), |b| b.0.to_string()))
            .y_desc("stable h w0 per evaluation")
            .draw()
            .map_err(drawing)?;
        chart
            .draw_series(
                bars.iter()
                    .enumerate()
                    .filter(|(_, b)| b.1.is_finite())
                    .map(|(i, b)| Rectangle::new([(i, 0.0), (i + 1, b.1)], colour(i).filled())),
            )
            .map_err(drawing)?;
        // no bar for two opposite reasons: say which
        chart
            .draw_series(bars.iter().enumerate().filter_map(|(i, b)| {
                let word = if b.1.is_nan() {
                    "no limit"
                } else if b.1 == 0.0 {
                    "0"
                } else {
                    return None;
                };
                Some(Text::new(word, (i, 0.02 * top), ("sans-serif", 11)))
            }))
            .map_err(drawing)?;
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
            .draw()
            .map_err(drawing)?;
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}

/// The Earth-Sun relative energy error against time, log scale.
pub fn earth_sun_energy(runs: &[TrajectoryRecord]) -> Result<String, std::io::Error> {
    let series: Vec<(String, Vec<(f64, f64)>)> = runs
        .iter()
        .map(|r| {
            let pts = r
                .times
                .iter()
                .zip(&r.relative_energy_error)
                .map(|(&t, &e)| (t, e.abs()))
                .collect();
            (format!("{} (dt = {})", r.scheme, r.h), pts)
        })
        .collect();
    log_log(
        "Earth-Sun, 10 years: |E - E0| / |E0|",
        "t (years)",
        "relative energy error",
        &series,
        SeriesLabelPosition::LowerRight,
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
        figures.push((format!("work-{}.svg", w.scene), work_precision(w)));
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

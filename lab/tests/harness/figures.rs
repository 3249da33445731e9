//! The figures and the Earth-Sun experiments behind them.

use stepladder::internals::accuracy::trajectory::earth_sun_experiments;
use stepladder_lab::report::figures::{mermaid_bars, mermaid_lines, write_figures};

/// Euler on the circular orbit gains `h^2 |a|^2 / 2 = h^2 w^4 r^2 / 2` of
/// energy a step (`r` stays perpendicular to `v`): relative to
/// `|E| = 2 pi^2` that is 3.9e-5 a step at `h = 0.001`, 0.39 over ten years
/// to first order, somewhat less as the orbit expands and slows. Velocity
/// Verlet keeps a modified energy: its error stays at the size of its step's
/// `(h w)^2 = 3.9e-3`, far below it in fact on a circle.
#[test]
fn the_earth_sun_experiments_show_what_the_course_notes_show() {
    let runs = earth_sun_experiments();
    let (euler, verlet) = (&runs[0], &runs[1]);
    assert_eq!((euler.scheme, verlet.scheme), ("euler", "velocity-verlet"));
    let final_euler = *euler.relative_energy_error.last().unwrap();
    assert!(
        final_euler > 0.2 && final_euler < 0.39,
        "Euler gained {final_euler}"
    );
    let radius = |p: &Vec<f64>| p.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(
        radius(euler.positions.last().unwrap()) > 1.2,
        "Euler's orbit did not spiral out"
    );
    let worst_verlet = verlet
        .relative_energy_error
        .iter()
        .fold(0.0f64, |a, e| a.max(e.abs()));
    assert!(worst_verlet < 3.9e-3, "{worst_verlet}");
    assert!((radius(verlet.positions.last().unwrap()) - 1.0).abs() < 1e-3);
}

#[test]
fn every_figure_is_written_as_svg() {
    let dir = std::env::temp_dir().join(format!("stepladder-figures-{}", std::process::id()));
    let written = write_figures(&dir, super::common::suite()).unwrap();
    assert!(written.len() >= 7, "{written:?}");
    for path in &written {
        let text = std::fs::read_to_string(path).unwrap();
        assert!(
            text.starts_with("<svg") && text.trim_end().ends_with("</svg>"),
            "{path:?}"
        );
    }
    assert!(written.iter().any(|p| p.ends_with("earth-sun-orbit.svg")));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn mermaid_charts_take_logs_and_keep_every_series() {
    let chart = mermaid_lines(
        "t",
        "x",
        &[1.0, 2.0],
        "y",
        &[
            ("a".into(), vec![1e-3, 1e-2]),
            ("b".into(), vec![1.0, 10.0]),
        ],
    );
    assert!(
        chart.contains("line [-3, -2]") && chart.contains("line [0, 1]"),
        "{chart}"
    );
    assert!(chart.contains("y-axis \"log10 y\" -3 --> 1"), "{chart}");
    assert!(chart.contains("line 1: a; line 2: b"));
    let bars = mermaid_bars("t", &["p", "q"], "y", &[2.0, f64::NAN]);
    assert!(bars.contains("bar [2.000, 0]"), "{bars}");
}

/// Every catalogue scheme is drawn in exactly one family's panel, and no
/// panel holds more series than there are colours and markers.
#[test]
fn every_scheme_has_one_panel_and_no_panel_is_crowded() {
    use stepladder_lab::report::figures::FAMILIES;
    use stepladder_lab::report::plot::MAX_SERIES;
    for meta in stepladder::scheme::catalogue() {
        let panels = FAMILIES
            .iter()
            .filter(|(_, ids)| ids.contains(&meta.id))
            .count();
        assert_eq!(panels, 1, "{} is in {panels} panels", meta.id);
    }
    let drawn: usize = FAMILIES.iter().map(|(_, ids)| ids.len()).sum();
    assert_eq!(
        drawn,
        stepladder::scheme::catalogue().len(),
        "no unknown id"
    );
    for (family, ids) in FAMILIES {
        assert!(ids.len() <= MAX_SERIES, "{family}: {} series", ids.len());
    }
}

/// A panel of more series than colours is refused, never drawn with shared
/// colours.
#[test]
fn a_crowded_panel_is_refused() {
    use stepladder_lab::report::plot::{MAX_SERIES, Panel, Series, log_log_panels};
    let series = |n: usize| -> Vec<Series> {
        (0..n)
            .map(|i| Series::plain(format!("s{i}"), [(1.0, 1.0 + i as f64), (2.0, 2.0)]))
            .collect()
    };
    let panel = |n| Panel {
        title: "p".into(),
        series: series(n),
    };
    assert!(log_log_panels("t", "x", "y", &[panel(MAX_SERIES)]).is_ok());
    let err = log_log_panels("t", "x", "y", &[panel(MAX_SERIES + 1)]).unwrap_err();
    assert!(err.to_string().contains("more than 8"), "{err}");
}

//! Bad input over random draws: non-finite, zero, negative, huge and tiny
//! values for every numeric field of the public specs and constructors, and
//! for every numeric option of the command line. Each is refused before any
//! run with a typed error that prints the offending value and the valid
//! range (or the true step count and the limit), never accepted, never a
//! panic, and never a saturated or 300-digit figure.

use super::cli::run;
use proptest::prelude::*;
use stepladder::error::Error;
use stepladder::internals::accuracy::order::{OrderSpec, global_order};
use stepladder::internals::geometry::energy::{EnergySpec, energy_drift};
use stepladder::internals::geometry::reverse::{ReverseSpec, reversibility};
use stepladder::internals::geometry::symplectic::{SymplecticSpec, symplecticity};
use stepladder::internals::hard::escape::EscapeSpec;
use stepladder::internals::ladder::{AutoLadder, Ladder, LadderChoice};
use stepladder::internals::round_off::floor::{RoundoffSpec, roundoff};
use stepladder::internals::wording::exact;
use stepladder::scene::{Anharmonic, Harmonic, KeplerEccentric, Separatrix};
use stepladder::scheme::{Euler, VELOCITY_VERLET};

/// Cases per property: few, since each is refused before any run.
const CASES: u32 = 32;

/// Values no positive step, span, scale or count can take, and those past
/// any range: NaN, the infinities, zeros, negatives, and the extremes of
/// the doubles.
fn hostile() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(1e300),
        Just(f64::MAX),
        Just(1e-300),
        Just(5e-324),
        -1e300..-1e-300f64,
        1e60..1e308f64,
        1e-320..1e-60f64,
    ]
}

/// Values in the range of a positive step or span, but far too small to
/// be run: refused as too many steps.
fn tiny() -> impl Strategy<Value = f64> {
    prop_oneof![Just(1e-300), Just(5e-324), 1e-320..1e-20f64]
}

/// A refusal is one line that names the value as typed and the range, or
/// the true count and the limit; no figure of 20 digits or more.
fn assert_refusal(e: &Error, value: f64) {
    let text = e.to_string();
    assert_eq!(text.lines().count(), 1, "{text}");
    let says_range = text.contains(&format!("= {} is invalid: expected", exact(value)));
    let says_cost = text.contains("refusing a run of") && text.contains("the limit is");
    assert!(says_range || says_cost, "{value:e}: {text}");
    let longest_digits = text
        .split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0);
    assert!(longest_digits < 20, "a saturated or long figure: {text}");
    if let Error::TooExpensive { steps, .. } = e {
        assert!(*steps > 2e9, "{text}");
    }
}

fn refused<T: std::fmt::Debug>(r: Result<T, Error>, value: f64) {
    match r {
        Err(e) => assert_refusal(&e, value),
        Ok(v) => panic!("{value:e} was accepted: {v:?}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    #[test]
    fn ladders_refuse_bad_first_steps_and_ratios(x in hostile()) {
        // over a run of 10: a first step that is not positive, longer than
        // the run, or so short that the rungs are too many steps
        refused(Ladder::new(x, 0.5, 8).and_then(|l| l.rungs(10.0)), x);
        // a ratio that is not positive, or of one or more, does not refine
        if x.is_nan() || x <= 0.0 {
            refused(Ladder::new(0.1, x, 8), x);
        }
        refused(Ladder::new(0.1, 1.0 + x.abs(), 8), 1.0 + x.abs());
    }

    #[test]
    fn order_specs_refuse_bad_end_times_and_steps(x in hostile(), t in tiny()) {
        let osc = Harmonic::default();
        let spec = OrderSpec { t_end: Some(x), ..OrderSpec::default() };
        refused(global_order(&Euler, &osc, &spec), x);
        // a fixed ladder of a tiny first step is too many steps
        let ladder = LadderChoice::Fixed(Ladder::new(t, 0.5, 8).unwrap());
        refused(global_order(&Euler, &osc, &OrderSpec { t_end: None, ladder }), t);
        // a first step longer than the run
        let ladder = LadderChoice::Fixed(Ladder::new(1.0, 0.5, 8).unwrap());
        let t_end = 0.999 - t.min(0.5);
        refused(global_order(&Euler, &osc, &OrderSpec { t_end: Some(t_end), ladder }), t_end);
    }

    #[test]
    fn automatic_ladders_refuse_densities_and_caps_out_of_range(
        m in prop_oneof![Just(0u32), 17..=u32::MAX],
        cap in prop_oneof![0..4096u64, 500_000_001..=u64::MAX],
    ) {
        let osc = Harmonic::default();
        for settings in [
            AutoLadder { per_octave: Some(m), ..AutoLadder::default() },
            AutoLadder { per_octave: None, max_rung_evaluations: cap },
        ] {
            let spec = OrderSpec { t_end: None, ladder: LadderChoice::AutoWith(settings) };
            let e = global_order(&Euler, &osc, &spec).unwrap_err();
            let value = if settings.per_octave.is_some() { f64::from(m) } else { cap as f64 };
            assert_refusal(&e, value);
        }
    }

    #[test]
    fn energy_specs_refuse_bad_steps_and_lengths(x in hostile(), t in tiny()) {
        let osc = Harmonic::default();
        for scheme_conserves in [false, true] {
            let run = |spec: EnergySpec| if scheme_conserves {
                energy_drift(&VELOCITY_VERLET, &osc, &spec)
            } else {
                energy_drift(&Euler, &osc, &spec)
            };
            refused(run(EnergySpec { h: Some(x), periods: None }), x);
            refused(run(EnergySpec { h: None, periods: Some(x) }), x);
            refused(run(EnergySpec { h: Some(t), periods: Some(1.0) }), t);
            refused(run(EnergySpec { h: Some(1.0), periods: Some(t) }), 1.0);
        }
    }

    #[test]
    fn reverse_and_symplectic_specs_refuse_bad_steps(x in hostile(), n in 1_000_000_001..=u64::MAX) {
        let osc = Harmonic::default();
        refused(reversibility(&Euler, &osc, &ReverseSpec { h: Some(x), steps: None }), x);
        refused(symplecticity(&Euler, &osc, &SymplecticSpec { h: Some(x) }), x);
        // twice a huge count is refused with its true value, not a saturated one
        let e = reversibility(&Euler, &osc, &ReverseSpec { h: None, steps: Some(n) }).unwrap_err();
        let Error::TooExpensive { steps, .. } = e else { panic!("{e}") };
        prop_assert_eq!(steps, 2.0 * n as f64);
    }

    #[test]
    fn roundoff_specs_refuse_bad_lengths(x in hostile()) {
        let osc = stepladder::scene::AnyScene::parse("harmonic").unwrap();
        refused(roundoff(&osc, &RoundoffSpec { periods: Some(x), max_steps: None }), x);
    }

    #[test]
    fn scenes_refuse_bad_parameters(x in hostile()) {
        refused(Harmonic::new(x, 1.0, 0.0), x);
        refused(Separatrix::new(x, 1.0), x);
        refused(Separatrix::new(1.0, x), x);
        refused(Anharmonic::new(x, 1.0, 0.5, 0.0), x);
        refused(EscapeSpec::new(x), x);
        refused(KeplerEccentric::new(1.0 + x.abs()), 1.0 + x.abs());
        // a coordinate may be zero, not outside the magnitudes
        if x != 0.0 {
            refused(Harmonic::new(1.0, x, 0.0), x);
            refused(Harmonic::new(1.0, 1.0, x), x);
        }
    }
}

/// The command line's options, one hostile value each: exit status 2, one
/// line on stderr with the value (or the true count), nothing on stdout.
#[test]
fn every_numeric_option_refuses_hostile_values() {
    let case = ["--scheme", "euler", "--scene", "harmonic"];
    let values = ["nan", "inf", "-inf", "0", "-1", "1e300", "1e-300", "5e-324"];
    let options: [(&[&str], &str); 9] = [
        (&["energy"], "--h"),
        (&["energy"], "--periods"),
        (&["symplectic"], "--h"),
        (&["reverse"], "--h"),
        (&["order"], "--h0"),
        (&["order"], "--t-end"),
        (&["order"], "--ratio"),
        (&["roundoff"], "--periods"),
        (&["separatrix", "--scheme", "euler"], "--k"),
    ];
    for (command, option) in options {
        for value in values {
            let mut args: Vec<&str> = command.to_vec();
            if matches!(command[0], "energy" | "symplectic" | "reverse" | "order") {
                args.extend_from_slice(&case);
            }
            // `--h=-inf`: a value that starts with a hyphen is not an option
            let pair = format!("{option}={value}");
            args.push(&pair);
            let out = run(&args);
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
            assert!(out.stdout.is_empty(), "{args:?} printed to stdout");
            let typed: f64 = value.parse().unwrap();
            let named = err.contains(&format!("= {} is invalid", exact(typed)))
                || err.contains("refusing a run of");
            assert!(named, "{args:?}: {err}");
            assert!(
                !err.split(|c: char| !c.is_ascii_digit())
                    .any(|d| d.len() >= 20),
                "{args:?}: {err}"
            );
        }
    }
}

/// The three requests of the report: a step longer than the whole run, and
/// runs of more steps than any integer holds, refused with the true
/// figures.
#[test]
fn huge_steps_and_runs_print_true_figures() {
    let energy = ["energy", "--scheme", "euler", "--scene", "harmonic"];
    let out = run(&[&energy[..], &["--h", "1e300"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("h = 1e300 is invalid") && err.contains("at least one step"),
        "{err}"
    );
    let out = run(&[&energy[..], &["--periods", "1e12"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    // 1e12 periods at the default 100 steps a period
    assert!(err.contains("refusing a run of 1.00e14 steps"), "{err}");
    let out = run(&[
        "order", "--scheme", "euler", "--scene", "harmonic", "--t-end", "1e300",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    // 1e300 over the automatic ladder's first step, 2 pi / 8
    let n = 1e300 / (std::f64::consts::TAU / 8.0);
    let printed = stepladder::internals::wording::figure(n);
    assert!(
        err.contains(&format!("refusing a run of {printed} steps")),
        "{err}"
    );
}

fn velocity_verlet(q: &mut [f64], v: &mut [f64], h: f64, force: &stepladder::scheme::Force<f64>) {
    let mut a = [0.0];
    force(q, &mut a);
    v[0] += 0.5 * h * a[0];
    q[0] += h * v[0];
    force(q, &mut a);
    v[0] += 0.5 * h * a[0];
}

/// Ids name pin files: an id that is a path is refused before any study
/// runs, and nothing is written, in the pin folder or two above it.
#[test]
fn an_id_that_is_a_path_writes_no_pin() {
    use stepladder::internals::accuracy::pin::check_pin_with;
    use stepladder::scheme::{BlackBox, SchemeMeta};
    let root = std::env::temp_dir().join(format!("stepladder-escape-{}", std::process::id()));
    let pins = root.join("a/b/snapshots/stepladder");
    std::fs::create_dir_all(&pins).unwrap();
    for id in [
        "../../escaped-pin",
        "a/b",
        "Upper",
        "two--hyphens",
        "-lead",
        "",
        "dot.pin",
    ] {
        let scheme = BlackBox::new(SchemeMeta::new(id, "velocity Verlet", 2), velocity_verlet);
        let e = check_pin_with(&scheme, &Harmonic::default(), &pins, true, false).unwrap_err();
        assert!(
            e.contains("is invalid: expected plain kebab-case"),
            "{id}: {e}"
        );
    }
    let written: Vec<_> = walk(&root);
    assert!(written.is_empty(), "written: {written:?}");
    // the same scheme under a kebab-case id writes its pin in the folder
    let scheme = BlackBox::new(
        SchemeMeta::new("escaped-pin", "velocity Verlet", 2)
            .symplectic()
            .symmetric(),
        velocity_verlet,
    );
    check_pin_with(&scheme, &Harmonic::default(), &pins, true, false).unwrap();
    assert_eq!(walk(&root), [pins.join("escaped-pin__harmonic.pin")]);
    std::fs::remove_dir_all(&root).unwrap();
}

/// Every file under `dir`.
fn walk(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(walk(&path));
        } else {
            files.push(path);
        }
    }
    files
}

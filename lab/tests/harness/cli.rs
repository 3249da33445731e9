//! The command line: JSON shapes, exit statuses, and a clear one-line error
//! for every kind of bad input, with nothing written.

use serde_json::Value;
use std::process::{Command, Output};

/// Runs the command line with `args`.
pub fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stepladder"))
        .args(args)
        .output()
        .unwrap()
}

/// The JSON a successful run prints.
pub fn json(args: &[&str]) -> Value {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Bad input: exit status 2, nothing on stdout, one line on stderr that
/// contains `needle`.
pub fn refused(args: &[&str], needle: &str) {
    let out = run(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?} printed to stdout");
    assert!(err.contains(needle), "{args:?}: {err:?} lacks {needle:?}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "{args:?}: not one line: {err}"
    );
}

#[test]
fn list_json_has_schemes_and_scenes() {
    let v = json(&["list", "--json"]);
    let schemes = v["schemes"].as_array().unwrap();
    assert!(schemes.len() >= 6);
    for s in schemes {
        assert!(s["id"].is_string() && s["order"].is_u64());
        assert!(s["symplectic"].is_boolean() && s["symmetric"].is_boolean());
    }
    let ids: Vec<&str> = v["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["id"].as_str().unwrap())
        .collect();
    assert!(ids.contains(&"harmonic") && ids.contains(&"kepler-circular"));
}

#[test]
fn order_json_has_the_record() {
    let v = json(&[
        "order",
        "--scheme",
        "velocity-verlet",
        "--scene",
        "kepler-circular",
        "--json",
    ]);
    assert_eq!(v["scheme"], "velocity-verlet");
    assert_eq!(v["scene"], "kepler-circular");
    assert_eq!(v["theoretical_order"], 2);
    assert_eq!(v["verdict"], "pass");
    let p = v["measured_order"].as_f64().unwrap();
    let ci: Vec<f64> = v["ci95"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(ci.len() == 2 && ci[0] <= p && p <= ci[1]);
    for r in v["rungs"].as_array().unwrap() {
        for key in ["h", "steps", "error", "final_error", "local_order", "used"] {
            assert!(r.get(key).is_some(), "rung lacks {key}");
        }
    }
}

#[test]
fn geometry_studies_have_their_json_fields() {
    let e = json(&[
        "energy",
        "--scheme",
        "euler",
        "--scene",
        "harmonic",
        "--periods",
        "50",
        "--json",
    ]);
    assert!(e["max_relative_energy_error"].as_f64().unwrap() > 0.0);
    assert!(e["growth_exponent"].as_f64().unwrap() > 0.75);
    assert_eq!(e["class"], "drifting");
    assert_eq!(e["verdict"], "pass");
    let s = json(&[
        "symplectic",
        "--scheme",
        "leapfrog",
        "--scene",
        "kepler-circular",
        "--h",
        "0.01",
        "--json",
    ]);
    assert!(s["det_minus_one"].as_f64().unwrap().abs() < 1e-12);
    assert!(s["symplectic_residual"].as_f64().unwrap() < 1e-12);
    let r = json(&[
        "reverse",
        "--scheme",
        "euler-cromer",
        "--scene",
        "harmonic",
        "--steps",
        "100",
        "--json",
    ]);
    assert!(r["return_error"].as_f64().unwrap() > 1e-6);
    assert_eq!(r["measured"], false);
}

#[test]
fn stability_json_and_scene_parameters() {
    let v = json(&["stability", "--scheme", "leapfrog", "--json"]);
    assert!((v["stability_limit"].as_f64().unwrap() - 2.0).abs() < 1e-9);
    assert_eq!(v["stable_intervals"].as_array().unwrap().len(), 1);
    let v = json(&["stability", "--scheme", "euler", "--json"]);
    assert_eq!(v["stability_limit"], 0.0);
    // a stiff oscillator above the limit: the run stops early and says so
    let out = run(&[
        "energy",
        "--scheme",
        "velocity-verlet",
        "--scene",
        "harmonic:w0=50",
        "--h",
        "0.05",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("h = 0.05") && text.contains("unstable"),
        "{text}"
    );
}

#[test]
fn fixed_ladder_from_the_command_line() {
    let v = json(&[
        "order",
        "--scheme",
        "euler-cromer",
        "--scene",
        "harmonic",
        "--h0",
        "0.05",
        "--levels",
        "8",
        "--ratio",
        "0.5",
        "--t-end",
        "7.3",
        "--json",
    ]);
    let rungs = v["rungs"].as_array().unwrap();
    assert_eq!(rungs.len(), 8);
    assert_eq!(rungs[0]["steps"], 146);
    assert_eq!(v["t_end"], 7.3);
}

#[test]
fn a_verdict_that_is_not_a_pass_exits_with_status_1() {
    // six rungs from a step of a sixth of the period, refining by 0.9, all
    // leave Euler's error above the ceiling: the data cannot decide, and
    // the command says what to change
    let out = run(&[
        "order", "--scheme", "euler", "--scene", "harmonic", "--h0", "1", "--levels", "6",
        "--ratio", "0.9",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("INCONCLUSIVE"), "{text}");
    assert!(text.contains("to decide: "), "{text}");
}

/// An unwritable path is refused before the suite runs (at once, not after
/// a minute of work), with exit status 2 and nothing written or printed.
/// `h w0 = 7` is past leap-frog's stability limit 2: the run stops at its
/// fourth step, and the line says why, with no growth law of three steps
/// and no drift blamed.
#[test]
fn a_step_past_the_stability_limit_is_said_to_be_so() {
    let out = run(&[
        "energy", "--scheme", "leapfrog", "--scene", "harmonic", "--h", "7",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{text}");
    for needle in [
        "INCONCLUSIVE",
        "h = 7, 3 steps",
        "g = -,",
        "at step 4",
        "h w = 7.00 is past the scheme's linear stability limit h w = 2.00",
    ] {
        assert!(text.contains(needle), "{needle:?} not in {text}");
    }
    assert!(!text.contains("drift"), "{text}");
}

#[test]
fn report_refuses_an_unwritable_path_at_once() {
    let missing = std::env::temp_dir().join(format!(
        "stepladder-cli-missing-{}/no/such/dir/R.md",
        std::process::id()
    ));
    let out = run(&["report", "--output", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!missing.exists());
    // no verdict was printed: the suite never ran
    assert!(String::from_utf8_lossy(&out.stdout).is_empty());
}

/// Every accuracy record is a pure function of its inputs: two runs of each
/// `--json` study print the very same bytes.
#[test]
fn json_records_are_identical_across_runs() {
    let studies: [&[&str]; 5] = [
        &[
            "order",
            "--scheme",
            "pefrl",
            "--scene",
            "kepler-eccentric",
            "--json",
        ],
        &[
            "energy",
            "--scheme",
            "rk4",
            "--scene",
            "anharmonic",
            "--periods",
            "100",
            "--json",
        ],
        &[
            "symplectic",
            "--scheme",
            "kahan-li8",
            "--scene",
            "kepler-circular",
            "--json",
        ],
        &[
            "reverse",
            "--scheme",
            "stormer-verlet",
            "--scene",
            "kepler-eccentric",
            "--json",
        ],
        &["stability", "--scheme", "yoshida6", "--json"],
    ];
    for args in studies {
        let (a, b) = (run(args), run(args));
        assert!(a.status.success(), "{args:?}");
        assert!(a.stdout == b.stdout, "{args:?} printed different records");
    }
}

#[test]
fn speed_json_has_every_scheme_against_the_floor() {
    let v = json(&["speed", "--json", "--repeats", "1", "--steps", "200"]);
    assert_eq!(v["scene"], "kepler-circular");
    assert_eq!(v["steps"], 200);
    assert!(v["floor_ns_per_step"].as_f64().unwrap() > 0.0);
    let ids: Vec<&str> = v["schemes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            assert!(s["ns_per_step"].as_f64().unwrap() > 0.0, "{s}");
            assert!(s["ratio_to_floor"].as_f64().unwrap() > 0.0, "{s}");
            assert!(s["ratio_per_evaluation"].as_f64().unwrap() > 0.0, "{s}");
            assert!(
                s["force_evaluations_per_step"].as_f64().unwrap() >= 1.0,
                "{s}"
            );
            s["id"].as_str().unwrap()
        })
        .collect();
    assert_eq!(ids, stepladder::scheme::scheme_ids());
    let text = run(&["speed", "--repeats", "1", "--steps", "100"]);
    assert!(text.status.success());
    assert!(String::from_utf8_lossy(&text.stdout).contains("velocity-verlet"));
}

#[test]
fn work_json_has_targets_schemes_peer_and_timings() {
    let v = json(&["work", "--scene", "harmonic", "--json"]);
    assert_eq!(v["scene"], "harmonic");
    let targets: Vec<f64> = v["targets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_f64().unwrap())
        .collect();
    assert_eq!(targets, stepladder::internals::cost::work_points::TARGETS);
    let schemes = v["schemes"].as_array().unwrap();
    assert_eq!(schemes.len(), stepladder::scheme::scheme_ids().len());
    let kinds = ["interpolated", "at-most", "not-reached"];
    for s in schemes {
        for key in ["global_targets", "energy_targets"] {
            let t = s[key].as_array().unwrap();
            assert_eq!(t.len(), targets.len(), "{key}");
            for c in t {
                assert!(kinds.contains(&c["reach"]["kind"].as_str().unwrap()), "{c}");
            }
        }
        for p in s["global"].as_array().unwrap() {
            assert!(p["evaluations"].as_u64().unwrap() >= p["steps"].as_u64().unwrap());
        }
    }
    let peers: Vec<&str> = v["peers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            assert!(!p["global"].as_array().unwrap().is_empty(), "{p}");
            p["peer"].as_str().unwrap()
        })
        .collect();
    assert_eq!(peers, stepladder_lab::peer::peer_names());
    for key in ["cheapest_global", "cheapest_energy"] {
        assert_eq!(v[key].as_array().unwrap().len(), targets.len());
    }
    let timing = &v["timing"];
    assert_eq!(timing["schemes"].as_array().unwrap().len(), schemes.len());
    assert_eq!(
        timing["fastest_global"].as_array().unwrap().len(),
        targets.len()
    );
}

#[test]
fn speed_and_work_refuse_bad_input() {
    refused(
        &["work", "--scene", "mars"],
        "valid scenes: harmonic, kepler-circular",
    );
    refused(&["work", "--scene", "harmonic:w0=0"], "w0 = 0 is invalid");
    refused(&["work", "--scene", "harmonic:spring=2"], "its parameters");
    refused(&["work"], "--scene");
    refused(
        &["work", "--scene", "harmonic", "--threads", "0"],
        "threads = 0 is invalid",
    );
    refused(&["speed", "--repeats", "0"], "repeats = 0 is invalid");
    refused(&["speed", "--steps", "0"], "steps = 0 is invalid");
    refused(&["speed", "--steps", "-5"], "'-5'");
    refused(&["speed", "--steps", "100000000000"], "refusing a run of");
}

/// A ladder of billions of rungs is refused on one line, never allocated
/// (it used to abort the process asking for 32 GB), and the energy tables
/// of `eccentric` show the eccentricities asked for, not the defaults.
#[test]
fn huge_ladders_are_refused_and_asked_eccentricities_are_shown() {
    for levels in ["2000000000", "18446744073709551615"] {
        refused(
            &[
                "order", "--scheme", "rk4", "--scene", "harmonic", "--levels", levels,
            ],
            "refusing a run of more than",
        );
    }
    let out = run(&[
        "eccentric",
        "--scheme",
        "velocity-verlet",
        "--max-rung-steps",
        "4096",
        "--e",
        "0.7",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("| scheme | e = 0.7 |"), "{text}");
    assert!(!text.contains("e = 0.99"), "{text}");
}

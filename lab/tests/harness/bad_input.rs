//! Bad input, case by case: the library returns a typed error (or a measured
//! outcome where the input is legitimate but the run fails), and the command
//! line turns it into one line on stderr and exit status 2, with nothing on
//! stdout and nothing written.

use super::cli::refused;
use nalgebra::Vector2;
use stepladder::error::Error;
use stepladder::internals::accuracy::order::{DropReason, OrderSpec, global_order};
use stepladder::internals::geometry::energy::{EnergySpec, energy_drift};
use stepladder::internals::geometry::reverse::{ReverseSpec, reversibility};
use stepladder::internals::geometry::symplectic::{SymplecticSpec, symplecticity};
use stepladder::internals::ladder::{Ladder, LadderChoice};
use stepladder::internals::run::{Outcome, integrate};
use stepladder::scene::{AnyScene, Harmonic, KeplerCircular, KeplerEccentric};
use stepladder::scheme::{ImplicitMidpoint, VELOCITY_VERLET};
use stepladder::state::State;

const BAD_NUMBERS: [f64; 5] = [0.0, -0.1, f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

fn order_with(extra: &[&'static str]) -> Vec<&'static str> {
    let mut a = vec![
        "order",
        "--scheme",
        "velocity-verlet",
        "--scene",
        "harmonic",
    ];
    a.extend_from_slice(extra);
    a
}

#[test]
fn step_sizes_must_be_finite_and_positive() {
    let osc = Harmonic::default();
    for h in BAD_NUMBERS {
        assert!(matches!(
            Ladder::new(h, 0.5, 8),
            Err(Error::InvalidParameter { name: "h0", .. })
        ));
        let e = energy_drift(
            &VELOCITY_VERLET,
            &osc,
            &EnergySpec {
                h: Some(h),
                periods: None,
            },
        );
        assert!(
            matches!(e, Err(Error::InvalidParameter { name: "h", .. })),
            "{h}"
        );
        let r = reversibility(
            &VELOCITY_VERLET,
            &osc,
            &ReverseSpec {
                h: Some(h),
                steps: None,
            },
        );
        assert!(
            matches!(r, Err(Error::InvalidParameter { name: "h", .. })),
            "{h}"
        );
        let s = symplecticity(&VELOCITY_VERLET, &osc, &SymplecticSpec { h: Some(h) });
        assert!(
            matches!(s, Err(Error::InvalidParameter { name: "h", .. })),
            "{h}"
        );
    }
    refused(&order_with(&["--h0", "-0.1"]), "h0 = -0.1 is invalid");
    refused(&order_with(&["--h0", "0"]), "h0 = 0 is invalid");
    refused(&order_with(&["--h0", "nan"]), "h0 = NaN is invalid");
    refused(&order_with(&["--h0", "abc"]), "invalid value 'abc'");
    refused(
        &[
            "energy", "--scheme", "euler", "--scene", "harmonic", "--h", "-1",
        ],
        "h = -1 is invalid",
    );
    refused(
        &[
            "symplectic",
            "--scheme",
            "euler",
            "--scene",
            "harmonic",
            "--h",
            "nan",
        ],
        "h = NaN is invalid",
    );
    refused(
        &[
            "reverse", "--scheme", "euler", "--scene", "harmonic", "--h", "inf",
        ],
        "h = inf is invalid",
    );
}

#[test]
fn end_times_and_run_lengths_must_be_finite_and_positive() {
    let osc = Harmonic::default();
    for t in BAD_NUMBERS {
        let spec = OrderSpec {
            t_end: Some(t),
            ..OrderSpec::default()
        };
        assert!(matches!(
            global_order(&VELOCITY_VERLET, &osc, &spec),
            Err(Error::InvalidParameter { name: "t_end", .. })
        ));
        let e = energy_drift(
            &VELOCITY_VERLET,
            &osc,
            &EnergySpec {
                h: None,
                periods: Some(t),
            },
        );
        assert!(
            matches!(
                e,
                Err(Error::InvalidParameter {
                    name: "periods",
                    ..
                })
            ),
            "{t}"
        );
    }
    let r = reversibility(
        &VELOCITY_VERLET,
        &osc,
        &ReverseSpec {
            h: None,
            steps: Some(0),
        },
    );
    assert!(matches!(
        r,
        Err(Error::InvalidParameter { name: "steps", .. })
    ));
    refused(&order_with(&["--t-end", "inf"]), "t_end = inf is invalid");
    refused(&order_with(&["--t-end", "-2"]), "t_end = -2 is invalid");
    refused(
        &[
            "energy",
            "--scheme",
            "euler",
            "--scene",
            "harmonic",
            "--periods",
            "0",
        ],
        "periods = 0 is invalid",
    );
    refused(
        &[
            "reverse", "--scheme", "euler", "--scene", "harmonic", "--steps", "0",
        ],
        "steps = 0 is invalid",
    );
}

#[test]
fn frequencies_must_be_finite_and_positive() {
    for w in BAD_NUMBERS {
        assert!(
            matches!(
                Harmonic::new(w, 1.0, 0.0),
                Err(Error::InvalidParameter { name: "w0", .. })
            ),
            "{w}"
        );
    }
    refused(
        &["order", "--scheme", "euler", "--scene", "harmonic:w0=0"],
        "w0 = 0 is invalid",
    );
    refused(
        &["order", "--scheme", "euler", "--scene", "harmonic:w0=-3"],
        "w0 = -3 is invalid",
    );
    refused(
        &["order", "--scheme", "euler", "--scene", "harmonic:w0=nan"],
        "w0 = NaN is invalid",
    );
}

#[test]
fn eccentricities_must_lie_in_zero_to_one() {
    for e in [-0.1, 1.0, 1.5, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(
                KeplerEccentric::new(e),
                Err(Error::InvalidParameter { name: "e", .. })
            ),
            "{e}"
        );
    }
    refused(
        &[
            "order",
            "--scheme",
            "euler",
            "--scene",
            "kepler-eccentric:e=1",
        ],
        "e = 1 is invalid",
    );
    refused(
        &[
            "order",
            "--scheme",
            "euler",
            "--scene",
            "kepler-eccentric:e=-0.2",
        ],
        "e = -0.2 is invalid",
    );
}

/// At the origin the Kepler force is infinite: a run started there must
/// end at once as unstable, not panic or return NaNs as results.
#[test]
fn a_kepler_state_at_the_origin_ends_the_run_as_unstable() {
    let at_origin = State::new(Vector2::new(0.0, 0.0), Vector2::new(0.0, 1.0));
    let mut observed = 0;
    let outcome = integrate(
        &VELOCITY_VERLET,
        &KeplerCircular,
        &at_origin,
        0.01,
        100,
        |_, _, s| {
            assert!(s.is_finite(), "a non-finite state was handed out: {s:?}");
            observed += 1;
        },
    );
    assert!(
        matches!(outcome, Outcome::Unstable { step: 1, .. }),
        "{outcome:?}"
    );
    assert_eq!(observed, 1, "only the start is observed");
}

#[test]
fn ladders_need_enough_rungs_to_fit() {
    for levels in 0..6 {
        assert!(matches!(
            Ladder::new(0.1, 0.5, levels),
            Err(Error::InvalidLadder(_))
        ));
    }
    assert!(Ladder::new(0.1, 0.5, 6).is_ok());
    refused(
        &order_with(&["--levels", "2"]),
        "2 rungs cannot measure an order",
    );
    refused(&order_with(&["--ratio", "1.5"]), "ratio = 1.5 is invalid");
}

#[test]
fn runs_too_long_to_finish_are_refused_with_an_estimate() {
    let osc = Harmonic::default();
    let e = energy_drift(
        &VELOCITY_VERLET,
        &osc,
        &EnergySpec {
            h: Some(1e-12),
            periods: None,
        },
    );
    let Err(Error::TooExpensive { steps, seconds, .. }) = e else {
        panic!("{e:?}")
    };
    assert!(steps > 1e16 && seconds > 1e8, "{steps} steps, {seconds} s");
    let r = reversibility(
        &VELOCITY_VERLET,
        &osc,
        &ReverseSpec {
            h: None,
            steps: Some(u64::MAX / 2),
        },
    );
    assert!(matches!(r, Err(Error::TooExpensive { .. })));
    refused(
        &order_with(&["--h0", "1e-9", "--levels", "8"]),
        "refusing a run of",
    );
    refused(
        &[
            "energy", "--scheme", "euler", "--scene", "harmonic", "--h", "1e-12",
        ],
        "refusing a run of",
    );
}

/// Velocity Verlet on a stiff oscillator (`w0 = 50`): the coarse rungs have
/// `h w0 > 2` and blow up mid-ladder; they are measured outcomes, dropped
/// with their reason, and the order still comes from the stable rungs.
#[test]
fn a_scheme_blowing_up_mid_ladder_is_a_measured_outcome() {
    let stiff = Harmonic::new(50.0, 1.0, 0.0).unwrap();
    let spec = OrderSpec {
        t_end: Some(10.0),
        ladder: LadderChoice::Fixed(Ladder::new(0.06, 0.5, 14).unwrap()),
    };
    let r = global_order(&VELOCITY_VERLET, &stiff, &spec).unwrap();
    assert!(matches!(r.rungs[0].outcome, Outcome::Unstable { .. }));
    assert_eq!(r.rungs[0].dropped, Some(DropReason::Unstable));
    assert!(r.passed(), "{}", r.reason);
}

/// A step through the Sun cannot be solved by the implicit midpoint rule:
/// the rung ends as a failed step, is dropped, and the finer rungs still
/// measure the order.
#[test]
fn an_implicit_solve_that_does_not_converge_is_a_measured_outcome() {
    let spec = OrderSpec {
        t_end: None,
        ladder: LadderChoice::Fixed(Ladder::new(0.5, 0.5, 16).unwrap()),
    };
    let r = global_order(&ImplicitMidpoint, &KeplerCircular, &spec).unwrap();
    let Outcome::Failed { failure, .. } = &r.rungs[0].outcome else {
        panic!("{:?}", r.rungs[0].outcome)
    };
    assert!(
        failure.to_string().contains("did not converge"),
        "{failure}"
    );
    assert_eq!(r.rungs[0].dropped, Some(DropReason::Unstable));
    assert!(r.passed(), "{}", r.reason);
}

#[test]
fn unknown_ids_list_the_valid_ones() {
    assert!(matches!(
        AnyScene::parse("mars"),
        Err(Error::UnknownScene { .. })
    ));
    assert!(matches!(
        AnyScene::parse("harmonic:spring=2"),
        Err(Error::InvalidScene(_))
    ));
    refused(
        &["order", "--scheme", "rk9", "--scene", "harmonic"],
        "valid schemes: euler, euler-cromer",
    );
    refused(
        &["order", "--scheme", "euler", "--scene", "mars"],
        "valid scenes: harmonic, kepler-circular",
    );
    refused(
        &["order", "--scheme", "euler", "--scene", "harmonic:spring=2"],
        "its parameters: w0, x0, v0",
    );
    refused(
        &["order", "--scheme", "euler", "--scene", "harmonic:w0"],
        "expected name=number",
    );
    refused(
        &[
            "order",
            "--scheme",
            "euler",
            "--scene",
            "harmonic:w0=2,w0=3",
        ],
        "'w0' is given twice",
    );
    refused(
        &[
            "order",
            "--scheme",
            "euler",
            "--scene",
            "harmonic:w0=2,,x0=3",
        ],
        "has an empty item",
    );
    refused(
        &["order", "--scheme", "euler", "--scene", "harmonic:w0=2,"],
        "has an empty item",
    );
    refused(&["stability", "--scheme", "rk9"], "valid schemes");
    refused(&["order", "--scene", "harmonic"], "--scheme");
    refused(&["frobnicate"], "unrecognized subcommand");
    refused(&["report", "--threads", "0"], "threads = 0 is invalid");
    refused(&["corpus", "--threads", "0"], "threads = 0 is invalid");
}

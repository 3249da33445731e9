//! Compensated summation and round-off: the compensated variants keep their
//! twins' claims, lower their floors by what theory says they must, and the
//! round-off of long runs grows by the law derived for it.

use super::cli::{json, refused, run};
use stepladder::guard::assert_claims;
use stepladder::internals::compensated::{PairVisitor, paired_ids, visit_pair};
use stepladder::internals::round_off::floor::{PairRecord, RoundoffRecord};
use stepladder::internals::tolerance::{
    COMPENSATED_LONGRUN_GAIN, RANDOM_WALK_EXPONENT_TOLERANCE, ROUND_OFF_EXPONENT_TOLERANCE,
    TWO_STEP_FLOOR_RATIO, reverse_tolerance_ulps,
};
use stepladder::scene::{Harmonic, KeplerCircular, Scene};
use stepladder::scheme::{STORMER_VERLET_COMPENSATED, Scheme, StormerVerlet};

/// Every claim of a compensated variant, on the oscillator and the orbit:
/// order, energy, symplecticity, time symmetry (the public guards, which
/// panic listing every claim that failed).
struct Claims;
impl PairVisitor for Claims {
    type Output = ();
    fn visit<P: Scheme + Sync + 'static, C: Scheme + Sync + 'static>(
        self,
        _: &'static P,
        c: &'static C,
    ) {
        assert_claims(c, &Harmonic::default());
        assert_claims(c, &KeplerCircular);
    }
}

#[test]
fn compensated_variants_keep_every_claim_of_their_twins() {
    for id in paired_ids() {
        visit_pair(id, Claims).unwrap();
    }
}

/// The same map in exact arithmetic: run side by side, a variant and its
/// twin differ by round-off only, within the bound a symmetric scheme's
/// round trip is allowed (16 units of `eps * scale` a step); and both start
/// from the state they are given.
struct SameMap;
impl PairVisitor for SameMap {
    type Output = ();
    fn visit<P: Scheme + Sync + 'static, C: Scheme + Sync + 'static>(
        self,
        p: &'static P,
        c: &'static C,
    ) {
        let scene = KeplerCircular;
        let s0 = scene.initial();
        let h = 0.01;
        let (mut a, mut b) = (p.start(&scene, &s0, h), c.start(&scene, &s0, h));
        assert!(scene.phase_distance(&c.state(&b, h), &s0) < 1e-13);
        let steps = 1000;
        let mut worst = 0.0f64;
        for _ in 0..steps {
            p.step(&scene, &mut a, h).unwrap();
            c.step(&scene, &mut b, h).unwrap();
            worst = worst.max(scene.phase_distance(&p.state(&a, h), &c.state(&b, h)));
        }
        let bound = reverse_tolerance_ulps(steps, 1.0) * f64::EPSILON * scene.scale();
        assert!(
            worst <= bound,
            "{} and {} part by {worst:e} > {bound:e}",
            p.meta().id,
            c.meta().id
        );
    }
}

#[test]
fn compensated_variants_are_their_twins_up_to_round_off() {
    for id in paired_ids() {
        visit_pair(id, SameMap).unwrap();
    }
}

/// On a dyadic oscillator (`w0 = 1, x0 = 1`, `h = 1/8`) the first steps of
/// the two-step form are exact in binary: its compensated variant must give
/// the same bits, and carry nothing in its low parts.
#[test]
fn where_nothing_is_rounded_the_two_step_forms_agree_bit_for_bit() {
    let osc = Harmonic::default();
    let h = 0.125;
    let mut a = StormerVerlet.start(&osc, &osc.initial(), h);
    let mut b = STORMER_VERLET_COMPENSATED.start(&osc, &osc.initial(), h);
    for _ in 0..4 {
        StormerVerlet.step(&osc, &mut a, h).unwrap();
        STORMER_VERLET_COMPENSATED.step(&osc, &mut b, h).unwrap();
        assert_eq!(a.current, b.current.value);
        assert_eq!(b.current.low[0], 0.0);
        assert_eq!(
            StormerVerlet.state(&a, h),
            STORMER_VERLET_COMPENSATED.state(&b, h)
        );
    }
}

fn floors(scene: &str) -> &'static RoundoffRecord {
    super::common::suite()
        .roundoff
        .floors
        .iter()
        .find(|r| r.scene == scene)
        .expect("the report studies this scene")
}

fn pair<'a>(r: &'a RoundoffRecord, plain: &str) -> &'a PairRecord {
    r.pairs
        .iter()
        .find(|p| p.plain == plain)
        .expect("every pair")
}

/// Where a plain scheme stops improving, at `h_f`, its error is at least its
/// truncation error `C h_f^2`, up to the part of it that round-off, random in
/// direction, cancels (at worst half, for a truncation error that grows
/// steadily along the run). The ladder runs on for `j` more halvings (two,
/// unless the finest step allowed comes first), where the compensated
/// variant's error is its truncation error `C (h_f / 2^j)^2`, its own
/// round-off being `h w` times smaller. So its floor is lower by at least
/// `4^j / 2`: 8 when the ladder has run two rungs past the plain floor.
#[test]
fn compensated_summation_lowers_the_floor_by_the_derived_factor() {
    let mut checked = 0;
    for r in &super::common::suite().roundoff.floors {
        for p in &r.pairs {
            let (Some(plain), Some(comp)) = (&p.plain_floor, &p.compensated_floor) else {
                panic!("{} on {}: no floors", p.plain, r.scene);
            };
            if !plain.stopped {
                continue;
            }
            let at = p.rungs.iter().position(|g| g.h == plain.h).unwrap();
            let past = (p.rungs.len() - 1 - at) as i32;
            let factor = 4f64.powi(past) / 2.0;
            assert!(
                plain.floor >= factor * comp.floor,
                "{} on {}: floor {:e} vs compensated {:e}, expected a factor {factor}",
                p.plain,
                r.scene,
                plain.floor,
                comp.floor
            );
            checked += 1;
        }
    }
    // the two-step form stops improving on both scenes, leap-frog on the oscillator
    assert!(checked >= 3, "only {checked} plain floors reached");
}

#[test]
fn the_two_step_floor_lies_far_above_velocity_verlets() {
    let r = floors("harmonic");
    let (sv, vv) = (pair(r, "stormer-verlet"), pair(r, "velocity-verlet"));
    let sv_floor = sv.plain_floor.as_ref().unwrap();
    let vv_floor = vv.plain_floor.as_ref().unwrap();
    assert!(sv_floor.stopped, "the two-step form reaches its floor");
    // velocity Verlet's smallest error is its floor or above it
    assert!(
        sv_floor.floor >= TWO_STEP_FLOOR_RATIO * vv_floor.floor,
        "{:e} vs {:e}",
        sv_floor.floor,
        vv_floor.floor
    );
    // and its round-off overtakes truncation at a coarser step
    assert!(sv.crossover_h.unwrap() > vv.crossover_h.unwrap_or(0.0));
}

#[test]
fn round_off_grows_with_the_derived_power_of_the_step() {
    for r in &super::common::suite().roundoff.floors {
        for p in &r.pairs {
            let g = -p.round_off_fit.expect("enough rungs to fit").slope;
            let theory = if p.plain == "stormer-verlet" {
                1.5
            } else {
                0.5
            };
            assert!(
                (g - theory).abs() <= ROUND_OFF_EXPONENT_TOLERANCE,
                "{} on {}: round-off ~ h^-{g}, theory h^-{theory}",
                p.plain,
                r.scene
            );
        }
    }
}

/// Velocity Verlet's modified energy on the oscillator is conserved exactly
/// in exact arithmetic, and each step's rounding changes it by an unbiased
/// amount: a random walk, exponent 1/2. Compensated summation must not make
/// it worse: the same law at most, and a smaller change.
#[test]
fn long_runs_walk_randomly_and_compensation_does_not_make_it_worse() {
    let runs = &super::common::suite().roundoff.longrun;
    let find = |scheme: &str, scene: &str| {
        runs.iter()
            .find(|r| r.scheme == scheme && r.scene == scene)
            .unwrap_or_else(|| panic!("no long run of {scheme} on {scene}"))
    };
    let vv = find("velocity-verlet", "harmonic");
    let g = vv.growth_exponent.unwrap();
    assert!(
        (g - 0.5).abs() <= RANDOM_WALK_EXPONENT_TOLERANCE,
        "velocity Verlet's modified energy grows as t^{g}"
    );
    for scene in ["harmonic", "kepler-circular"] {
        for plain in paired_ids() {
            let p = find(plain, scene);
            let c = find(&format!("{plain}-compensated"), scene);
            assert!(
                c.final_rms * COMPENSATED_LONGRUN_GAIN <= p.final_rms,
                "{} on {scene}: {:e} vs plain {:e}",
                c.scheme,
                c.final_rms,
                p.final_rms
            );
            assert!(
                c.growth_exponent.unwrap() <= 0.5 + RANDOM_WALK_EXPONENT_TOLERANCE,
                "{} on {scene} grows as t^{:?}",
                c.scheme,
                c.growth_exponent
            );
        }
    }
}

#[test]
fn roundoff_and_longrun_on_the_command_line() {
    let v = json(&[
        "roundoff",
        "--scene",
        "harmonic",
        "--scheme",
        "stormer-verlet",
        "--max-steps",
        "1048576",
        "--json",
    ]);
    assert_eq!(v["scene"], "harmonic");
    let p = &v["pairs"][0];
    assert_eq!(p["plain"], "stormer-verlet");
    assert_eq!(p["compensated"], "stormer-verlet-compensated");
    for key in [
        "h",
        "steps",
        "plain_error",
        "compensated_error",
        "round_off",
    ] {
        assert!(p["rungs"][0].get(key).is_some(), "rung lacks {key}");
    }
    assert!(p["plain_floor"]["floor"].as_f64().unwrap() > 0.0);

    let v = json(&[
        "longrun",
        "--scheme",
        "velocity-verlet-compensated",
        "--steps",
        "20000",
        "--json",
    ]);
    assert_eq!(v[0]["scheme"], "velocity-verlet-compensated");
    assert_eq!(v[0]["compensated"], true);
    assert_eq!(v[0]["invariant"], "modified-energy");
    assert!(v[0]["growth_exponent"].is_f64());

    // a variant is a scheme like any other for the single-case studies
    let out = run(&[
        "order",
        "--scheme",
        "leapfrog-compensated",
        "--scene",
        "kepler-circular",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn bad_roundoff_and_longrun_requests_are_refused_in_one_line() {
    for (args, needle) in [
        (
            &["longrun", "--steps", "1000000000"][..],
            "refusing a run of",
        ),
        (&["longrun", "--steps", "10"][..], "steps = 10 is invalid"),
        (
            &["longrun", "--scheme", "rk4"][..],
            "valid schemes: stormer-verlet, leapfrog, velocity-verlet",
        ),
        (
            &["longrun", "--scene", "anharmonic"][..],
            "no quantity the Verlet forms conserve exactly",
        ),
        // a pericentre of e = 0.99 at a hundredth of the period: the orbit
        // is lost, and what the angular momentum does then is no round-off
        (
            &[
                "longrun",
                "--scene",
                "kepler-eccentric:e=0.99",
                "--scheme",
                "velocity-verlet",
                "--steps",
                "10000",
            ][..],
            "the step does not resolve the motion",
        ),
        (&["roundoff", "--scene", "mars"][..], "valid scenes"),
        (
            &["roundoff", "--periods", "-1"][..],
            "periods = -1 is invalid",
        ),
        (
            &["roundoff", "--max-steps", "100000000000"][..],
            "refusing a run of",
        ),
        (&["roundoff", "--scheme", "euler"][..], "valid schemes"),
    ] {
        refused(args, needle);
    }
}

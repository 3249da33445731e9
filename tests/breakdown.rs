//! Breakdowns the rule was not written around: steps that stop below some
//! step size (a NaN from an overflow guard, a velocity blown up by a power
//! of `1/h`, a refused step, a panic), in `f64` and `f32`, fixed and
//! adaptive, on scenes with and without an exact solution. Each must fail
//! the claim its run decides, say where (the step size and the step index),
//! and no other claim's message may advise a smaller step. Correct steps on
//! the same scenes, including ones that blow up at coarse steps, must not be
//! called broken.

use stepladder::prelude::*;
use stepladder::scene::{Anharmonic, Pleiades};
use stepladder::scheme::Advance;
use stepladder::scheme::{Euler, Leapfrog, VELOCITY_VERLET};
use stepladder::study::{
    AdaptiveClaim, DropReason, EnergySpec, OrderSpec, ReverseSpec, SymplecticSpec, energy_drift,
    evaluations, global_order, reversibility, symplecticity,
};

/// Velocity Verlet on slices, as a user's crate might write it, in `f64`
/// or `f32`.
fn velocity_verlet<T: Real>(q: &mut [T], v: &mut [T], h: T, force: &Force<T>) {
    let n = q.len();
    let half = h * T::of(0.5);
    let mut a = [T::of(0.0); 2];
    force(q, &mut a[..n]);
    for i in 0..n {
        v[i] += half * a[i];
        q[i] += h * v[i];
    }
    force(q, &mut a[..n]);
    for i in 0..n {
        v[i] += half * a[i];
    }
}

const VERLET: SchemeMeta = SchemeMeta::new("bb-verlet", "black-box Verlet", 2)
    .symplectic()
    .symmetric()
    .force_evaluations(2);

/// How a step breaks down below its threshold.
#[derive(Clone, Copy, Debug)]
enum Fault {
    /// An overflow guard that answers NaN.
    NaN,
    /// A factor `1 + (h*/h)^200`: finite, but far past any orbit.
    Overflow,
    /// An `assert!` on the step.
    Panic,
}

impl Fault {
    fn apply(self, v: &mut [f64], h: f64, threshold: f64) {
        if h.abs() >= threshold {
            return;
        }
        match self {
            Fault::NaN => v[0] = f64::NAN,
            Fault::Overflow => v[0] *= 1.0 + (threshold / h.abs()).powi(200),
            Fault::Panic => panic!("step {h} below the supported {threshold}"),
        }
    }
}

/// A step on `f64` slices, as the black-box adapter takes it.
trait Step: Fn(&mut [f64], &mut [f64], f64, &Force<f64>) + Sync {}
impl<F: Fn(&mut [f64], &mut [f64], f64, &Force<f64>) + Sync> Step for F {}

/// The step broken below `fraction` of the scene's period.
fn broken<S: Scene<D>, const D: usize>(
    scene: &S,
    fault: Fault,
    fraction: f64,
) -> BlackBox<f64, impl Step> {
    let threshold = fraction * scene.period();
    BlackBox::new(VERLET, move |q: &mut [f64], v: &mut [f64], h, force| {
        velocity_verlet(q, v, h, force);
        fault.apply(v, h, threshold);
    })
}

/// The order study fails on the breakdown, names where, and the guard's
/// message carries it.
fn fails_with_breakdown<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S, below: f64) {
    let r = global_order(scheme, scene, &OrderSpec::default()).unwrap();
    println!("{}: {}", scene.meta().id, r.reason);
    assert_eq!(
        r.verdict,
        Verdict::Fail,
        "{}: {}",
        scene.meta().id,
        r.reason
    );
    let b = r.breakdown.as_ref().expect("a breakdown is recorded");
    let h = b.outcome.h().unwrap();
    assert!(h < below, "stopped at h = {h}, above the threshold {below}");
    assert!(b.outcome.step().unwrap() >= 1);
    assert!(r.reason.starts_with("breakdown"), "{}", r.reason);
    assert!(r.reason.contains("h = "), "{}", r.reason);
    assert!(r.reason.contains("step "), "{}", r.reason);
    assert!(r.advice.is_none(), "{:?}", r.advice);
    // no rung finer than the clean one is set aside as mere instability
    let clean = b.clean_h.unwrap_or(f64::INFINITY);
    assert!(
        r.rungs
            .iter()
            .filter(|g| g.h < clean && !g.outcome.completed() && g.dropped.is_some())
            .all(|g| g.dropped != Some(DropReason::Unstable)),
        "{:?}",
        r.rungs
    );
}

#[test]
fn a_step_that_breaks_down_below_some_step_fails_its_order_on_every_scene() {
    let e6 = KeplerEccentric::default();
    let well = Anharmonic::default();
    for fault in [Fault::NaN, Fault::Overflow, Fault::Panic] {
        // the threshold sits inside every scene's default ladder, which
        // starts at periods/8 or so and runs to the round-off floor
        let fraction = 2e-3;
        fails_with_breakdown(
            &broken(&Harmonic::default(), fault, fraction),
            &Harmonic::default(),
            fraction * Harmonic::default().period(),
        );
        fails_with_breakdown(
            &broken(&KeplerCircular, fault, fraction),
            &KeplerCircular,
            fraction * KeplerCircular.period(),
        );
        fails_with_breakdown(&broken(&e6, fault, fraction), &e6, fraction * e6.period());
        // no exact solution: the half-step reference decides
        fails_with_breakdown(
            &broken(&well, fault, fraction),
            &well,
            fraction * well.period(),
        );
    }
}

#[test]
fn a_breakdown_in_single_precision_fails_too() {
    let scene = KeplerCircular;
    let threshold = 4e-3 * scene.period() as f32;
    let step = BlackBox::new(
        VERLET,
        move |q: &mut [f32], v: &mut [f32], h: f32, force: &Force<f32>| {
            velocity_verlet(q, v, h, force);
            if h.abs() < threshold {
                v[1] = f32::NAN;
            }
        },
    );
    fails_with_breakdown(&step, &scene, f64::from(threshold));
}

#[test]
fn a_step_refused_below_some_step_fails_its_order() {
    let scene = Harmonic::default();
    let threshold = 1e-3 * scene.period();
    let step = GuardedVerlet {
        threshold,
        refuse: true,
    };
    fails_with_breakdown(&step, &scene, threshold);
}

#[test]
fn every_other_claim_agrees_and_none_advises_a_smaller_step() {
    // broken below a quarter of the default steps of the geometric studies
    // (a hundredth of a period), so their default runs break at step 1
    let scene = Harmonic::default();
    for fault in [Fault::NaN, Fault::Panic] {
        let step = broken(&scene, fault, 0.04);
        let r = reversibility(&step, &scene, &ReverseSpec::default()).unwrap();
        println!("reverse: {}", r.reason);
        assert_eq!(r.verdict, Verdict::Fail, "{fault:?}: {}", r.reason);
        assert!(!r.reason.contains("smaller step"), "{}", r.reason);
        assert!(r.reason.contains("breakdown"), "{}", r.reason);
        let e = energy_drift(&step, &scene, &EnergySpec::default()).unwrap();
        println!("energy: {}", e.reason);
        assert_eq!(e.verdict, Verdict::Fail, "{fault:?}: {}", e.reason);
        assert!(!e.reason.contains("smaller"), "{}", e.reason);
        let c = evaluations(&step, &scene, 1e-4 * scene.period());
        assert_eq!(c.verdict, Verdict::Fail, "{fault:?}: {}", c.reason);
        assert!(c.reason.contains("breakdown"), "{}", c.reason);
        let s = symplecticity(
            &step,
            &scene,
            &SymplecticSpec {
                h: Some(0.01 * scene.period()),
            },
        )
        .unwrap();
        assert_eq!(s.verdict, Verdict::Fail, "{fault:?}: {}", s.reason);
        assert!(s.reason.contains("breakdown"), "{}", s.reason);
    }
}

#[test]
fn a_panic_fails_the_guard_with_scheme_scene_step_and_index() {
    let scene = KeplerCircular;
    let step = broken(&scene, Fault::Panic, 2e-3);
    let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        assert_order(&step, &scene);
    }));
    let payload = caught.expect_err("the guard fails");
    let message = payload
        .downcast_ref::<String>()
        .cloned()
        .unwrap_or_default();
    for needle in [
        "bb-verlet",
        "kepler-circular",
        "h = ",
        "step ",
        "below the supported",
    ] {
        assert!(message.contains(needle), "`{needle}` not in: {message}");
    }
}

#[test]
fn a_step_past_the_stability_limit_is_called_unstable_not_broken() {
    // leap-frog at h w = 7 on the oscillator: past its limit 2, and h/4 runs
    let scene = Harmonic::default();
    let e = energy_drift(
        &Leapfrog,
        &scene,
        &EnergySpec {
            h: Some(7.0 / scene.frequency()),
            periods: None,
        },
    )
    .unwrap();
    println!("energy at h w = 7: {}", e.reason);
    assert_eq!(e.verdict, Verdict::Inconclusive, "{}", e.reason);
    assert!(e.reason.contains("h w = 7"), "{}", e.reason);
    assert!(e.reason.contains("stability limit h w = 2"), "{}", e.reason);
    assert!(!e.reason.contains("breakdown"), "{}", e.reason);
}

#[test]
fn correct_steps_are_not_called_broken() {
    // velocity Verlet through the same adapter, and the catalogue's
    // explicit Euler, whose coarse runs on the eccentric orbit blow up
    let e9 = KeplerEccentric::new(0.9).unwrap();
    let verlet = BlackBox::new(VERLET, velocity_verlet::<f64>);
    for r in [
        global_order(&verlet, &e9, &OrderSpec::default()).unwrap(),
        global_order(&Euler, &e9, &OrderSpec::default()).unwrap(),
        global_order(&verlet, &Anharmonic::default(), &OrderSpec::default()).unwrap(),
    ] {
        assert!(r.breakdown.is_none(), "{}: {}", r.scheme, r.reason);
        assert_ne!(r.verdict, Verdict::Fail, "{}: {}", r.scheme, r.reason);
    }
}

/// A near-parabolic orbit, `e = 1 - 1e-7`: its pericentre, `1e-7` AU from
/// the Sun, passes in some `1e-11` of a year, and the force there turns at
/// `sqrt(2 GM / r_p^3) = 2.8e11` radians a year, so the finest step a
/// ladder reaches within its cap (about `2e-6`) takes some `5e5` radians of
/// it: correct schemes blow up on every rung, and the order study must say
/// that no rung resolves the motion, not blame them. The sign-flipped
/// Verlet blows up on every rung of an oscillator whose every rung
/// resolves it, and still fails.
#[test]
fn a_blow_up_on_every_rung_the_motion_is_not_resolved_on_blames_no_scheme() {
    let grazing = KeplerEccentric::new(1.0 - 1e-7).unwrap();
    let verlet = BlackBox::new(VERLET, velocity_verlet::<f64>);
    for r in [
        global_order(&verlet, &grazing, &OrderSpec::default()).unwrap(),
        global_order(&VELOCITY_VERLET, &grazing, &OrderSpec::default()).unwrap(),
    ] {
        println!("{}: {}", r.scheme, r.reason);
        assert_eq!(
            r.verdict,
            Verdict::Inconclusive,
            "{}: {}",
            r.scheme,
            r.reason
        );
        assert!(
            r.reason
                .contains("none resolves the motion's fastest time scale"),
            "{}: {}",
            r.scheme,
            r.reason
        );
    }
    let flipped = BlackBox::new(
        VERLET,
        |q: &mut [f64], v: &mut [f64], h, force: &Force<f64>| {
            let repelled = |q: &[f64], a: &mut [f64]| {
                force(q, a);
                a.iter_mut().for_each(|x| *x = -*x);
            };
            velocity_verlet(q, v, h, &repelled);
        },
    );
    let r = global_order(&flipped, &Harmonic::default(), &OrderSpec::default()).unwrap();
    assert_eq!(r.verdict, Verdict::Fail, "{}", r.reason);
    assert!(r.reason.contains("every rung blew up"), "{}", r.reason);
}

/// Adaptive RK4 by step doubling (see the adaptive black box's docs), with
/// a fault at tolerances below `tight`.
fn doubling(
    q: &mut [f64],
    v: &mut [f64],
    t1: f64,
    tol: f64,
    force: &Force<f64>,
    fault: Option<(Fault, f64)>,
) -> Advance {
    let n = q.len();
    let rk4 = |y: &mut [f64; 4], h: f64| {
        let f = |y: &[f64; 4]| {
            let mut d = [0.0; 4];
            d[..n].copy_from_slice(&y[n..2 * n]);
            force(&y[..n], &mut d[n..2 * n]);
            d
        };
        let at = |k: &[f64; 4], c: f64| std::array::from_fn(|i| y[i] + c * h * k[i]);
        let k1 = f(y);
        let k2 = f(&at(&k1, 0.5));
        let k3 = f(&at(&k2, 0.5));
        let k4 = f(&at(&k3, 1.0));
        for i in 0..2 * n {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    };
    let mut y = [0.0; 4];
    y[..n].copy_from_slice(q);
    y[n..2 * n].copy_from_slice(v);
    let (mut t, mut h, mut run) = (0.0, 1e-2f64, Advance::reached());
    while t < t1 {
        h = h.min(t1 - t);
        let (mut whole, mut halves) = (y, y);
        rk4(&mut whole, h);
        rk4(&mut halves, 0.5 * h);
        rk4(&mut halves, 0.5 * h);
        let scale = 1.0 + y.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let err = (0..2 * n).fold(0.0f64, |m, i| m.max((whole[i] - halves[i]).abs())) / scale;
        if err <= tol {
            (y, t) = (halves, t + h);
            run.accepted += 1;
        } else {
            run.rejected += 1;
        }
        h *= (0.9 * (tol / err.max(1e-300)).powf(0.2)).clamp(0.2, 5.0);
    }
    q.copy_from_slice(&y[..n]);
    v.copy_from_slice(&y[n..2 * n]);
    if let Some((fault, tight)) = fault
        && tol < tight
    {
        fault.apply(v, 0.0, 1.0);
    }
    run
}

#[test]
fn an_adaptive_run_that_breaks_down_at_tight_tolerances_fails_its_exponent() {
    for fault in [Fault::NaN, Fault::Panic] {
        let faulty = AdaptiveBlackBox::new(
            "rk4-doubling-faulty",
            AdaptiveClaims::pair(4, 4),
            move |q: &mut [f64], v: &mut [f64], _t0, t1, tol, force: &Force<f64>| {
                doubling(q, v, t1, tol, force, Some((fault, 1e-8)))
            },
        );
        let r = stepladder::guard::adaptive_ladder(&faulty, &KeplerCircular);
        assert_eq!(r.verdict, Verdict::Fail, "{fault:?}: {}", r.reason);
        let exponent = r.claim(AdaptiveClaim::Exponent).unwrap();
        assert_eq!(exponent.verdict, Verdict::Fail, "{}", exponent.reason);
        assert!(
            exponent.reason.starts_with("breakdown"),
            "{}",
            exponent.reason
        );
        assert!(
            exponent.reason.contains("TOL = 1e-9"),
            "{}",
            exponent.reason
        );
    }
    let sound = AdaptiveBlackBox::new(
        "rk4-doubling",
        AdaptiveClaims::pair(4, 4),
        |q: &mut [f64], v: &mut [f64], _t0, t1, tol, force: &Force<f64>| {
            doubling(q, v, t1, tol, force, None)
        },
    );
    let r = stepladder::guard::adaptive_ladder(&sound, &KeplerCircular);
    assert!(
        r.points.iter().all(|p| p.breakdown.is_none()),
        "{}",
        r.reason
    );
    assert_eq!(r.verdict, Verdict::Pass, "{}", r.reason);
}

/// Velocity Verlet written generically, broken below `threshold`: it
/// refuses the step (an implicit solve whose tolerance, relative to `h^2`,
/// cannot be met) or answers NaN (an overflow guard). The same defects in a
/// scheme the studies can differentiate, on a scene of any dimension.
struct GuardedVerlet {
    threshold: f64,
    refuse: bool,
}

impl OneStep for GuardedVerlet {
    fn meta(&self) -> &SchemeMeta {
        &VERLET
    }

    fn advance<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let below = h.abs() < R::of(self.threshold);
        if below && self.refuse {
            return Err(StepFailure::NotConverged {
                iterations: 50,
                residual: 1e-9,
            });
        }
        let half = R::of(0.5) * h;
        s.v += scene.acceleration(&s.q) * half;
        s.q += s.v * h;
        s.v += scene.acceleration(&s.q) * half;
        if below {
            s.v[D - 1] = R::of(f64::NAN);
        }
        Ok(())
    }
}

#[test]
fn a_breakdown_on_seven_bodies_fails_too() {
    // 14 coordinates, no exact solution, close encounters at coarse steps
    let stars = Pleiades::default();
    let threshold = 1e-3 * stars.period();
    let step = GuardedVerlet {
        threshold,
        refuse: false,
    };
    fails_with_breakdown(&step, &stars, threshold);
}

/// The clean coarser run a breakdown is set against is the first that
/// resolved the motion: broken below a hundredth of a period and run at
/// 0.006 periods, the energy run stops at step 1, every finer probe stops
/// too, and the probe's first coarser step, 0.012 periods, is past the fault
/// and resolves the oscillator (Verlet's relative energy error there is
/// about (h w)^2/8 = 7e-4, within the ceiling). A coarser step whose error
/// is above the ceiling would prove nothing, and the rule must not cite one.
#[test]
fn a_breakdown_cites_the_first_coarser_step_that_resolved_the_motion() {
    cites_the_first_resolving_coarser_step(&Harmonic::default());
}

/// Verlet broken below a hundredth of `scene`'s period and run at 0.006
/// periods: the breakdown cites 2h as its clean step, with an error within
/// the ceiling and below `(2 h w)^2`.
fn cites_the_first_resolving_coarser_step<S: Scene<1>>(scene: &S) {
    let step = broken(scene, Fault::NaN, 0.01);
    let h = 0.006 * scene.period();
    let spec = EnergySpec {
        h: Some(h),
        ..EnergySpec::default()
    };
    let e = energy_drift(&step, scene, &spec).unwrap();
    assert_eq!(e.verdict, Verdict::Fail, "{}", e.reason);
    let b = e.breakdown.expect("a breakdown, not instability");
    assert_eq!(b.clean_h, Some(2.0 * h), "{}", b.describe());
    let error = b.clean_error.expect("the clean run's error");
    let w_h = 2.0 * h * scene.frequency();
    assert!(
        error > 0.0
            && error <= stepladder::internals::tolerance::ERROR_CEILING
            && error < w_h * w_h,
        "clean error {error:e} at h w = {w_h}"
    );
}

/// The same fault on the oscillator in units a thousand times smaller: every
/// length is 1e3 times larger and the energy 1e6 times, E0 = 5e5. The clean
/// coarser run's energy error is about 350 in those units, 7e-4 of E0, and
/// it is that fraction the ceiling (0.3) judges: the probe still cites 2h
/// with an error below (h w)^2. An energy error read in the scene's units
/// would exceed the ceiling at every coarser step and leave the breakdown
/// unexplained.
#[test]
fn a_breakdown_judges_the_coarser_run_by_its_relative_energy_error() {
    use stepladder::scene::Scaled;
    let scene = Scaled::new(Harmonic::default(), 1e3);
    assert_eq!(scene.energy(&scene.initial()), 5e5);
    cites_the_first_resolving_coarser_step(&scene);
}

/// Where the symplecticity study calls a non-finite tangent map a defect:
/// at steps up to a tenth of a period, the coarsest of its default steps,
/// that one included, and not above it, where a force growing faster than
/// linearly can overflow in one step by itself. A step that answers NaN
/// every time fails at exactly a tenth and is left undecided at 0.15.
#[test]
fn a_non_finite_tangent_map_is_a_defect_up_to_a_tenth_of_a_period() {
    let scene = Harmonic::default();
    let nan = BlackBox::new(
        VERLET,
        |q: &mut [f64], v: &mut [f64], h, force: &Force<f64>| {
            velocity_verlet(q, v, h, force);
            v[0] = f64::NAN;
        },
    );
    let at = |fraction: f64| {
        symplecticity(
            &nan,
            &scene,
            &SymplecticSpec {
                h: Some(fraction * scene.period()),
            },
        )
        .unwrap()
    };
    let tenth = at(0.1);
    assert_eq!(tenth.verdict, Verdict::Fail, "{}", tenth.reason);
    assert!(tenth.reason.contains("breakdown"), "{}", tenth.reason);
    let coarser = at(0.15);
    assert_eq!(coarser.verdict, Verdict::Inconclusive, "{}", coarser.reason);
    assert!(!coarser.measured, "{}", coarser.reason);
}

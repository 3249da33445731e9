//! Black boxes the finite-difference tangent map was not designed around:
//! a highly eccentric orbit (e = 0.9, the map's derivatives large at the
//! pericentre), a non-symmetric symplectic map, and an implicit midpoint rule
//! whose fixed-point solve stops at a loose 1e-10, so its output carries
//! solver noise far above the round-off the error bound models. Correct
//! claims must pass, a false symplecticity claim must fail.

use stepladder::prelude::*;
use stepladder::scene::Anharmonic;
use stepladder::study::{
    OrderSpec, ReverseSpec, SymplecticSpec, evaluations, global_order, reversibility, symplecticity,
};

fn velocity_verlet(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
    let n = q.len();
    let mut a = [0.0; 2];
    force(q, &mut a[..n]);
    for i in 0..n {
        v[i] += 0.5 * h * a[i];
        q[i] += h * v[i];
    }
    force(q, &mut a[..n]);
    for i in 0..n {
        v[i] += 0.5 * h * a[i];
    }
}

fn euler_cromer(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
    let n = q.len();
    let mut a = [0.0; 2];
    force(q, &mut a[..n]);
    for i in 0..n {
        v[i] += h * a[i];
        q[i] += h * v[i];
    }
}

/// The implicit midpoint rule, its midpoint velocity found by fixed-point
/// iteration stopped once a sweep changes it by less than 1e-10.
fn loose_midpoint(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
    let n = q.len();
    let (mut q0, mut v0, mut mid, mut a, mut x) =
        ([0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2]);
    q0[..n].copy_from_slice(q);
    v0[..n].copy_from_slice(v);
    mid[..n].copy_from_slice(v);
    for _ in 0..200 {
        for i in 0..n {
            x[i] = q0[i] + 0.5 * h * mid[i];
        }
        force(&x[..n], &mut a[..n]);
        let mut change: f64 = 0.0;
        for i in 0..n {
            let next = v0[i] + 0.5 * h * a[i];
            change = change.max((next - mid[i]).abs());
            mid[i] = next;
        }
        if change < 1e-10 {
            break;
        }
    }
    for i in 0..n {
        q[i] = q0[i] + h * mid[i];
        v[i] = 2.0 * mid[i] - v0[i];
    }
}

fn rk4(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
    let n = q.len();
    let (mut kq, mut kv) = ([[0.0; 2]; 4], [[0.0; 2]; 4]);
    let (mut x, mut u) = ([0.0; 2], [0.0; 2]);
    x[..n].copy_from_slice(q);
    u[..n].copy_from_slice(v);
    for (stage, c) in [0.5, 0.5, 1.0, 1.0].into_iter().enumerate() {
        let mut a = [0.0; 2];
        force(&x[..n], &mut a[..n]);
        kq[stage] = u;
        kv[stage] = a;
        for i in 0..n {
            x[i] = q[i] + c * h * kq[stage][i];
            u[i] = v[i] + c * h * kv[stage][i];
        }
    }
    for i in 0..n {
        q[i] += h / 6.0 * (kq[0][i] + 2.0 * kq[1][i] + 2.0 * kq[2][i] + kq[3][i]);
        v[i] += h / 6.0 * (kv[0][i] + 2.0 * kv[1][i] + 2.0 * kv[2][i] + kv[3][i]);
    }
}

fn geometry<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S) -> (Verdict, Verdict) {
    let s = symplecticity(scheme, scene, &SymplecticSpec::default()).unwrap();
    let r = reversibility(scheme, scene, &ReverseSpec::default()).unwrap();
    (s.verdict, r.verdict)
}

#[test]
fn correct_claims_pass_on_scenes_the_bound_was_not_designed_around() {
    let e9 = KeplerEccentric::new(0.9).unwrap();
    let well = Anharmonic::default();
    let pass = (Verdict::Pass, Verdict::Pass);
    let verlet = BlackBox::new(
        SchemeMeta::new("bb-verlet", "bb-verlet", 2)
            .symplectic()
            .symmetric()
            .force_evaluations(2),
        velocity_verlet,
    );
    assert_eq!(geometry(&verlet, &e9), pass);
    let cromer = BlackBox::new(
        SchemeMeta::new("bb-euler-cromer", "bb-euler-cromer", 1).symplectic(),
        euler_cromer,
    );
    assert_eq!(geometry(&cromer, &e9), pass);
    assert_eq!(geometry(&cromer, &well), pass);
    let midpoint = BlackBox::new(
        SchemeMeta::new("bb-loose-midpoint", "bb-loose-midpoint", 2)
            .symplectic()
            .symmetric()
            .force_evaluations(2),
        loose_midpoint,
    );
    for verdicts in [
        geometry(&midpoint, &KeplerCircular),
        geometry(&midpoint, &well),
        geometry(&midpoint, &e9),
    ] {
        assert_eq!(verdicts, pass);
    }
}

#[test]
fn a_false_symplecticity_claim_fails_on_the_eccentric_orbit() {
    let e9 = KeplerEccentric::new(0.9).unwrap();
    let liar = BlackBox::new(
        SchemeMeta::new("bb-rk4-liar", "bb-rk4-liar", 4)
            .symplectic()
            .force_evaluations(4),
        rk4,
    );
    let record = symplecticity(&liar, &e9, &SymplecticSpec::default()).unwrap();
    assert_eq!(record.verdict, Verdict::Fail, "{}", record.reason);
    // the defect stands far above the finite differences' bound
    assert!(
        record.symplectic_residual > 1e3 * record.tolerance,
        "{}",
        record.reason
    );
}

/// Velocity Verlet that keeps its last force for the next step's first
/// kick: one evaluation a step. The kept force belongs to the run it was
/// computed in.
fn first_same_as_last(
    last: &mut Vec<f64>,
    q: &mut [f64],
    v: &mut [f64],
    h: f64,
    force: &Force<f64>,
) {
    if last.len() != q.len() {
        last.resize(q.len(), 0.0);
        force(q, last);
    }
    for i in 0..q.len() {
        v[i] += 0.5 * h * last[i];
        q[i] += h * v[i];
    }
    force(q, last);
    for i in 0..q.len() {
        v[i] += 0.5 * h * last[i];
    }
}

#[test]
fn a_stateful_step_needs_its_reset_and_gets_it() {
    let meta = SchemeMeta::new("bb-fsal-verlet", "bb-fsal-verlet", 2)
        .symplectic()
        .symmetric();
    let scene = KeplerEccentric::default();
    // Kept in the closure, as a wrapper without a reset must keep it: every
    // run but the first starts with a force from another run's end (the
    // order study ends its runs at 2 sqrt(2) periods, away from the start),
    // an O(h) error in the first kick, so the global error is O(h).
    let kept = std::sync::Mutex::new(Vec::new());
    let never_reset = BlackBox::new(
        meta,
        |q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>| {
            first_same_as_last(&mut kept.lock().unwrap(), q, v, h, force)
        },
    );
    let wrong = global_order(&never_reset, &scene, &OrderSpec::default()).unwrap();
    assert_ne!(
        wrong.verdict,
        Verdict::Pass,
        "a stale first force passed: {}",
        wrong.reason
    );
    // The same step with its state in the carry, fresh at every run.
    let stateful = BlackBox::stateful(meta, Vec::new, first_same_as_last);
    let right = global_order(&stateful, &scene, &OrderSpec::default()).unwrap();
    assert_eq!(right.verdict, Verdict::Pass, "{}", right.reason);
    assert_eq!(
        stepladder::guard::assert_evaluations(&stateful, &scene).per_step,
        1.0
    );
}

/// The implicit midpoint rule on a 1-D scene, its midpoint velocity found by
/// relaxed fixed-point iteration `mid += relaxation (v0 + h/2 a - mid)` (one
/// force call an iteration) until a sweep changes it by at most
/// `tolerance max(1, |mid|)`, reporting the iterations and that last change.
fn midpoint_solve(
    tolerance: f64,
    relaxation: f64,
    q: &mut [f64],
    v: &mut [f64],
    h: f64,
    force: &Force<f64>,
) -> Solve {
    let (q0, v0) = (q[0], v[0]);
    let (mut mid, mut a) = (v0, [0.0]);
    let mut solve = Solve {
        iterations: 0,
        residual: f64::NAN,
    };
    while solve.iterations < 200 {
        force(&[q0 + 0.5 * h * mid], &mut a);
        let change = relaxation * (v0 + 0.5 * h * a[0] - mid);
        mid += change;
        solve = Solve {
            iterations: solve.iterations + 1,
            residual: change.abs(),
        };
        if solve.residual <= tolerance * mid.abs().max(1.0) {
            break;
        }
    }
    q[0] = q0 + h * mid;
    v[0] = 2.0 * mid - v0;
    solve
}

/// Solved to round-off (a sweep changes the midpoint velocity by at most 4
/// ulps): the rule itself.
fn tight_midpoint(_: &mut (), q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) -> Solve {
    midpoint_solve(4.0 * f64::EPSILON, 1.0, q, v, h, force)
}

#[test]
fn an_implicit_black_box_is_charged_what_its_solves_report() {
    let scene = Harmonic::default();
    let midpoint = BlackBox::implicit(
        SchemeMeta::new("bb-midpoint", "bb-midpoint", 2)
            .symplectic()
            .symmetric()
            .implicit(),
        || (),
        tight_midpoint,
    );
    assert!(midpoint.meta().implicit);
    // one call an iteration, as reported: counted and reported agree
    let r = evaluations(&midpoint, &scene, 0.01);
    assert_eq!(r.reported_per_step, Some(r.per_step), "{}", r.reason);
    assert!(r.per_step >= 2.0, "{}", r.reason);
    assert_eq!(r.verdict, Verdict::Pass, "{}", r.reason);
    // every rung of the order study carries its solves: at least one
    // iteration a step, and a last change of at most a few ulps of |v| <= 1
    let order = global_order(&midpoint, &scene, &OrderSpec::default()).unwrap();
    assert_eq!(order.verdict, Verdict::Pass, "{}", order.reason);
    for g in order.rungs.iter().filter(|g| g.error.is_some()) {
        let tally = g.solve.expect("an implicit black box reports its solves");
        assert_eq!(tally.steps, g.steps);
        assert!(tally.iterations_per_step() >= 1.0, "{tally:?}");
        assert!(tally.largest_residual <= 4.0 * f64::EPSILON, "{tally:?}");
    }
    // a step that calls the force once more than its iterations (an
    // acceleration for output, say) spends more than its report says
    let extra = BlackBox::implicit(
        SchemeMeta::new("bb-midpoint-extra-call", "bb-midpoint-extra-call", 2)
            .symplectic()
            .symmetric()
            .implicit(),
        || (),
        |_: &mut (), q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>| {
            let solve = tight_midpoint(&mut (), q, v, h, force);
            force(q, &mut [0.0]);
            solve
        },
    );
    // a stateful step that claims to be implicit but reports nothing: the
    // count is shown, not judged, and no rung carries a tally
    let silent = BlackBox::stateful(
        SchemeMeta::new("bb-midpoint-silent", "bb-midpoint-silent", 2)
            .symplectic()
            .symmetric()
            .implicit(),
        || (),
        |_: &mut (), q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>| {
            tight_midpoint(&mut (), q, v, h, force);
        },
    );
    let r = evaluations(&silent, &scene, 0.01);
    assert_eq!(
        (r.reported_per_step, r.verdict),
        (None, Verdict::NotClaimed),
        "{}",
        r.reason
    );
    // a claim not made passes its guard (the rule: Verdict::fails_a_guard)
    stepladder::guard::assert_evaluations(&silent, &scene);
    let order = global_order(&silent, &scene, &OrderSpec::default()).unwrap();
    assert!(order.rungs.iter().all(|g| g.solve.is_none()));
    let r = evaluations(&extra, &scene, 0.01);
    let reported = r.reported_per_step.expect("reported");
    assert_eq!(r.per_step, reported + 1.0, "{}", r.reason);
    assert_eq!(r.verdict, Verdict::Fail, "{}", r.reason);
    assert!(
        r.reason.contains(&format!("{:.2}", r.per_step))
            && r.reason.contains(&format!("{reported:.2}")),
        "{}",
        r.reason
    );
}

#[test]
fn a_solve_stopped_at_a_fixed_tolerance_shows_its_residual_beside_the_error() {
    // Relaxed by 1/2, the iteration contracts by about 1/2 a sweep whatever
    // the step, so stopping at a change of 1e-7 leaves the midpoint velocity
    // about 1e-7 off and the velocity 2e-7 off in every step: an error that
    // no step size removes and that adds up over the N = t_end / h steps.
    // The error cannot fall like h^2 to round-off: order 2 must not pass.
    let loose = BlackBox::implicit(
        SchemeMeta::new("bb-midpoint-1e-7", "bb-midpoint-1e-7", 2)
            .symplectic()
            .symmetric()
            .implicit(),
        || (),
        |_: &mut (), q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>| {
            midpoint_solve(1e-7, 0.5, q, v, h, force)
        },
    );
    let record = global_order(&loose, &Harmonic::default(), &OrderSpec::default()).unwrap();
    assert_ne!(record.verdict, Verdict::Pass, "{}", record.reason);
    let judged = stepladder::study::ClaimVerdict::from(&record);
    let message = judged.failure().expect("fails its guard");
    assert!(
        message.contains("iterations a step, largest residual"),
        "{message}"
    );
    let finest = record
        .rungs
        .iter()
        .rev()
        .find_map(|g| g.solve.filter(|_| g.error.is_some()))
        .expect("solves reported");
    assert!(
        finest.largest_residual > 0.0 && finest.largest_residual <= 1e-7,
        "{finest:?}"
    );
}

/// An adaptive integrator that gives up at once and records no state at
/// all, not even the start: every study must say the runs did not finish,
/// never panic on what a black box leaves out.
#[test]
fn a_run_that_records_nothing_leaves_the_round_trip_unfinished() {
    use stepladder::scheme::{AdaptiveClaims, AdaptiveIntegrator, AdaptiveRun, RunEnd};
    use stepladder::state::State;
    use stepladder::study::{AdaptiveClaim, ToleranceLadderSpec, tolerance_ladder};
    struct Silent;
    impl AdaptiveIntegrator for Silent {
        fn name(&self) -> &'static str {
            "silent"
        }
        fn claims(&self) -> AdaptiveClaims {
            AdaptiveClaims::pair(5, 4)
        }
        fn integrate<S: Scene<D>, const D: usize>(
            &self,
            _scene: &S,
            _start: &State<D>,
            _t_end: f64,
            _tol: f64,
        ) -> Result<AdaptiveRun<D>, stepladder::error::Error> {
            Ok(AdaptiveRun {
                trajectory: Vec::new(),
                evaluations: 1,
                accepted: 0,
                rejected: 0,
                end: RunEnd::GaveUp,
                time: std::time::Duration::ZERO,
                reported_evaluations: None,
            })
        }
    }
    let r = tolerance_ladder(
        &Silent,
        &Harmonic::default(),
        &ToleranceLadderSpec::default(),
    )
    .expect("a record");
    let trip = r.round_trip.expect("the round trip is recorded");
    assert_eq!(trip.distance, None);
    assert!(!trip.returns);
    let judged = r
        .judged
        .iter()
        .find(|j| j.claim == AdaptiveClaim::RoundTrip)
        .expect("the round trip is judged");
    assert!(!judged.reason.contains("panicked"), "{}", judged.reason);
}

/// The round trip's round-off bound is the reversibility study's, `16 eps N
/// scale`, with `N` the accepted steps of both legs, recomputed here from
/// the two legs run apart: on an oscillator of amplitude 3 (scale 3), so
/// that the scale's place in it shows.
#[test]
fn the_round_trip_bound_counts_both_legs_and_the_scale() {
    use stepladder::scheme::{AdaptiveIntegrator, DPRKN8_ADAPTIVE};
    use stepladder::state::State;
    use stepladder::study::{ToleranceLadderSpec, tolerance_ladder};
    let scene = Harmonic::new(1.0, 3.0, 0.0).unwrap();
    let spec = ToleranceLadderSpec::default();
    let r = tolerance_ladder(&DPRKN8_ADAPTIVE, &scene, &spec).unwrap();
    let trip = r.round_trip.expect("the round trip is recorded");
    let there = DPRKN8_ADAPTIVE
        .run(&scene, trip.t_end, trip.tolerance)
        .unwrap();
    let end = there.trajectory.last().unwrap().1;
    let back = DPRKN8_ADAPTIVE
        .integrate(
            &scene,
            &State::new(end.q, -end.v),
            trip.t_end,
            trip.tolerance,
        )
        .unwrap();
    assert!(there.accepted > 10 && back.accepted > 10);
    let expected = 16.0 * (there.accepted + back.accepted) as f64 * f64::EPSILON * 3.0;
    assert!((scene.scale() - 3.0).abs() < 1e-15);
    assert!(
        (trip.round_off / expected - 1.0).abs() < 1e-12,
        "{:e} against {expected:e}",
        trip.round_off
    );
}

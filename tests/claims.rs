//! Every claim from one call, and the one rule by which a guard judges a
//! verdict: a refutation and an inconclusive measurement fail, a claim not
//! made passes. Each case is a real measurement of the verdict it tests.

use stepladder::guard::{assert_adaptive_claim, assert_claims, assert_order};
use stepladder::scene::{Anharmonic, Harmonic, KeplerCircular, KeplerEccentric, Scene};
use stepladder::scheme::DPRKN8_ADAPTIVE;
use stepladder::scheme::{DPRKN8, Euler, Leapfrog, VELOCITY_VERLET, YOSHIDA6};
use stepladder::study::{
    AdaptiveClaim, ClaimVerdict, EnergySpec, OrderSpec, ReverseSpec, SymplecticSpec,
    ToleranceLadderSpec, Verdict, claims, energy_drift, evaluations, global_order, reversibility,
    symplecticity, tolerance_ladder,
};

fn panics(f: impl FnOnce() + std::panic::UnwindSafe) -> String {
    let payload = std::panic::catch_unwind(f).expect_err("the guard should fail");
    payload
        .downcast_ref::<String>()
        .cloned()
        .unwrap_or_else(|| payload.downcast_ref::<&str>().unwrap().to_string())
}

/// The record holds the same verdicts as the five studies run one by one
/// with the guards' default specs, in the documented order.
#[test]
fn one_call_returns_the_verdict_of_every_study() {
    let scene = Harmonic::default();
    let record = claims(&Euler, &scene).unwrap();
    let names: Vec<&str> = record.verdicts.iter().map(|v| v.claim).collect();
    assert_eq!(
        names,
        ["order", "symplectic", "reversible", "energy", "evaluations"]
    );
    let alone = [
        global_order(&Euler, &scene, &OrderSpec::default())
            .unwrap()
            .verdict,
        symplecticity(&Euler, &scene, &SymplecticSpec::default())
            .unwrap()
            .verdict,
        reversibility(&Euler, &scene, &ReverseSpec::default())
            .unwrap()
            .verdict,
        energy_drift(&Euler, &scene, &EnergySpec::default())
            .unwrap()
            .verdict,
        evaluations(
            &Euler,
            &scene,
            stepladder::internals::cost::evaluations::counting_step(&scene),
        )
        .verdict,
    ];
    let verdicts: Vec<Verdict> = record.verdicts.iter().map(|v| v.verdict).collect();
    assert_eq!(verdicts, alone);
    // explicit Euler makes honest claims (first order, not symplectic, not
    // symmetric, energy drifting, one call a step): every one holds
    assert!(record.passed(), "{:?}", record.failures());
    let json = serde_json::to_string(&record).unwrap();
    for name in ["\"order\"", "\"evaluations\"", "\"verdicts\"", "\"rungs\""] {
        assert!(json.contains(name), "{name} missing from the record");
    }
}

/// The guard over every claim returns the same record and fails, listing
/// each failing claim once, when one claim is false.
#[test]
fn the_guard_over_every_claim_lists_each_failing_claim() {
    let record = assert_claims(&VELOCITY_VERLET, &KeplerCircular);
    assert!(record.verdicts.iter().all(|v| v.verdict == Verdict::Pass));
    // velocity Verlet claimed third order: only its order claim is false (a
    // claim below the measured order is a lower bound, and holds)
    let wrong = stepladder::scheme::BlackBox::new(
        stepladder::scheme::SchemeMeta::new("verlet-said-third", "Verlet said third", 3)
            .symplectic()
            .symmetric()
            .force_evaluations(2),
        |q: &mut [f64], v: &mut [f64], h: f64, force: &stepladder::scheme::Force<f64>| {
            let mut a = [0.0; 1];
            force(q, &mut a);
            v[0] += 0.5 * h * a[0];
            q[0] += h * v[0];
            force(q, &mut a);
            v[0] += 0.5 * h * a[0];
        },
    );
    let record = claims(&wrong, &Harmonic::default()).unwrap();
    let failing: Vec<&str> = record
        .verdicts
        .iter()
        .filter(|v| v.verdict.fails_a_guard())
        .map(|v| v.claim)
        .collect();
    assert_eq!(failing, ["order"], "{:?}", record.failures());
    let message = panics(|| {
        assert_claims(&wrong, &Harmonic::default());
    });
    assert_eq!(message.lines().count(), 1, "{message}");
    assert!(message.contains("fail order 3 claimed"), "{message}");
}

/// Inconclusive fails, claim by claim, on real undecided measurements.
#[test]
fn an_inconclusive_order_fails_its_guard() {
    // DPRKN8 on the anharmonic well: no window fits between its next terms
    // and the round-off floor
    let r = global_order(&DPRKN8, &Anharmonic::default(), &OrderSpec::default()).unwrap();
    assert_eq!(r.verdict, Verdict::Inconclusive, "{}", r.reason);
    let message = panics(|| {
        assert_order(&DPRKN8, &Anharmonic::default());
    });
    assert!(
        message.contains("inconclusive order 8 claimed"),
        "{message}"
    );
}

#[test]
fn an_inconclusive_energy_or_count_fails_its_guard() {
    let scene = Harmonic::default();
    // leap-frog at h w0 = 7, past its stability limit 2
    let energy = energy_drift(
        &Leapfrog,
        &scene,
        &EnergySpec {
            h: Some(7.0),
            periods: None,
        },
    )
    .unwrap();
    assert_eq!(energy.verdict, Verdict::Inconclusive, "{}", energy.reason);
    let judged = ClaimVerdict::from(&energy);
    assert_eq!(judged.failure(), Some(judged.message.as_str()));
    let count = evaluations(&Leapfrog, &scene, 7.0);
    assert_eq!(count.verdict, Verdict::Inconclusive, "{}", count.reason);
    assert!(ClaimVerdict::from(&count).failure().is_some());
}

/// The adaptive integrator's record lists all six claims; an undecided
/// exponent fails its guard, an error factor it does not state passes.
#[test]
fn an_adaptive_claim_not_made_passes_and_an_undecided_one_fails() {
    let spec = ToleranceLadderSpec {
        energy_periods: 0.0,
        ..Default::default()
    };
    let record = tolerance_ladder(&DPRKN8_ADAPTIVE, &KeplerCircular, &spec).unwrap();
    let verdicts = record.verdicts();
    assert_eq!(verdicts.len(), AdaptiveClaim::ALL.len());
    let of = |name: &str| verdicts.iter().find(|v| v.claim == name).unwrap().verdict;
    assert_eq!(of("exponent"), Verdict::Inconclusive, "{}", record.reason);
    assert_eq!(of("error factor"), Verdict::NotClaimed);
    assert!(!record.passed());
    assert_adaptive_claim(&record, AdaptiveClaim::ErrorFactor);
    let message = panics(|| assert_adaptive_claim(&record, AdaptiveClaim::Exponent));
    assert!(message.contains("exponent inconclusive"), "{message}");
}

/// The rule itself, for every verdict.
#[test]
fn refuted_and_undecided_fail_a_guard_and_nothing_else_does() {
    let fails: Vec<bool> = [
        Verdict::Pass,
        Verdict::Fail,
        Verdict::Inconclusive,
        Verdict::NotClaimed,
    ]
    .map(Verdict::fails_a_guard)
    .into();
    assert_eq!(fails, [false, true, true, false]);
}

/// The energy's growth is fitted from the end of the first period on: an
/// error oscillating with the orbit reaches its largest value within one
/// period, so before that a bounded error's running maximum still rises.
/// Velocity Verlet on the oscillator at its default step is bounded; a run
/// too short to fit a decade of time after the first period is undecided,
/// never the drift a fit from a fraction of a period would read (a run of
/// 14 periods fitted from 0.14 of a period gave `g = 1.5`).
#[test]
fn a_run_too_short_for_a_growth_law_is_undecided_not_a_drift() {
    let scene = Harmonic::default();
    for (periods, expected) in [
        (0.5, Some(Verdict::Inconclusive)),
        (5.0, Some(Verdict::Inconclusive)),
        (14.0, Some(Verdict::Inconclusive)),
        (50.0, Some(Verdict::Pass)),
        (200.0, Some(Verdict::Pass)),
    ] {
        let r = energy_drift(
            &VELOCITY_VERLET,
            &scene,
            &EnergySpec {
                h: None,
                periods: Some(periods),
            },
        )
        .unwrap();
        assert_ne!(r.verdict, Verdict::Fail, "{periods}: {}", r.reason);
        if let Some(v) = expected {
            assert_eq!(r.verdict, v, "{periods}: {}", r.reason);
        }
    }
}

/// A given step that does not resolve the first period (an `e = 0.99`
/// pericentre at a hundredth of a period) tests no conservation law, as the
/// default step's halving rule says: the orbit lost at it leaves velocity
/// Verlet's claims undecided, not refuted. At a step that resolves it the
/// claims are judged (at 1e-5 of the period the excursion, 0.106, is still
/// above a tenth of the energy).
#[test]
fn an_orbit_lost_at_a_given_unresolved_step_is_undecided() {
    let orbit = KeplerEccentric::new(0.99).unwrap();
    let at = |h: f64, periods: f64| {
        energy_drift(
            &VELOCITY_VERLET,
            &orbit,
            &EnergySpec {
                h: Some(h * orbit.period()),
                periods: Some(periods),
            },
        )
        .unwrap()
    };
    let coarse = at(0.01, 100.0);
    assert!(coarse.lost_at.is_some(), "{}", coarse.reason);
    assert_eq!(coarse.verdict, Verdict::Inconclusive, "{}", coarse.reason);
    assert!(
        coarse.reason.contains("does not resolve"),
        "{}",
        coarse.reason
    );
    // the pericentre's time scale is about 1e-4 of the period: at 4e-6 of it
    // the passage takes some thirty steps and the excursion is 0.017
    let fine = at(4e-6, 20.0);
    assert_eq!(fine.verdict, Verdict::Pass, "{}", fine.reason);
}

/// A force growing faster than linearly (the well's cubic past its
/// barrier) can overflow within one coarse step from a state on the orbit:
/// no defect of the step, and nothing measured. Sixth-order Yoshida at
/// `h = 10` on the anharmonic well is undecided there, symplectic at a
/// resolving step.
#[test]
fn an_overflow_at_a_coarse_step_on_a_cubic_force_is_no_breakdown() {
    let well = Anharmonic::default();
    let coarse = symplecticity(&YOSHIDA6, &well, &SymplecticSpec { h: Some(10.0) }).unwrap();
    assert_eq!(coarse.verdict, Verdict::Inconclusive, "{}", coarse.reason);
    assert!(
        !coarse.measured && !coarse.reason.contains("breakdown"),
        "{}",
        coarse.reason
    );
    let fine = symplecticity(&YOSHIDA6, &well, &SymplecticSpec { h: Some(0.5) }).unwrap();
    assert_eq!(fine.verdict, Verdict::Pass, "{}", fine.reason);
}

/// The long runs measure round-off only where the fixed step resolves the
/// motion: an `e = 0.99` pericentre at a hundredth of the period loses the
/// orbit in its first passage (the energy moves by 1e5 of itself), and the
/// study refuses it, naming the excursion; `e = 0.5` at the same step
/// (excursion under a tenth) runs.
#[test]
fn a_long_run_that_loses_its_orbit_is_refused_not_reported_as_round_off() {
    use stepladder::study::{LongrunSpec, longrun};
    let spec = LongrunSpec {
        steps: Some(10_000),
    };
    let lost = longrun(
        &VELOCITY_VERLET,
        false,
        &KeplerEccentric::new(0.99).unwrap(),
        &spec,
    );
    let Err(e) = lost else { panic!("{lost:?}") };
    let text = e.to_string();
    assert!(text.contains("does not resolve the motion"), "{text}");
    let kept = longrun(
        &VELOCITY_VERLET,
        false,
        &KeplerEccentric::new(0.5).unwrap(),
        &spec,
    )
    .expect("a resolved orbit runs");
    // round-off alone: a few eps a step at most over 10^4 steps
    assert!(
        kept.max_relative_error < 1e-12,
        "{}",
        kept.max_relative_error
    );
}

/// A counted run of equal steps ends where the scheme's own steps end and
/// counts what the force was asked: velocity Verlet over one period of the
/// oscillator at 64 steps is within its `(h w)^2 / 24`-sized phase error of
/// the start, one evaluation a step plus the first; a run that blows up
/// has no end state.
#[test]
fn a_counted_run_of_equal_steps_gives_its_end_and_its_evaluations() {
    use stepladder::internals::run::counted_end;
    let scene = Harmonic::default();
    let period = scene.period();
    let (end, evaluations) = counted_end(&VELOCITY_VERLET, &scene, period, 64);
    let end = end.expect("the run ends");
    let exact = scene.exact(period).unwrap();
    let h_w = std::f64::consts::TAU / 64.0;
    // the phase lags by about N (h w)^3 / 24 over the period
    let lag = 64.0 * h_w.powi(3) / 24.0;
    let distance = scene.phase_distance(&end, &exact);
    assert!(
        distance < 1.5 * lag && distance > 0.5 * lag,
        "{distance:e} against {lag:e}"
    );
    assert_eq!(evaluations, 65);
    // Euler at h w = 1e3 leaves the doubles within the run
    let (blown, _) = counted_end(&Euler, &scene, 1e3 * 1e4, 10_000);
    assert!(blown.is_none());
}

/// The size a ladder is refused with is its own: `t_end / h0` times the
/// geometric sum `(r^-L - 1) / (r^-1 - 1)`, here at a ratio of a quarter
/// (at one half the divisor is 1 and hides its own mistakes).
#[test]
fn a_refused_ladder_states_its_geometric_size() {
    use stepladder::error::Error;
    use stepladder::internals::ladder::Ladder;
    let levels = 17;
    match Ladder::new(0.1, 0.25, levels).unwrap().rungs(1.0) {
        Err(Error::TooExpensive { steps, .. }) => {
            let expected = 10.0 * (4f64.powi(levels as i32) - 1.0) / 3.0;
            assert!(
                (steps / expected - 1.0).abs() < 1e-12,
                "{steps:e} against {expected:e}"
            );
        }
        other => panic!("{other:?}"),
    }
}

/// The drift from the state after the first period is fitted from the end
/// of the second, where it has reached its plateau if bounded, and a window
/// of exactly one decade from there still fits a law: twenty periods at a
/// step of a 64th of the period (a power of two, so that the run ends at
/// twenty periods exactly) pass velocity Verlet bounded. Fitted from the
/// first period, ten periods read `g = 0.33` and failed it.
#[test]
fn exactly_a_decade_after_the_drifts_plateau_fits_a_law() {
    let scene = Harmonic::default();
    let run = |periods: f64| {
        energy_drift(
            &VELOCITY_VERLET,
            &scene,
            &EnergySpec {
                h: Some(scene.period() / 64.0),
                periods: Some(periods),
            },
        )
        .unwrap()
    };
    let decade = run(20.0);
    assert_eq!(decade.steps, 1280);
    assert_eq!(decade.verdict, Verdict::Pass, "{}", decade.reason);
    let short = run(10.0);
    assert_eq!(short.verdict, Verdict::Inconclusive, "{}", short.reason);
}

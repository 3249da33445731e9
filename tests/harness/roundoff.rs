//! Compensated summation: the compensated variants keep their twins' claims
//! and are the same maps up to round-off.

use stepladder::measure::Verdict;
use stepladder::measure::energy::{EnergySpec, energy_drift};
use stepladder::measure::order::{OrderSpec, global_order};
use stepladder::measure::reverse::{ReverseSpec, reversibility};
use stepladder::measure::symplectic::{SymplecticSpec, symplecticity};
use stepladder::scene::{Harmonic, KeplerCircular, Scene};
use stepladder::scheme::compensated::{PairVisitor, paired_ids, visit_pair};
use stepladder::scheme::{Scheme, StormerVerlet, StormerVerletCompensated};
use stepladder::tolerance::reverse_tolerance_ulps;

/// Every claim of a compensated variant, on the oscillator and the orbit:
/// order, energy, symplecticity, time symmetry.
struct Claims;
impl PairVisitor for Claims {
    type Output = Vec<String>;
    fn visit<P: Scheme + Sync + 'static, C: Scheme + Sync + 'static>(
        self,
        _: &'static P,
        c: &'static C,
    ) -> Vec<String> {
        let mut failures = Vec::new();
        let mut check = |what: &str, scene: &str, verdict: Verdict, reason: &str| {
            if verdict != Verdict::Pass {
                failures.push(format!("{} on {scene} {what}: {reason}", c.meta().id));
            }
        };
        let osc = Harmonic::default();
        let o = global_order(c, &osc, &OrderSpec::default()).unwrap();
        check("order", "harmonic", o.verdict, &o.reason);
        let o = global_order(c, &KeplerCircular, &OrderSpec::default()).unwrap();
        check("order", "kepler-circular", o.verdict, &o.reason);
        let e = energy_drift(c, &osc, &EnergySpec::default()).unwrap();
        check("energy", "harmonic", e.verdict, &e.reason);
        let e = energy_drift(c, &KeplerCircular, &EnergySpec::default()).unwrap();
        check("energy", "kepler-circular", e.verdict, &e.reason);
        let s = symplecticity(c, &osc, &SymplecticSpec::default()).unwrap();
        check("symplectic", "harmonic", s.verdict, &s.reason);
        let s = symplecticity(c, &KeplerCircular, &SymplecticSpec::default()).unwrap();
        check("symplectic", "kepler-circular", s.verdict, &s.reason);
        let r = reversibility(c, &osc, &ReverseSpec::default()).unwrap();
        check("reverse", "harmonic", r.verdict, &r.reason);
        let r = reversibility(c, &KeplerCircular, &ReverseSpec::default()).unwrap();
        check("reverse", "kepler-circular", r.verdict, &r.reason);
        failures
    }
}

#[test]
fn compensated_variants_keep_every_claim_of_their_twins() {
    let failures: Vec<String> = paired_ids()
        .into_iter()
        .flat_map(|id| visit_pair(id, Claims).unwrap())
        .collect();
    assert!(failures.is_empty(), "{failures:#?}");
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
    let mut b = StormerVerletCompensated.start(&osc, &osc.initial(), h);
    for _ in 0..4 {
        StormerVerlet.step(&osc, &mut a, h).unwrap();
        StormerVerletCompensated.step(&osc, &mut b, h).unwrap();
        assert_eq!(a.current, b.current.value);
        assert_eq!(b.current.low[0], 0.0);
        assert_eq!(
            StormerVerlet.state(&a, h),
            StormerVerletCompensated.state(&b, h)
        );
    }
}

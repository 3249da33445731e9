//! Force evaluations counted, not trusted: the claim `force_evaluations`
//! against the calls a scheme actually makes.
//!
//! A scheme's cost per step is read off a counting scene
//! ([`crate::scene::Counted`]) as the difference of two runs from the same
//! start, of [`COUNT_STEPS`] and twice as many steps, divided by
//! [`COUNT_STEPS`]: what the start-up spends (a two-step scheme's first
//! step, a first-same-as-last force computed once) cancels, and a cost that
//! repeats with any period dividing [`COUNT_STEPS`] is counted exactly. The
//! count is an integer ratio, not a measurement with noise, so an explicit
//! scheme's claim must equal it: more calls than claimed make every cost
//! figure built on the claim too cheap by their ratio, fewer too dear.
//!
//! An implicit scheme claims evaluations per iteration of its solve. Where
//! the scheme reports what its solves spent
//! ([`crate::scheme::Scheme::solver_evaluations`]) the count must equal the
//! report; an implicit black box reports nothing, so its count is shown and
//! not judged.

use super::count::counted_run;
pub use super::count::{COUNT_STEPS, counting_step};
use crate::run::caught;
use crate::scene::{Counted, Scene};
use crate::scheme::Scheme;
use crate::study::breakdown::probe;
use crate::study::verdict::Verdict;
use crate::wording::figure;
use serde::Serialize;

/// The force evaluations a scheme spends, counted, against its claim.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EvaluationRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Scene id.
    pub scene: &'static str,
    /// `force_evaluations` as claimed (per iteration for an implicit scheme).
    pub claimed: u32,
    /// Evaluations `start` spends before the first step.
    pub start: u64,
    /// Evaluations per step once started: the difference of the two runs
    /// over [`COUNT_STEPS`].
    pub per_step: f64,
    /// What an implicit scheme's solves report they spent per step over
    /// the same steps; `None` for an explicit scheme or a black box.
    pub reported_per_step: Option<f64>,
    /// Pass or fail; inconclusive when the counting run did not complete
    /// for want of stability; not claimed for an implicit scheme that does
    /// not report its solves (its count per iteration has nothing to be
    /// checked against).
    pub verdict: Verdict,
    /// Why, with the figures.
    pub reason: String,
}

/// Counts what `scheme` spends on `scene` at step `h` (any step the scheme
/// is stable at; the count of an explicit scheme does not depend on it).
pub fn evaluations<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    h: f64,
) -> EvaluationRecord {
    let meta = scheme.meta();
    let start = {
        let counted = Counted::new(scene);
        // a panic here shows again in the counting runs, which report it
        let _ = caught(|| scheme.start(&counted, &counted.initial(), h));
        counted.evaluations()
    };
    let short = counted_run(scheme, scene, h, COUNT_STEPS);
    let long = counted_run(scheme, scene, h, 2 * COUNT_STEPS);
    let mut record = EvaluationRecord {
        scheme: meta.id,
        scene: scene.meta().id,
        claimed: meta.force_evaluations,
        start,
        per_step: f64::NAN,
        reported_per_step: None,
        verdict: Verdict::Inconclusive,
        reason: String::new(),
    };
    let ((short, short_reported), (long, long_reported)) = match (short, long) {
        (Ok(short), Ok(long)) => (short, long),
        (Err(stop), _) | (_, Err(stop)) => {
            // a defect of the step (a panic, a stop below a step that runs
            // cleanly) fails; instability at the counting step decides nothing
            let probe = probe(scheme, scene, &scene.initial(), h, &stop);
            if probe.is_defect() {
                record.verdict = Verdict::Fail;
            }
            record.reason = format!(
                "the counting run of h = {} did not complete, so nothing was counted: {}",
                figure(h),
                probe.describe(h, &stop)
            );
            return record;
        }
    };
    let per_step = (long - short) as f64 / COUNT_STEPS as f64;
    record.per_step = per_step;
    let claimed = f64::from(meta.force_evaluations);
    if meta.implicit {
        match (short_reported, long_reported) {
            (Some(a), Some(b)) => {
                let reported = (b - a) as f64 / COUNT_STEPS as f64;
                record.reported_per_step = Some(reported);
                let agree = reported == per_step;
                record.verdict = Verdict::from_bool(agree);
                record.reason = if agree {
                    format!(
                        "{per_step:.2} force evaluations per step counted, as its solves report ({claimed} per iteration claimed)"
                    )
                } else {
                    format!(
                        "{per_step:.2} force evaluations per step counted, but its solves report {reported:.2}: cost figures from the report are off by a factor {:.3}",
                        per_step / reported
                    )
                };
            }
            _ => {
                record.verdict = Verdict::NotClaimed;
                record.reason = format!(
                    "{per_step:.2} force evaluations per step counted ({claimed} per iteration claimed); the iterations of its solves are not reported (a black box reports them through `BlackBox::implicit`), so the claim cannot be checked"
                );
            }
        }
        return record;
    }
    let agree = per_step == claimed;
    record.verdict = Verdict::from_bool(agree);
    record.reason = if agree {
        format!("{per_step} force evaluations per step counted, as claimed")
    } else {
        format!(
            "{per_step:.2} force evaluations per step counted over {COUNT_STEPS} steps, {claimed} claimed: cost figures from the claim would be {} by a factor {:.3}",
            if per_step > claimed {
                "too cheap"
            } else {
                "too dear"
            },
            per_step / claimed.max(f64::MIN_POSITIVE)
        )
    };
    record
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Harmonic, KeplerCircular};
    use crate::scheme::{
        BlackBox, DPRKN6, Force, ImplicitMidpoint, QUINLAN_TREMAINE8, Rk4, StormerVerlet,
        VELOCITY_VERLET, YOSHIDA6,
    };

    #[test]
    fn the_catalogue_spends_what_it_claims() {
        // reuse of the last force (Verlet: 1), first-same-as-last (DPRKN6:
        // 5 of 6 stages), compositions (Yoshida6: 7 kicks, one shared per
        // step boundary), a two-step start-up (Störmer) and a multistep
        // history: each is counted exactly
        let scene = KeplerCircular;
        let h = counting_step(&scene);
        for (record, expected) in [
            (evaluations(&VELOCITY_VERLET, &scene, h), 1.0),
            (evaluations(&DPRKN6, &scene, h), 5.0),
            (evaluations(&YOSHIDA6, &scene, h), 7.0),
            (evaluations(&Rk4, &scene, h), 4.0),
            (evaluations(&StormerVerlet, &scene, h), 1.0),
            (evaluations(&QUINLAN_TREMAINE8, &scene, h), 1.0),
        ] {
            assert_eq!(
                record.per_step, expected,
                "{}: {}",
                record.scheme, record.reason
            );
            assert_eq!(record.verdict, Verdict::Pass, "{}", record.reason);
        }
    }

    fn verlet_without_reuse(q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>) {
        let mut a = [0.0; 2];
        let a = &mut a[..q.len()];
        force(q, a);
        for i in 0..q.len() {
            v[i] += 0.5 * h * a[i];
            q[i] += h * v[i];
        }
        force(q, a);
        for i in 0..q.len() {
            v[i] += 0.5 * h * a[i];
        }
    }

    #[test]
    fn an_under_claim_fails_with_both_figures() {
        // two calls a step, the catalogue's claim of one
        let bb = BlackBox::new(*VELOCITY_VERLET.meta(), verlet_without_reuse);
        let r = evaluations(&bb, &KeplerCircular, 0.01);
        assert_eq!(r.per_step, 2.0);
        assert_eq!(r.verdict, Verdict::Fail);
        assert!(
            r.reason.contains("2.00 force evaluations per step") && r.reason.contains("1 claimed"),
            "{}",
            r.reason
        );
        assert!(
            r.reason.contains("too cheap by a factor 2.000"),
            "{}",
            r.reason
        );
        // and the same step with its true claim passes
        let mut meta = *VELOCITY_VERLET.meta();
        meta.force_evaluations = 2;
        let honest = BlackBox::new(meta, verlet_without_reuse);
        assert_eq!(
            evaluations(&honest, &KeplerCircular, 0.01).verdict,
            Verdict::Pass
        );
    }

    #[test]
    fn an_over_claim_fails_too() {
        let mut meta = *VELOCITY_VERLET.meta();
        meta.force_evaluations = 3;
        let bb = BlackBox::new(meta, verlet_without_reuse);
        let r = evaluations(&bb, &Harmonic::default(), 0.01);
        assert_eq!(r.verdict, Verdict::Fail);
        assert!(r.reason.contains("too dear"), "{}", r.reason);
    }

    #[test]
    fn a_periodic_cost_is_counted_exactly() {
        // a step that spends one extra call every third step: 7/3 a step
        let bb = BlackBox::stateful(
            *VELOCITY_VERLET.meta(),
            || 0u32,
            |n: &mut u32, q: &mut [f64], v: &mut [f64], h: f64, force: &Force<f64>| {
                if (*n).is_multiple_of(3) {
                    let mut a = [0.0; 2];
                    force(q, &mut a[..q.len()]);
                }
                *n += 1;
                verlet_without_reuse(q, v, h, force);
            },
        );
        let r = evaluations(&bb, &Harmonic::default(), 0.01);
        assert_eq!(r.per_step, 7.0 / 3.0, "{}", r.reason);
        assert_eq!(r.verdict, Verdict::Fail);
    }

    #[test]
    fn an_implicit_scheme_is_judged_against_its_own_report() {
        let r = evaluations(&ImplicitMidpoint, &Harmonic::default(), 0.01);
        assert_eq!(r.reported_per_step, Some(r.per_step), "{}", r.reason);
        assert!(r.per_step > 1.0, "{}", r.reason);
        assert_eq!(r.verdict, Verdict::Pass, "{}", r.reason);
    }

    #[test]
    fn the_counting_step_keeps_explicit_euler_inside_the_well() {
        // at a hundredth of the period Euler escaped the anharmonic well
        // within the 120 counted steps and nothing was counted
        // near the separatrix (x0 = 0.95 alpha), where the period is long
        let well = crate::scene::Anharmonic::new(1.0, 1.0, 0.95, 0.0).unwrap();
        let r = evaluations(&crate::scheme::Euler, &well, counting_step(&well));
        assert_eq!(
            (r.per_step, r.verdict),
            (1.0, Verdict::Pass),
            "{}",
            r.reason
        );
        let coarse = evaluations(&crate::scheme::Euler, &well, well.period() / 100.0);
        assert_eq!(coarse.verdict, Verdict::Inconclusive, "{}", coarse.reason);
    }
}

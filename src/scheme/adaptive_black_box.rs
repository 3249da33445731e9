//! An adaptive integrator from any crate, as a black box: a function that
//! advances positions and velocities on `f64` slices from `t0` to `t1` at a
//! tolerance, calling a force callback, and says how it went. The tolerance
//! ladder, the energy run and the round trip then judge it as they judge the
//! crate's own pairs; every force call is counted on the callback, and what
//! the integrator reports it spent is checked against the count.
//!
//! ```
//! use stepladder::guard;
//! use stepladder::scheme::{AdaptiveBlackBox, AdaptiveClaims, Advance};
//! use stepladder::scene::KeplerCircular;
//! use stepladder::scheme::Force;
//!
//! /// Someone's adaptive classical Runge-Kutta by step doubling: a step of
//! /// h against two of h/2, their difference (~ h^5) the estimate; it
//! /// advances with the two half steps.
//! fn doubling(q: &mut [f64], v: &mut [f64], t0: f64, t1: f64, tol: f64, force: &Force<f64>) -> Advance {
//!     let n = q.len();
//!     let rk4 = |y: &mut [f64; 4], h: f64| {
//!         let f = |y: &[f64; 4]| {
//!             let mut d = [0.0; 4];
//!             d[..n].copy_from_slice(&y[n..2 * n]);
//!             force(&y[..n], &mut d[n..2 * n]);
//!             d
//!         };
//!         let at = |k: &[f64; 4], c: f64| std::array::from_fn(|i| y[i] + c * h * k[i]);
//!         let k1 = f(y);
//!         let k2 = f(&at(&k1, 0.5));
//!         let k3 = f(&at(&k2, 0.5));
//!         let k4 = f(&at(&k3, 1.0));
//!         for i in 0..2 * n {
//!             y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
//!         }
//!     };
//!     let mut y = [0.0; 4];
//!     y[..n].copy_from_slice(q);
//!     y[n..2 * n].copy_from_slice(v);
//!     let (mut t, mut h, mut run) = (t0, 1e-2f64, Advance::reached());
//!     while t < t1 {
//!         h = h.min(t1 - t);
//!         let (mut whole, mut halves) = (y, y);
//!         rk4(&mut whole, h);
//!         rk4(&mut halves, 0.5 * h);
//!         rk4(&mut halves, 0.5 * h);
//!         let scale = 1.0 + y.iter().fold(0.0f64, |m, x| m.max(x.abs()));
//!         let err = (0..2 * n).fold(0.0f64, |m, i| m.max((whole[i] - halves[i]).abs())) / scale;
//!         if err <= tol {
//!             (y, t) = (halves, t + h);
//!             run.accepted += 1;
//!         } else {
//!             run.rejected += 1;
//!         }
//!         h *= (0.9 * (tol / err.max(1e-300)).powf(0.2)).clamp(0.2, 5.0);
//!     }
//!     q.copy_from_slice(&y[..n]);
//!     v.copy_from_slice(&y[n..2 * n]);
//!     run
//! }
//! // order 4, estimated by a difference that behaves like h^5 (an
//! // "order 4" estimate): error ~ TOL^(4/5)
//! let theirs = AdaptiveBlackBox::new("rk4-doubling", AdaptiveClaims::pair(4, 4), doubling);
//! guard::assert_adaptive(&theirs, &KeplerCircular);
//! ```

use super::adaptive::{AdaptiveClaims, AdaptiveIntegrator, AdaptiveRun, RunEnd, check_request};
use crate::error::Error;
use crate::scene::Scene;
use crate::scheme::Force;
use crate::state::State;
use nalgebra::SVector;
use std::cell::Cell;
use std::time::Instant;

/// How one black-box run went, as the integrator itself tells it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Advance {
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// How the run ended.
    pub end: RunEnd,
    /// The force evaluations it says it spent, if it keeps statistics
    /// (checked against the calls counted on the callback).
    pub reported_evaluations: Option<u64>,
}

impl Advance {
    /// A run that reached `t1`, with nothing counted yet.
    pub const fn reached() -> Self {
        Self {
            accepted: 0,
            rejected: 0,
            end: RunEnd::Reached,
            reported_evaluations: None,
        }
    }
}

impl AdaptiveClaims {
    /// The claims of an embedded pair advancing with its order-`order`
    /// solution and estimating with an order-`estimate_order` one: the
    /// estimate behaves like `h^(q+1)`, the error like `TOL^(p/(q+1))`;
    /// neither symplectic nor symmetric.
    pub const fn pair(order: u32, estimate_order: u32) -> Self {
        let estimate_power = estimate_order + 1;
        Self {
            order,
            estimate_power,
            // proportionality_exponent(order, estimate_power), in a const fn
            proportionality: Some(order as f64 / estimate_power as f64),
            symplectic: false,
            symmetric: false,
            error_factor: None,
        }
    }
}

/// An advance function as a plain `fn`: the type of
/// `AdaptiveBlackBox<AdvanceFn>` when the function is a named one (a
/// `static` integrator, say).
pub type AdvanceFn = fn(&mut [f64], &mut [f64], f64, f64, f64, &Force<'_, f64>) -> Advance;

/// An adaptive integrator given as `advance(q, v, t0, t1, tol, force)`:
/// it advances `q` and `v` in place from `t0` to `t1` at tolerance `tol`
/// (relative and absolute alike, as the crate's own pairs take it) and
/// returns how it went. The studies call it once per run, from `t0 = 0`.
pub struct AdaptiveBlackBox<F> {
    name: &'static str,
    claims: AdaptiveClaims,
    advance: F,
}

impl<F> AdaptiveBlackBox<F>
where
    F: Fn(&mut [f64], &mut [f64], f64, f64, f64, &Force<'_, f64>) -> Advance + Sync,
{
    /// Wraps `advance` with its claims.
    pub const fn new(name: &'static str, claims: AdaptiveClaims, advance: F) -> Self {
        Self {
            name,
            claims,
            advance,
        }
    }
}

impl<F> AdaptiveIntegrator for AdaptiveBlackBox<F>
where
    F: Fn(&mut [f64], &mut [f64], f64, f64, f64, &Force<'_, f64>) -> Advance + Sync,
{
    fn name(&self) -> &'static str {
        self.name
    }

    fn claims(&self) -> AdaptiveClaims {
        self.claims
    }

    fn integrate<S: Scene<D>, const D: usize>(
        &self,
        scene: &S,
        start: &State<D>,
        t_end: f64,
        tol: f64,
    ) -> Result<AdaptiveRun<D>, Error> {
        check_request(t_end, tol)?;
        let (mut q, mut v) = ([0.0; D], [0.0; D]);
        q.copy_from_slice(start.q.as_slice());
        v.copy_from_slice(start.v.as_slice());
        let calls = Cell::new(0u64);
        let force = |x: &[f64], a: &mut [f64]| {
            assert!(
                x.len() == D && a.len() == D,
                "stepladder: an adaptive black box's force call needs slices of the scene's \
                 dimension {D}, got {} and {}",
                x.len(),
                a.len()
            );
            calls.set(calls.get() + 1);
            a.copy_from_slice(
                scene
                    .acceleration(&SVector::<f64, D>::from_column_slice(x))
                    .as_slice(),
            );
        };
        let clock = Instant::now();
        let advance = (self.advance)(&mut q, &mut v, 0.0, t_end, tol, &force);
        let time = clock.elapsed();
        let end = State::new(SVector::from(q), SVector::from(v));
        // a run that ended early is not compared at t_end
        let trajectory = if advance.end == RunEnd::Reached {
            vec![(0.0, *start), (t_end, end)]
        } else {
            vec![(0.0, *start)]
        };
        Ok(AdaptiveRun {
            trajectory,
            evaluations: calls.get(),
            accepted: advance.accepted,
            rejected: advance.rejected,
            end: advance.end,
            time,
            reported_evaluations: advance.reported_evaluations,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::KeplerCircular;
    use crate::study::adaptive::{ToleranceLadderSpec, tolerance_ladder};
    use crate::study::verdict::Verdict;

    /// Adaptive RK4 by step doubling on the circular orbit's 4-vector, with
    /// two defects to switch on: a report of one evaluation too few per
    /// step, and an estimate with an `O(h)` term (`1e-3 h`) added, which
    /// dominates once the tolerance is tight and makes the steps grow like
    /// `1/TOL`.
    fn doubling(
        under_report: bool,
        first_order_estimate: bool,
    ) -> impl Fn(&mut [f64], &mut [f64], f64, f64, f64, &Force<'_, f64>) -> Advance + Sync {
        move |q, v, t0, t1, tol, force| {
            let f = |y: &[f64; 4]| {
                let mut d = [0.0; 4];
                d[..2].copy_from_slice(&y[2..]);
                force(&y[..2], &mut d[2..]);
                d
            };
            let rk4 = |y: &mut [f64; 4], h: f64| {
                let at = |y: &[f64; 4], k: &[f64; 4], c: f64| {
                    std::array::from_fn(|i| y[i] + c * h * k[i])
                };
                let k1 = f(y);
                let k2 = f(&at(y, &k1, 0.5));
                let k3 = f(&at(y, &k2, 0.5));
                let k4 = f(&at(y, &k3, 1.0));
                for i in 0..4 {
                    y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
                }
            };
            let mut y = [q[0], q[1], v[0], v[1]];
            let (mut t, mut h, mut run) = (t0, 1e-2f64, Advance::reached());
            let mut spent = 0;
            while t < t1 {
                h = h.min(t1 - t);
                let (mut whole, mut halves) = (y, y);
                rk4(&mut whole, h);
                rk4(&mut halves, 0.5 * h);
                rk4(&mut halves, 0.5 * h);
                spent += if under_report { 11 } else { 12 };
                let scale = 1.0 + y.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                let mut err =
                    (0..4).fold(0.0f64, |m, i| m.max((whole[i] - halves[i]).abs())) / scale;
                if first_order_estimate {
                    err += 1e-3 * h;
                }
                if err <= tol {
                    (y, t) = (halves, t + h);
                    run.accepted += 1;
                } else {
                    run.rejected += 1;
                }
                h *= (0.9 * (tol / err.max(1e-300)).powf(0.2)).clamp(0.2, 5.0);
                if run.accepted + run.rejected > 20_000_000 {
                    run.end = RunEnd::StepLimit;
                    break;
                }
            }
            q.copy_from_slice(&y[..2]);
            v.copy_from_slice(&y[2..]);
            run.reported_evaluations = Some(spent);
            run
        }
    }

    fn ladder(bb: &impl AdaptiveIntegrator) -> crate::study::adaptive::ToleranceLadderRecord {
        let spec = ToleranceLadderSpec {
            tolerances: (3..=12).map(|k| 10f64.powi(-k)).collect(),
            energy_periods: 0.0,
            ..ToleranceLadderSpec::default()
        };
        tolerance_ladder(bb, &KeplerCircular, &spec).unwrap()
    }

    #[test]
    fn a_correct_adaptive_black_box_passes_with_its_count_checked() {
        let bb = AdaptiveBlackBox::new(
            "rk4-doubling",
            AdaptiveClaims::pair(4, 4),
            doubling(false, false),
        );
        let r = ladder(&bb);
        assert_eq!(r.verdict, Verdict::Pass, "{}", r.reason);
        assert!(
            r.reason
                .contains("reported force evaluations equal the counted"),
            "{}",
            r.reason
        );
        // every run counted: 12 calls per attempted step
        for p in &r.points {
            assert_eq!(p.evaluations, 12 * (p.accepted + p.rejected), "{p:?}");
        }
    }

    #[test]
    fn a_report_one_call_short_fails_with_both_figures() {
        let bb = AdaptiveBlackBox::new(
            "rk4-doubling",
            AdaptiveClaims::pair(4, 4),
            doubling(true, false),
        );
        let r = ladder(&bb);
        assert_eq!(r.verdict, Verdict::Fail, "{}", r.reason);
        assert!(
            r.reason.contains("reports") && r.reason.contains("and made"),
            "{}",
            r.reason
        );
    }

    #[test]
    fn an_estimate_with_a_first_order_term_costs_too_much_and_fails() {
        let bb = AdaptiveBlackBox::new(
            "rk4-doubling",
            AdaptiveClaims::pair(4, 4),
            doubling(false, true),
        );
        let r = ladder(&bb);
        assert_eq!(r.verdict, Verdict::Fail, "{}", r.reason);
        assert!(r.reason.contains("the cost grows faster"), "{}", r.reason);
    }
}

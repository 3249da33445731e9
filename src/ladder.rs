//! Step-size ladders: `h_k = h0 * ratio^k`, each rung rounded to a whole
//! number of steps over the run so that every rung ends exactly at `t_end`.

use crate::error::Error;
use serde::Serialize;

use crate::tolerance::MIN_WINDOW;

/// The most steps one request may take in total. At a few tens of
/// nanoseconds a step this is about a minute of work; more is refused with an
/// estimate instead of leaving the user waiting.
pub const MAX_TOTAL_STEPS: u64 = 2_000_000_000;

/// Rough cost of one step with its error evaluation, used only to tell the
/// user how long a refused request would have taken.
pub const SECONDS_PER_STEP: f64 = 3e-8;

/// The automatic ladder's first step, in periods of the scene: coarse enough
/// that every scheme starts outside its asymptotic regime (the window search
/// drops such rungs, and they cost little).
pub const AUTO_START: f64 = 1.0 / 8.0;

/// The automatic ladder's largest rung, in force evaluations: `2^21`, a step
/// of 1/741455 period over the default 2 sqrt(2) periods for a scheme of one
/// force a step, proportionally coarser for one of more (a scheme's cost is
/// its force evaluations). With two rungs a halving and a twin for every
/// rung, a ladder to the cap spends about `2 * 3.4 * 2^21 = 1.4e7`
/// evaluations, a fraction of a second for a scene of a few flops a force.
/// Every correct scheme of order two or more reaches the round-off floor
/// well before it on the built-in scenes; a first-order scheme on a sharp
/// pericentre may not resolve it at all, and the study then says so and how
/// to go further. (An implicit scheme is counted at its evaluations per
/// iteration, a lower bound of its cost.)
pub const AUTO_MAX_RUNG_EVALUATIONS: u64 = 1 << 21;

/// Interleaved halving ladders the automatic ladder runs for a scheme that
/// claims order `p`: `ceil(p / 2)`, a ratio `2^(-1/m)` between neighbouring
/// rungs, so the error falls about fourfold a rung whatever the order, and
/// at least two, so that a window of six rungs needs the error resolved over
/// two and a half halvings of the step rather than five: a first- or
/// second-order scheme on a slow scene may resolve its motion only a few
/// halvings above the step cap. A high-order scheme gets enough rungs
/// between its pre-asymptotic regime and the round-off floor; finer ratios
/// would make neighbouring rungs so alike that little separates their errors.
pub fn per_octave(order: u32) -> u32 {
    order.div_ceil(2).max(2)
}

/// How the step sizes of an order study are chosen.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum LadderChoice {
    /// Chosen from the scheme and the data: [`per_octave`] interleaved
    /// halving ladders from [`AUTO_START`] periods, down to the round-off
    /// floor or until a rung would exceed [`AUTO_MAX_RUNG_EVALUATIONS`].
    Auto,
    /// The automatic ladder with another density of rungs or step cap.
    AutoWith(AutoLadder),
    /// Exactly these rungs.
    Fixed(Ladder),
}

/// The automatic ladder's settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AutoLadder {
    /// Rungs per halving of the step (interleaved halving ladders); `None`
    /// for [`per_octave`] of the claimed order.
    pub per_octave: Option<u32>,
    /// The largest rung, in force evaluations (steps times the scheme's
    /// evaluations a step).
    pub max_rung_evaluations: u64,
}

impl Default for AutoLadder {
    fn default() -> Self {
        Self {
            per_octave: None,
            max_rung_evaluations: AUTO_MAX_RUNG_EVALUATIONS,
        }
    }
}

/// The most rungs per halving of the step: neighbouring steps then differ
/// by `2^(1/16)`, 4.4%, and a first-order error by as much, about what a
/// fit separates from the rounding of the steps to whole counts; the
/// interleaved ladder keeps `per_octave` bases in memory and starts at
/// `4 per_octave` steps, so a finer one costs more and resolves less.
pub const MAX_PER_OCTAVE: u32 = 16;

/// The smallest rung cap, in force evaluations: the default first rung of
/// 23 steps refined over the window's two and a half halvings, for a scheme
/// of up to 17 evaluations a step, `23 * 2^2.5 * 17 = 2.2e3`, rounded up.
pub const MIN_RUNG_EVALUATIONS: u64 = 1 << 12;

impl AutoLadder {
    /// Refuses settings that measure nothing or cannot finish: `per_octave`
    /// in `1..=`[`MAX_PER_OCTAVE`], `max_rung_evaluations` in
    /// `[`[`MIN_RUNG_EVALUATIONS`]`, `[`MAX_TOTAL_STEPS`]` / 4]` (the rungs of
    /// halving ladders add up to twice the finest, and each has a twin).
    pub fn checked(&self) -> Result<(), Error> {
        if let Some(m) = self.per_octave
            && !(1..=MAX_PER_OCTAVE).contains(&m)
        {
            return Err(Error::InvalidParameter {
                name: "per_octave",
                value: f64::from(m),
                expected: "1 to 16 rungs per halving of the step",
            });
        }
        let cap = self.max_rung_evaluations;
        if !(MIN_RUNG_EVALUATIONS..=MAX_TOTAL_STEPS / 4).contains(&cap) {
            return Err(Error::InvalidParameter {
                name: "max_rung_evaluations",
                value: cap as f64,
                expected: "a rung cap in [4096, 5e8] force evaluations: enough for a window's \
                           rungs, and a ladder of at most the step limit",
            });
        }
        Ok(())
    }
}

/// How an order study's ladder ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LadderEnd {
    /// Round-off reached the errors of the finest rungs.
    Floor,
    /// The next rung would have exceeded the step cap.
    Cap,
    /// A fixed ladder ran every rung it was given.
    Fixed,
    /// A run broke down at a finer step than a rung that resolved the
    /// motion, or panicked (see [`crate::study::breakdown`]): finer rungs
    /// cannot undo it.
    Breakdown,
}

/// A geometric ladder `h_k = h0 * ratio^k`, `k = 0..levels`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Ladder {
    /// The coarsest step.
    pub h0: f64,
    /// Each rung's step over the previous one, in `(0, 1)`; 0.5 halves.
    pub ratio: f64,
    /// Number of rungs.
    pub levels: usize,
}

/// One rung as run: a whole number of steps over `t_end`, and the step that
/// actually results, `t_end / steps` (the fit uses this one).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RungSize {
    /// The step used.
    pub h: f64,
    /// Steps to `t_end`.
    pub steps: u64,
}

impl Ladder {
    /// A validated ladder.
    ///
    /// ```
    /// use stepladder::ladder::Ladder;
    /// assert!(Ladder::new(0.1, 0.5, 8).is_ok());
    /// assert!(Ladder::new(0.1, 2.0, 8).is_err()); // must refine
    /// assert!(Ladder::new(0.1, 0.5, 2).is_err()); // too few rungs to fit
    /// ```
    pub fn new(h0: f64, ratio: f64, levels: usize) -> Result<Self, Error> {
        crate::scene::positive("h0", h0)?;
        if !(ratio.is_finite() && ratio > 0.0 && ratio < 1.0) {
            return Err(Error::InvalidParameter {
                name: "ratio",
                value: ratio,
                expected: "a number in (0, 1): each rung's step is ratio times the previous one (0.5 halves)",
            });
        }
        if levels < MIN_WINDOW {
            return Err(Error::InvalidLadder(format!(
                "{levels} rungs cannot measure an order: a fit needs at least {MIN_WINDOW}"
            )));
        }
        Ok(Self { h0, ratio, levels })
    }

    /// The rungs over `[0, t_end]`, refusing ladders whose rungs would round
    /// to the same step count or whose total cost is out of proportion.
    pub fn rungs(&self, t_end: f64) -> Result<Vec<RungSize>, Error> {
        // the coarsest rung must take at least one step
        if self.h0 > t_end {
            return Err(Error::OutOfRange {
                name: "h0",
                value: self.h0,
                expected: format!(
                    "a step in (0, {}], the end time: at least one step",
                    crate::wording::exact(t_end)
                ),
            });
        }
        // the whole ladder's nominal steps, `t_end / h0` times the geometric
        // sum of `ratio^-k`, reckoned before any rung is built, so that a
        // request of billions of rungs is refused with its size (infinite
        // past the largest double) instead of being allocated
        let growth = 1.0 / self.ratio;
        let nominal = t_end / self.h0 * (growth.powf(self.levels as f64) - 1.0) / (growth - 1.0);
        check_count(nominal)?;
        let mut out: Vec<RungSize> = Vec::new();
        let mut total: u64 = 0;
        for k in 0..self.levels {
            let nominal = self.h0 * self.ratio.powi(k as i32);
            let steps = steps_for(t_end, nominal)?;
            if let Some(prev) = out.last()
                && prev.steps >= steps
            {
                return Err(Error::InvalidLadder(format!(
                    "rungs {} and {k} both round to {steps} steps over t_end = {}: use a smaller h0 or a smaller ratio",
                    k - 1,
                    crate::wording::exact(t_end)
                )));
            }
            total = total.saturating_add(steps);
            out.push(RungSize {
                h: t_end / steps as f64,
                steps,
            });
        }
        check_cost(total)?;
        Ok(out)
    }
}

/// Whole steps nearest to `t_end / h` (at least one), refusing absurd counts
/// with the true count, and a span or step that is not a finite positive
/// number (whose count would be NaN).
pub fn steps_for(t_end: f64, h: f64) -> Result<u64, Error> {
    crate::scene::positive("t_end", t_end)?;
    crate::scene::positive("h", h)?;
    let n = (t_end / h).round();
    check_count(n)?;
    Ok((n as u64).max(1))
}

/// Refuses a request of `steps` total steps when it exceeds [`MAX_TOTAL_STEPS`].
pub fn check_cost(steps: u64) -> Result<(), Error> {
    check_count(steps as f64)
}

/// [`check_cost`] of a count reckoned in floating point, so that a product
/// of factors (steps times runs, a span over a step) is refused with its
/// true value, not one saturated at the largest integer.
pub fn check_count(steps: f64) -> Result<(), Error> {
    // NaN is refused too: it is no count
    if !(0.0..=MAX_TOTAL_STEPS as f64).contains(&steps) {
        return Err(Error::TooExpensive {
            steps,
            limit: MAX_TOTAL_STEPS,
            seconds: steps * SECONDS_PER_STEP,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rungs_end_exactly_at_t_end_and_refine() {
        let l = Ladder::new(0.3, 0.5, 6).unwrap();
        let r = l.rungs(10.0).unwrap();
        assert_eq!(
            r.iter().map(|x| x.steps).collect::<Vec<_>>(),
            [33, 67, 133, 267, 533, 1067]
        );
        for x in &r {
            assert!((x.h * x.steps as f64 - 10.0).abs() < 1e-12);
        }
    }

    #[test]
    fn refuses_bad_ladders() {
        assert!(Ladder::new(0.0, 0.5, 6).is_err());
        assert!(Ladder::new(f64::NAN, 0.5, 6).is_err());
        assert!(Ladder::new(0.1, 1.0, 6).is_err());
        assert!(Ladder::new(0.1, f64::INFINITY, 6).is_err());
        // 0.99 refines too slowly for 10 steps: 10 and 10.1 both round to 10
        assert!(matches!(
            Ladder::new(1.0, 0.99, 6).unwrap().rungs(10.0),
            Err(Error::InvalidLadder(_))
        ));
        assert!(matches!(
            Ladder::new(1e-9, 0.5, 6).unwrap().rungs(10.0),
            Err(Error::TooExpensive { .. })
        ));
    }

    /// A ladder is reckoned before it is built: billions of rungs are
    /// refused with the ladder's size, `t_end / h0 (2^levels - 1)` at ratio
    /// one half (infinite past the largest double), never allocated.
    #[test]
    fn a_ladder_of_billions_of_rungs_is_refused_before_it_is_built() {
        for levels in [usize::MAX, 2_000_000_000, 4_294_967_297] {
            match Ladder::new(0.1, 0.5, levels).unwrap().rungs(1.0) {
                Err(Error::TooExpensive { steps, .. }) => assert!(steps.is_infinite(), "{steps}"),
                other => panic!("{levels}: {other:?}"),
            }
        }
        match Ladder::new(0.1, 0.5, 31).unwrap().rungs(1.0) {
            Err(Error::TooExpensive { steps, .. }) => {
                let expected = 10.0 * (2f64.powi(31) - 1.0);
                assert!((steps / expected - 1.0).abs() < 1e-12, "{steps}");
            }
            other => panic!("{other:?}"),
        }
        // 10 (2^27 - 1) = 1.3e9 steps: within the limit, and built
        assert_eq!(
            Ladder::new(0.1, 0.5, 27).unwrap().rungs(1.0).unwrap().len(),
            27
        );
    }

    /// A refused count is stated as it was reckoned, with the time it would
    /// take at the stated rate: 4e9 steps at 3e-8 s a step is 120 s.
    #[test]
    fn a_refused_count_states_its_steps_and_time() {
        assert_eq!(SECONDS_PER_STEP, 3e-8);
        match check_count(4e9) {
            Err(Error::TooExpensive {
                steps,
                limit,
                seconds,
            }) => {
                assert_eq!((steps, limit), (4e9, MAX_TOTAL_STEPS));
                assert!((seconds - 120.0).abs() < 1e-9, "{seconds}");
            }
            other => panic!("{other:?}"),
        }
        assert!(check_count(MAX_TOTAL_STEPS as f64).is_ok());
        assert!(check_count(f64::NAN).is_err());
        assert!(check_count(-1.0).is_err());
    }
}

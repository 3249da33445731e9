//! The cost of reaching a target error, with its 95% interval, from runs on
//! a fine tolerance grid: what the race compares its contenders by when
//! they differ by a few percent.
//!
//! An adaptive pair's error at the end time is not a smooth function of its
//! tolerance: it changes by whole steps, and where each step falls on the
//! orbit moves the error by a factor of a few from one tolerance to the
//! next. Interpolating between two runs that bracket the target therefore
//! inherits the scatter of two points, and moves with where the grid falls.
//!
//! Every run near the target instead predicts the target's cost from the
//! method's order `p`: at `N` steps its error `e` falls like `N^(-p)`, so
//! a run of cost `c` and error `e` predicts `c (e / target)^(1/p)`. Over
//! the runs whose error lies within [`WINDOW_DECADES`] of the target (one
//! prediction per distinct evaluation count, the mean of its runs':
//! neighbouring tolerances that take the same number of steps place them
//! almost alike, so they are not independent samples), the mean of the
//! logarithms is the estimate and their scatter its 95% interval
//! (Student's t). With fewer than [`FEWEST`] step counts near the target
//! (a contender whose step count barely moves with its tolerance) the cost
//! is bracketed by measurement instead ([`Reach::Bracketed`]): no run of
//! any tolerance cost less than the cheapest, and the cheapest run that
//! reaches the target cost what it did. Were
//! the local slope `p'` rather than `p`, a run one decade off would be
//! moved by `10^|1/p - 1/p'|` too much or too little (at most `10^(1/24)`,
//! 10%, for `p'` from 8 to 24 with `p = 12`), and a window that straddles
//! the target cancels that to first order.

use statrs::distribution::{ContinuousCDF, StudentsT};

/// How far, in decades of error, a run may lie from the target and still
/// predict its cost. One decade either side spans, for a twelfth-order
/// method (error `~ N^(-12)`), a factor `10^(2/12) = 1.47` of step counts:
/// about five distinct counts at 10 steps, twenty at 40, more beyond. Half a
/// decade leaves two or three at the loosest targets, too few for an
/// interval.
pub const WINDOW_DECADES: f64 = 1.0;

/// The fewest distinct step counts that form an interval: with two, the t
/// quantile (12.7) makes any interval uninformative; below it the cost is
/// bracketed by the runs.
pub const FEWEST: usize = 3;

/// One run: its cost (evaluations or seconds), its evaluations (which
/// identify the step sequence) and its error at the end time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Run {
    pub cost: f64,
    pub evaluations: u64,
    pub error: f64,
}

/// The estimated cost at a target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TargetCost {
    /// The mean log prediction and its standard error.
    pub ln_mean: f64,
    pub ln_standard_error: f64,
    /// Distinct step counts in the window, at least [`FEWEST`].
    pub counts: usize,
}

impl TargetCost {
    /// The estimate, `exp` of the mean log prediction.
    pub fn cost(&self) -> f64 {
        self.ln_mean.exp()
    }

    /// The 95% interval of the cost.
    pub fn interval(&self) -> [f64; 2] {
        let half = t975((self.counts - 1) as f64) * self.ln_standard_error;
        [(self.ln_mean - half).exp(), (self.ln_mean + half).exp()]
    }
}

/// How a contender stands at a target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reach {
    /// Runs near the target predict its cost.
    Estimated(TargetCost),
    /// Too few step counts near the target to estimate: the cost is at
    /// least the cheapest run's of any tolerance and at most the cheapest
    /// of those that reach the target.
    Bracketed { least: f64, most: f64 },
    /// No run reaches the target.
    NotReached,
}

impl Reach {
    /// The estimate, or the measured cost of reaching the target.
    pub fn cost(&self) -> Option<f64> {
        match self {
            Reach::Estimated(c) => Some(c.cost()),
            Reach::Bracketed { most, .. } => Some(*most),
            Reach::NotReached => None,
        }
    }

    /// The same reach at `factor` times the cost (evaluations to seconds).
    pub fn scaled(self, factor: f64) -> Reach {
        match self {
            Reach::Estimated(c) => Reach::Estimated(TargetCost {
                ln_mean: c.ln_mean + factor.ln(),
                ..c
            }),
            Reach::Bracketed { least, most } => Reach::Bracketed {
                least: least * factor,
                most: most * factor,
            },
            Reach::NotReached => Reach::NotReached,
        }
    }

    /// The 95% interval, or the bracket.
    pub fn interval(&self) -> Option<[f64; 2]> {
        match self {
            Reach::Estimated(c) => Some(c.interval()),
            Reach::Bracketed { least, most } => Some([*least, *most]),
            Reach::NotReached => None,
        }
    }
}

/// The median of `values` (the mean of the middle two for an even count);
/// `None` when there are none.
pub fn median(mut values: Vec<f64>) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(values[n / 2]),
        _ => Some(0.5 * (values[n / 2 - 1] + values[n / 2])),
    }
}

/// Student's t quantile at 0.975.
fn t975(dof: f64) -> f64 {
    StudentsT::new(0.0, 1.0, dof)
        .expect("positive degrees of freedom")
        .inverse_cdf(0.975)
}

/// The cost of reaching `target` for a method of order `order` from its
/// runs, loosest first (runs that failed to reach the end left out).
pub fn target_cost(runs: &[Run], target: f64, order: f64) -> Reach {
    if !runs.iter().any(|r| r.error <= target) {
        return Reach::NotReached;
    }
    // per evaluation count: the sum of its runs' log predictions, and how many
    let mut predictions: Vec<(u64, f64, f64)> = Vec::new();
    for r in runs {
        if r.error <= 0.0 || (r.error / target).log10().abs() > WINDOW_DECADES {
            continue;
        }
        let ln = r.cost.ln() + (r.error / target).ln() / order;
        match predictions.iter_mut().find(|(n, _, _)| *n == r.evaluations) {
            Some((_, sum, k)) => {
                *sum += ln;
                *k += 1.0;
            }
            None => predictions.push((r.evaluations, ln, 1.0)),
        }
    }
    let predictions: Vec<f64> = predictions.iter().map(|(_, sum, k)| sum / k).collect();
    let n = predictions.len();
    if n < FEWEST {
        let cheapest = |reaching: bool| {
            runs.iter()
                .filter(|r| !reaching || r.error <= target)
                .map(|r| r.cost)
                .fold(f64::INFINITY, f64::min)
        };
        return Reach::Bracketed {
            least: cheapest(false),
            most: cheapest(true),
        };
    }
    let mean = predictions.iter().sum::<f64>() / n as f64;
    let variance = predictions.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    Reach::Estimated(TargetCost {
        ln_mean: mean,
        ln_standard_error: (variance / n as f64).sqrt(),
        counts: n,
    })
}

/// `a / b` and its 95% interval: Welch's (the two standard errors
/// combined, Satterthwaite's degrees of freedom) when both are estimates,
/// else the quotient of the two intervals (a bracket holds the cost
/// surely, so the quotient holds the ratio at least as often as the
/// estimate's interval holds its cost). `None` unless both reach.
pub fn ratio(a: &Reach, b: &Reach) -> Option<(f64, [f64; 2])> {
    let value = a.cost()? / b.cost()?;
    if let (Reach::Estimated(a), Reach::Estimated(b)) = (a, b) {
        let (va, vb) = (a.ln_standard_error.powi(2), b.ln_standard_error.powi(2));
        let dof =
            (va + vb).powi(2) / (va * va / (a.counts - 1) as f64 + vb * vb / (b.counts - 1) as f64);
        let half = t975(dof) * (va + vb).sqrt();
        let ln = a.ln_mean - b.ln_mean;
        return Some((ln.exp(), [(ln - half).exp(), (ln + half).exp()]));
    }
    let ([a_lo, a_hi], [b_lo, b_hi]) = (a.interval()?, b.interval()?);
    Some((value, [a_lo / b_hi, a_hi / b_lo]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs on an exact power law `e = (N0 / N)^p`, cost `N`.
    fn exact_runs(p: f64, n0: f64) -> Vec<Run> {
        (10..80)
            .map(|n| Run {
                cost: n as f64,
                evaluations: n,
                error: (n0 / n as f64).powf(p),
            })
            .collect()
    }

    fn estimate(runs: &[Run], target: f64) -> TargetCost {
        match target_cost(runs, target, 12.0) {
            Reach::Estimated(c) => c,
            other => panic!("{other:?}"),
        }
    }

    /// The law's runs, their errors alternately `amplitude` above and below.
    fn scattered(n0: f64, amplitude: f64) -> Vec<Run> {
        exact_runs(12.0, n0)
            .into_iter()
            .enumerate()
            .map(|(i, r)| Run {
                error: r.error
                    * if i % 2 == 0 {
                        amplitude
                    } else {
                        1.0 / amplitude
                    },
                ..r
            })
            .collect()
    }

    #[test]
    fn runs_on_the_methods_law_predict_the_cost_exactly() {
        // e = (5/N)^12 reaches 1e-9 at N = 5 * 10^(9/12) = 28.12
        let c = estimate(&exact_runs(12.0, 5.0), 1e-9);
        let expected = 5.0 * 10f64.powf(0.75);
        assert!((c.cost() / expected - 1.0).abs() < 1e-12, "{}", c.cost());
        let [lo, hi] = c.interval();
        assert!(hi / lo - 1.0 < 1e-10);
        // the window: errors from 1e-10 to 1e-8, N from 5 * 10^(8/12) = 23.2
        // to 5 * 10^(10/12) = 34.0, so 24 to 34
        assert_eq!(c.counts, 11);
    }

    #[test]
    fn a_run_repeating_a_step_count_is_one_sample() {
        let mut runs = exact_runs(12.0, 5.0);
        // N = 30, error 4.6e-10, again at 1.4e-9: both in the window
        let twin = runs[20];
        runs.insert(
            21,
            Run {
                error: twin.error * 3.0,
                ..twin
            },
        );
        let c = estimate(&runs, 1e-9);
        assert_eq!(c.counts, 11);
        // the count's two predictions average: 3^(1/12) on one of 11
        let expected = 5.0 * 10f64.powf(0.75) * 3f64.powf(1.0 / 24.0 / 11.0);
        assert!((c.cost() / expected - 1.0).abs() < 1e-12, "{}", c.cost());
    }

    #[test]
    fn scatter_widens_the_interval_and_it_covers_the_law() {
        // errors a factor 3 above and below the law: the mean of the logs
        // stays near the law's cost, the interval holds it
        let [lo, hi] = estimate(&scattered(5.0, 3.0), 1e-9).interval();
        let law = 5.0 * 10f64.powf(0.75);
        assert!(lo < law && law < hi, "{lo} {law} {hi}");
        // each prediction is off by 3^(1/12) = 9.6%: the interval's half
        // width is about t * 0.092 / sqrt(n), some 6% for 10 or so counts
        assert!(hi / lo > 1.04 && hi / lo < 1.2, "{}", hi / lo);
    }

    #[test]
    fn too_few_step_counts_bracket_the_cost_by_the_runs() {
        let runs = exact_runs(12.0, 5.0);
        // the tightest run, N = 79, has error (5/79)^12 = 4e-15
        assert_eq!(target_cost(&runs, 1e-15, 12.0), Reach::NotReached);
        // near 1e-3 only N = 10 (2.4e-4; N = 11 has 7.8e-5): it is the
        // cheapest run and it reaches, so the cost is 10 exactly
        let exact = Reach::Bracketed {
            least: 10.0,
            most: 10.0,
        };
        assert_eq!(target_cost(&runs, 1e-3, 12.0), exact);
        // a gap of four decades between N = 20 and 21 leaves no run near
        // 1e-8: at least the cheapest run, at most the first that reaches
        let gapped: Vec<Run> = runs
            .iter()
            .map(|r| Run {
                error: if r.evaluations <= 20 { 1e-6 } else { 1e-10 },
                ..*r
            })
            .collect();
        let bracket = Reach::Bracketed {
            least: 10.0,
            most: 21.0,
        };
        assert_eq!(target_cost(&gapped, 1e-8, 12.0), bracket);
    }

    /// A contender whose step count does not move with its tolerance (its
    /// runs' errors span decades at one count) is bracketed by its runs.
    #[test]
    fn a_flat_cost_is_bracketed() {
        let runs: Vec<Run> = [(238, 4e-3), (255, 3e-3), (255, 2e-4), (255, 3e-7)]
            .into_iter()
            .chain([(255, 4e-9), (272, 1e-9)])
            .map(|(n, error)| Run {
                cost: n as f64,
                evaluations: n,
                error,
            })
            .collect();
        let bracket = |least: f64, most: f64| Reach::Bracketed { least, most };
        assert_eq!(target_cost(&runs, 1e-6, 12.0), bracket(238.0, 255.0));
        // 1e-9 is reached only at 272: two counts near it
        assert_eq!(target_cost(&runs, 1e-9, 12.0), bracket(238.0, 272.0));
        assert_eq!(target_cost(&runs, 1e-10, 12.0), Reach::NotReached);
    }

    #[test]
    fn the_ratio_resolves_a_difference_only_beyond_the_scatter() {
        let reach = |n0, amplitude| target_cost(&scattered(n0, amplitude), 1e-9, 12.0);
        // 10% apart with little scatter: resolved
        let (r, [lo, hi]) = ratio(&reach(5.5, 1.1), &reach(5.0, 1.1)).unwrap();
        assert!((r - 1.1).abs() < 0.02 && lo > 1.0, "{r} [{lo}, {hi}]");
        // 2% apart with a factor-10 scatter: not resolved
        let (r, [lo, hi]) = ratio(&reach(5.1, 10.0), &reach(5.0, 10.0)).unwrap();
        assert!(lo < 1.0 && hi > 1.0, "{r} [{lo}, {hi}]");
        // unreached: no ratio
        assert_eq!(ratio(&Reach::NotReached, &reach(5.0, 1.1)), None);
    }

    #[test]
    fn a_bracket_divides_by_the_other_sides_interval() {
        let estimate = reach_with_interval();
        let [lo, hi] = estimate.interval().unwrap();
        let bracket = Reach::Bracketed {
            least: 238.0,
            most: 255.0,
        };
        let (r, interval) = ratio(&bracket, &estimate).unwrap();
        assert_eq!(r, 255.0 / estimate.cost().unwrap());
        assert_eq!(interval, [238.0 / hi, 255.0 / lo]);
        let (_, inverse) = ratio(&estimate, &bracket).unwrap();
        assert_eq!(inverse, [lo / 255.0, hi / 238.0]);
    }

    #[test]
    fn scaling_moves_the_cost_and_its_interval_alike() {
        let reach = reach_with_interval();
        let [lo, hi] = reach.interval().unwrap();
        let scaled = reach.scaled(2e-7);
        let [slo, shi] = scaled.interval().unwrap();
        assert!((scaled.cost().unwrap() / reach.cost().unwrap() / 2e-7 - 1.0).abs() < 1e-12);
        assert!((slo / lo / 2e-7 - 1.0).abs() < 1e-12 && (shi / hi / 2e-7 - 1.0).abs() < 1e-12);
        let bracket = Reach::Bracketed {
            least: 10.0,
            most: 20.0,
        };
        let scaled = Reach::Bracketed {
            least: 30.0,
            most: 60.0,
        };
        assert_eq!(bracket.scaled(3.0), scaled);
        assert_eq!(Reach::NotReached.scaled(3.0), Reach::NotReached);
    }

    #[test]
    fn the_median_takes_the_middle_or_the_mean_of_the_middle_two() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(vec![4.0, 1.0, 3.0, 2.0]), Some(2.5));
        assert_eq!(median(Vec::new()), None);
    }

    fn reach_with_interval() -> Reach {
        target_cost(&scattered(5.0, 3.0), 1e-9, 12.0)
    }
}

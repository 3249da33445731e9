//! Every splitting table against the order conditions of `q'' = a(q)`
//! itself, on a nonlinear test problem, independently of the integration
//! runs: the check that applies to the Runge-Kutta-Nystrom tables, which the
//! generic-matrix check of `order_conditions.rs` rejects by design.
//!
//! The test problem: `D = 2`, a force `a(q)` with every monomial
//! `q1^i q2^j`, `i + j <= 7`, pseudo-random coefficients, and four initial
//! points. The local error of a method of order `p` for `q'' = a(q)` is
//! `sum_k E_k h^k` with `E_1 = .. = E_p = 0` for every force: each `E_k` is a
//! sum over Nystrom trees of the trees' condition defects times their
//! elementary differentials, which involve derivatives of `a` of order at
//! most `k - 2`, all present in a generic polynomial of degree 7 up to
//! `k = 9`; with four points in two dimensions no nonzero defect hides by
//! accident (the coefficient refinement in `tests/refine_nystrom_coefficients.py`
//! sees every independent condition on the same kind of problem).
//!
//! Two views of the same claim. The `E_k` themselves, as exact power
//! series in `h` evaluated in double-double: the method applied to series
//! (a drift adds `c h v`, a kick `c h a(q)` with the force on series) minus
//! the Taylor series of the exact flow (`Q_(k+2) = [a(q(t))]_k / ((k+1)(k+2))`).
//! And the local error of one numerical step at `h` and `h/2` against the
//! summed Taylor series, whose ratio must be `2^(p+1)` within what the
//! expansion and rounding allow.

use super::double_double::Dd;
use stepladder::scheme::{Flow, MCLACHLAN_ATELA4, MCLACHLAN_SB3A4, SplittingTable, TABLES};

const D: usize = 2;
/// Degree of the force polynomial: every `E_k` up to `k = DEGREE + 2`
/// sees every elementary differential.
const DEGREE: usize = 7;
/// Monomials `q1^i q2^j` with `i + j <= DEGREE`.
const MONOMIALS: usize = (DEGREE + 1) * (DEGREE + 2) / 2;
const POINTS: usize = 4;

/// Uniform in `[-1, 1]` from SplitMix64.
fn uniform(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    2.0 * (z >> 11) as f64 / (1u64 << 53) as f64 - 1.0
}

/// A truncated power series in `h` in double-double, and beside it in
/// doubles the same series built from absolute values: its entries bound
/// the sizes of every term that went into the corresponding coefficient,
/// hence its rounding.
#[derive(Clone, Debug)]
struct Series {
    value: Vec<Dd>,
    size: Vec<f64>,
}

impl Series {
    fn constant(x: Dd, terms: usize) -> Self {
        let mut s = Series {
            value: vec![Dd::default(); terms],
            size: vec![0.0; terms],
        };
        s.value[0] = x;
        s.size[0] = x.to_f64().abs();
        s
    }

    fn times(&self, other: &Series) -> Series {
        let n = self.value.len();
        let mut out = Series::constant(Dd::default(), n);
        for k in 0..n {
            for i in 0..=k {
                out.value[k] = out.value[k].add(self.value[i].mul(other.value[k - i]));
                out.size[k] += self.size[i] * other.size[k - i];
            }
        }
        out
    }

    /// `self += c h^shift x`, truncated.
    fn add_scaled(&mut self, x: &Series, c: f64, shift: usize) {
        for k in shift..self.value.len() {
            self.value[k] = self.value[k].add(x.value[k - shift].mul(Dd::of(c)));
            self.size[k] += c.abs() * x.size[k - shift];
        }
    }
}

/// `q'' = a(q)` with a polynomial force and the initial points.
struct Problem {
    /// `coefficients[c][m]` multiplies monomial `m` in component `c`.
    coefficients: [[f64; MONOMIALS]; D],
    /// Exponents `(i, j)` of each monomial.
    exponents: [(usize, usize); MONOMIALS],
    starts: [([f64; D], [f64; D]); POINTS],
}

impl Problem {
    fn new() -> Self {
        let mut state = 0x5eed_0003;
        let mut exponents = [(0, 0); MONOMIALS];
        let mut m = 0;
        for i in 0..=DEGREE {
            for j in 0..=DEGREE - i {
                exponents[m] = (i, j);
                m += 1;
            }
        }
        // coefficients shrink with the degree so that the Taylor series of
        // the flow converge well beyond the steps used here
        let coefficients = std::array::from_fn(|_| {
            std::array::from_fn(|m| {
                let (i, j) = exponents[m];
                uniform(&mut state) / ((1 + i + j) * (1 + i + j)) as f64
            })
        });
        let starts = std::array::from_fn(|_| {
            (
                std::array::from_fn(|_| uniform(&mut state) / 2.0),
                std::array::from_fn(|_| uniform(&mut state) / 2.0),
            )
        });
        Problem {
            coefficients,
            exponents,
            starts,
        }
    }

    /// `a(q)` on series.
    fn force_series(&self, q: &[Series; D]) -> [Series; D] {
        let n = q[0].value.len();
        let powers: [Vec<Series>; D] = std::array::from_fn(|c| {
            let mut p = vec![Series::constant(Dd::of(1.0), n)];
            for e in 1..=DEGREE {
                p.push(p[e - 1].times(&q[c]));
            }
            p
        });
        std::array::from_fn(|c| {
            let mut acc = Series::constant(Dd::default(), n);
            for (m, &(i, j)) in self.exponents.iter().enumerate() {
                acc.add_scaled(
                    &powers[0][i].times(&powers[1][j]),
                    self.coefficients[c][m],
                    0,
                );
            }
            acc
        })
    }

    /// `a(q)` at a point.
    fn force(&self, q: &[Dd; D]) -> [Dd; D] {
        let powers: [[Dd; DEGREE + 1]; D] = std::array::from_fn(|c| {
            let mut p = [Dd::of(1.0); DEGREE + 1];
            for e in 1..=DEGREE {
                p[e] = p[e - 1].mul(q[c]);
            }
            p
        });
        std::array::from_fn(|c| {
            self.exponents
                .iter()
                .enumerate()
                .fold(Dd::default(), |acc, (m, &(i, j))| {
                    acc.add(
                        powers[0][i]
                            .mul(powers[1][j])
                            .mul(Dd::of(self.coefficients[c][m])),
                    )
                })
        })
    }

    /// The Taylor series of `q(h)` and `v(h)`, `terms` coefficients each.
    fn exact(&self, point: usize, terms: usize) -> ([Series; D], [Series; D]) {
        let (q0, v0) = self.starts[point];
        let mut q: [Series; D] = std::array::from_fn(|c| {
            let mut s = Series::constant(Dd::of(q0[c]), terms + 1);
            s.value[1] = Dd::of(v0[c]);
            s.size[1] = v0[c].abs();
            s
        });
        for k in 0..terms - 1 {
            // [a(q(t))]_k depends on Q_0..Q_k only, all known by now
            let a = self.force_series(&q);
            let r = Dd::recip(((k + 1) * (k + 2)) as f64);
            for c in 0..D {
                q[c].value[k + 2] = a[c].value[k].mul(r);
                q[c].size[k + 2] = a[c].size[k] / ((k + 1) * (k + 2)) as f64;
            }
        }
        let v = std::array::from_fn(|c| Series {
            value: (0..terms)
                .map(|k| q[c].value[k + 1].mul(Dd::of((k + 1) as f64)))
                .collect(),
            size: (0..terms)
                .map(|k| q[c].size[k + 1] * (k + 1) as f64)
                .collect(),
        });
        let q = q.map(|s| Series {
            value: s.value[..terms].to_vec(),
            size: s.size[..terms].to_vec(),
        });
        (q, v)
    }

    /// One step of the flows applied to series in `h`.
    fn method_series(&self, flows: &[(Flow, f64)], point: usize, terms: usize) -> [Series; 2 * D] {
        let (q0, v0) = self.starts[point];
        let mut q: [Series; D] = std::array::from_fn(|c| Series::constant(Dd::of(q0[c]), terms));
        let mut v: [Series; D] = std::array::from_fn(|c| Series::constant(Dd::of(v0[c]), terms));
        for &(flow, w) in flows {
            match flow {
                Flow::Drift => {
                    for c in 0..D {
                        let vc = v[c].clone();
                        q[c].add_scaled(&vc, w, 1);
                    }
                }
                Flow::Kick => {
                    let a = self.force_series(&q);
                    for c in 0..D {
                        v[c].add_scaled(&a[c], w, 1);
                    }
                }
            }
        }
        let [q1, q2] = q;
        let [v1, v2] = v;
        [q1, q2, v1, v2]
    }

    /// One numerical step of size `h` from point 0: `(q1, q2, v1, v2)`.
    fn step(&self, flows: &[(Flow, f64)], h: f64) -> [Dd; 2 * D] {
        let (q0, v0) = self.starts[0];
        let mut q = q0.map(Dd::of);
        let mut v = v0.map(Dd::of);
        for &(flow, w) in flows {
            let c = Dd::of(w).mul(Dd::of(h));
            match flow {
                Flow::Drift => {
                    for i in 0..D {
                        q[i] = q[i].add(v[i].mul(c));
                    }
                }
                Flow::Kick => {
                    let a = self.force(&q);
                    for i in 0..D {
                        v[i] = v[i].add(a[i].mul(c));
                    }
                }
            }
        }
        [q[0], q[1], v[0], v[1]]
    }
}

/// The defect `E_k` of one table: every `q` and `v` component at every
/// point, per power `h^k`, with what rounding can explain.
#[derive(Debug)]
struct Defects {
    /// Largest entry of `E_k`.
    defect: Vec<f64>,
    /// Largest entry of the sum over every flow weight of the change of
    /// `E_k` when that weight moves by one unit in the last place: what
    /// rounding the weights to doubles can do to a condition they satisfy
    /// exactly.
    rounding: Vec<f64>,
    /// The double-double arithmetic's own rounding, with room to spare.
    noise: Vec<f64>,
    /// `E_k` at point 0 alone, each entry (`q1, q2, v1, v2`): the local
    /// error expansion the numerical step is compared with.
    first_point: Vec<[f64; 2 * D]>,
}

/// `E_k` entries and the size bounds of the terms behind them, per `k`.
fn defect_entries(
    problem: &Problem,
    flows: &[(Flow, f64)],
    terms: usize,
) -> (Vec<Vec<Dd>>, Vec<Vec<f64>>) {
    let mut entries = vec![Vec::new(); terms];
    let mut sizes = vec![Vec::new(); terms];
    for point in 0..POINTS {
        let (q, v) = problem.exact(point, terms);
        let m = problem.method_series(flows, point, terms);
        for (i, e) in q.iter().chain(v.iter()).enumerate() {
            for k in 0..terms {
                entries[k].push(m[i].value[k].add(e.value[k].neg()));
                sizes[k].push(m[i].size[k] + e.size[k]);
            }
        }
    }
    (entries, sizes)
}

impl Defects {
    fn of(problem: &Problem, flows: &[(Flow, f64)], degree: usize) -> Self {
        let terms = degree + 1;
        let (base, sizes) = defect_entries(problem, flows, terms);
        let max = |v: &[f64]| v.iter().fold(0.0f64, |a, &b| a.max(b));
        let mut rounding = vec![vec![0.0; base[0].len()]; terms];
        for i in 0..flows.len() {
            let mut moved = flows.to_vec();
            let w = moved[i].1;
            moved[i].1 = f64::from_bits(if w > 0.0 {
                w.to_bits() + 1
            } else {
                w.to_bits() - 1
            });
            let (d, _) = defect_entries(problem, &moved, terms);
            for k in 0..terms {
                for (r, (x, y)) in rounding[k].iter_mut().zip(d[k].iter().zip(&base[k])) {
                    *r += x.add(y.neg()).to_f64().abs();
                }
            }
        }
        // Each double-double operation rounds at 2^-104 relative to the
        // terms it combines; along one path through a step there are at most
        // `flows` kicks, each with `DEGREE + 1` products of series of
        // `terms` terms and a sum over `MONOMIALS` monomials. A factor 8 on
        // that count covers the worst-case accumulation (Higham, Accuracy
        // and Stability of Numerical Algorithms, 2002, 3.1).
        let units = 2f64.powi(-104) * 8.0 * (flows.len() * (DEGREE + 1 + terms + MONOMIALS)) as f64;
        Defects {
            defect: base
                .iter()
                .map(|e| max(&e.iter().map(|x| x.to_f64().abs()).collect::<Vec<_>>()))
                .collect(),
            rounding: rounding.iter().map(|r| max(r)).collect(),
            noise: sizes.iter().map(|s| units * max(s)).collect(),
            first_point: base
                .iter()
                .map(|e| std::array::from_fn(|i| e[i].to_f64()))
                .collect(),
        }
    }

    /// What the claimed order allows `E_k` to be: rounding and noise.
    fn allowance(&self, k: usize) -> f64 {
        self.rounding[k] + self.noise[k]
    }

    /// `E_k` in units of what rounding can explain: at most 1 for a
    /// condition that holds.
    fn ratio(&self, k: usize) -> f64 {
        self.defect[k] / self.allowance(k)
    }
}

/// How far above what rounding explains the first violated condition must
/// be for the order not to be an underclaim (the same margin as the generic
/// check's).
const BEYOND_ORDER: f64 = 1e6;

/// The failures of the claim "order `p` for `q'' = a(q)`": a condition
/// through `h^p` off by more than rounding, or `h^(p+1)` nearly holding.
fn series_failures(id: &str, p: usize, d: &Defects) -> Vec<String> {
    let mut failures = Vec::new();
    for k in 1..=p {
        if d.ratio(k) > 1.0 {
            failures.push(format!(
                "{id}: h^{k} Nystrom defect {:.2e}, {:.1} times what rounding explains",
                d.defect[k],
                d.ratio(k)
            ));
        }
    }
    if d.ratio(p + 1) < BEYOND_ORDER {
        failures.push(format!(
            "{id}: the h^{} Nystrom defect nearly vanishes ({:.2e}): order {p} underclaimed?",
            p + 1,
            d.defect[p + 1]
        ));
    }
    failures
}

/// Every table has its claimed order `p` for `q'' = a(q)`, no more: the
/// local error's coefficients `E_1 .. E_p` vanish to rounding and `E_(p+1)`
/// does not. Generic splittings are checked too (the Nystrom conditions are
/// a subset of theirs), so no table escapes both checks.
#[test]
fn every_table_has_its_order_for_second_order_equations() {
    let problem = Problem::new();
    let mut failures = Vec::new();
    for t in TABLES {
        let p = t.meta.order as usize;
        let d = Defects::of(&problem, &t.sequence(), p + 1);
        failures.extend(series_failures(t.meta.id, p, &d));
        println!(
            "{:>20}: h^1..h^{} Nystrom defect / allowance: {}",
            t.meta.id,
            p + 1,
            (1..=p + 1)
                .map(|k| format!("{:.1e}/{:.1e}", d.defect[k], d.allowance(k)))
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Terms of the exact flow's Taylor series summed for the reference step
/// (what is left out is bounded by [`truncation`]).
const REFERENCE_TERMS: usize = 40;
/// Expansion terms beyond the leading one carried into the error bound.
const EXTRA_TERMS: usize = 4;

/// One numerical step against the exact flow, at `h` and `h/2`.
#[derive(Debug)]
struct LocalErrorRatio {
    h: f64,
    /// `e(h) / e(h/2)`, `e` the largest entry of (method - exact flow).
    measured: f64,
    /// The range the expansion allows for it if the order is `p`.
    low: f64,
    high: f64,
}

impl LocalErrorRatio {
    /// The ratio for `flows` claimed to be of order `p`.
    ///
    /// Why its range. The local error is `sum_k E_k h^k`, a vector; let
    /// `P(h)` be the largest entry of `sum_(p<k<=K) E_k h^k` (the terms from
    /// the leading one to `K = p + 1 + EXTRA_TERMS`, from the series). The
    /// triangle inequality in the max norm gives `|e(h) - P(h)| <= R(h)`,
    /// with `R(h) = sum_(k<=p) allowance_k h^k` (what the claimed order
    /// allows the lower coefficients: rounding) `+ 2 |E_K| h^K` (the tail
    /// beyond `K`, on the premise that its terms fall at least by half per
    /// power; steps at which the last two kept terms do not are not used)
    /// `+` the double-double rounding of the steps `+` the truncation of the
    /// reference series. Hence
    /// `e(h)/e(h/2)` lies in `[(P - R)(h) / (P + R)(h/2), (P + R)(h) / (P - R)(h/2)]`,
    /// which is near `2^(p+1)` when the leading term dominates `P`. The step
    /// is the power of two, at most 1/4, with the narrowest range: smaller
    /// steps see the rounded weights, larger ones more of the higher terms.
    /// A weight off in its 8th digit leaves some `E_k`, `k <= p`, near 1e-8
    /// or above, which is in neither `P` nor `R` and moves `e` outside.
    fn of(problem: &Problem, flows: &[(Flow, f64)], p: usize) -> Self {
        let top = p + 1 + EXTRA_TERMS;
        let d = Defects::of(problem, flows, top);
        let power = |h: f64, k: usize| h.powi(k as i32);
        let rounding = |h: f64| (1..=p).map(|k| d.allowance(k) * power(h, k)).sum::<f64>();
        let largest = |k: usize| d.first_point[k].iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        let predicted = |h: f64| {
            (0..2 * D)
                .map(|i| {
                    (p + 1..=top)
                        .map(|k| d.first_point[k][i] * power(h, k))
                        .sum::<f64>()
                        .abs()
                })
                .fold(0.0, f64::max)
        };
        let tail = |h: f64| {
            let (before, last) = (
                largest(top - 1) * power(h, top - 1),
                largest(top) * power(h, top),
            );
            (last <= before / 2.0).then_some(2.0 * last)
        };
        let (q0, v0) = problem.starts[0];
        let state_size = q0.iter().chain(&v0).fold(1.0f64, |a, &b| a.max(b.abs()));
        let step_noise = 2f64.powi(-104)
            * 8.0
            * (flows.len() * (DEGREE + 1 + MONOMIALS) + REFERENCE_TERMS) as f64
            * state_size;
        let reference = problem.exact(0, REFERENCE_TERMS);
        // None where the premise on the tail fails
        let range = |h: f64| {
            let bound =
                |h: f64| Some(rounding(h) + tail(h)? + step_noise + truncation(&reference, h));
            let (b1, b2) = (bound(h)?, bound(h / 2.0)?);
            let (p1, p2) = (predicted(h), predicted(h / 2.0));
            (p2 > b2).then(|| ((p1 - b1) / (p2 + b2), (p1 + b1) / (p2 - b2)))
        };
        let (h, (low, high)) = (2..60)
            .map(|j| 2f64.powi(-j))
            .filter_map(|h| Some((h, range(h)?)))
            .min_by(|x, y| (x.1.1 / x.1.0).total_cmp(&(y.1.1 / y.1.0)))
            .expect("some step lets the expansion dominate rounding");
        let (e1, e2) = (
            local_error(problem, &reference, flows, h),
            local_error(problem, &reference, flows, h / 2.0),
        );
        LocalErrorRatio {
            h,
            measured: e1 / e2,
            low,
            high,
        }
    }

    fn holds(&self) -> bool {
        self.low <= self.measured && self.measured <= self.high
    }
}

/// The Taylor series of the exact flow from point 0, `REFERENCE_TERMS`
/// coefficients of `q` and of `v`.
type Reference = ([Series; D], [Series; D]);

/// A bound on the Taylor terms of the exact flow left out of `reference` at
/// step `h`: twice the last term kept, on the premise (asserted) that the
/// terms fall at least by half per power from there on, as the last two do.
fn truncation(reference: &Reference, h: f64) -> f64 {
    let (q, v) = reference;
    let term = |k: usize| {
        q.iter()
            .chain(v.iter())
            .map(|s| s.value[k].to_f64().abs() * h.powi(k as i32))
            .fold(0.0, f64::max)
    };
    let (before, last) = (term(REFERENCE_TERMS - 2), term(REFERENCE_TERMS - 1));
    assert!(
        last <= before / 2.0,
        "the reference series converges at h = {h}"
    );
    2.0 * last
}

/// Largest entry of one numerical step from point 0 minus the exact flow.
fn local_error(problem: &Problem, reference: &Reference, flows: &[(Flow, f64)], h: f64) -> f64 {
    let (q, v) = reference;
    let step = problem.step(flows, h);
    q.iter()
        .chain(v.iter())
        .zip(step)
        .map(|(s, x)| {
            // Horner in double-double; h is a power of two, exact
            let exact = s
                .value
                .iter()
                .rev()
                .fold(Dd::default(), |acc, &c| acc.mul(Dd::of(h)).add(c));
            x.add(exact.neg()).to_f64().abs()
        })
        .fold(0.0, f64::max)
}

/// The local error of one step falls by `2^(p+1)` when the step is halved,
/// within the range the error expansion and rounding allow, and that range
/// is narrow enough to tell `p` from `p - 1` and `p + 1` (it lies within a
/// factor `sqrt 2` of `2^(p+1)`).
#[test]
fn every_table_has_a_local_error_ratio_of_two_to_the_order_plus_one() {
    let problem = Problem::new();
    let mut failures = Vec::new();
    for t in TABLES {
        let p = t.meta.order as usize;
        let r = LocalErrorRatio::of(&problem, &t.sequence(), p);
        let expected = 2f64.powi(p as i32 + 1);
        println!(
            "{:>20}: h = 2^{}: e(h)/e(h/2) = {:.4} in [{:.4}, {:.4}], 2^{} = {expected}",
            t.meta.id,
            r.h.log2(),
            r.measured,
            r.low,
            r.high,
            p + 1
        );
        if !r.holds() {
            failures.push(format!("{}: {r:?}", t.meta.id));
        }
        if r.low < expected / 2f64.sqrt() || r.high > expected * 2f64.sqrt() {
            failures.push(format!(
                "{}: range too wide to tell the order: {r:?}",
                t.meta.id
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// `table` with one weight of `flow` moved by `delta` and others moved to
/// keep the weights of `flow` summing to one, so that only a condition from
/// `h^2` on can see it: in a palindrome the first weight and its mirror image
/// move by `delta` and the centre weight by `-2 delta` (or the two centre
/// weights by `-delta` each), which keeps it symmetric and leaves the first
/// violated condition at `h^3`; otherwise the first weight moves by `delta`
/// and the second by `-delta`.
fn perturbed(table: &SplittingTable, flow: Flow, delta: f64) -> Vec<(Flow, f64)> {
    let mut seq = table.sequence();
    let at: Vec<usize> = (0..seq.len()).filter(|&i| seq[i].0 == flow).collect();
    let n = at.len();
    if table.meta.symmetric {
        seq[at[0]].1 += delta;
        seq[at[n - 1]].1 += delta;
        // the centre weight twice, or each of the two of an even palindrome
        for i in [at[n / 2], at[(n - 1) / 2]] {
            seq[i].1 -= delta;
        }
    } else {
        seq[at[0]].1 += delta;
        seq[at[1]].1 -= delta;
    }
    seq
}

/// Both checks must be able to fail. A weight moved by one unit in its 8th
/// significant digit (others moved to stay consistent and, for the symmetric
/// table, symmetric) leaves a defect at `h^2` or `h^3` near 1e-9, which the
/// series check sees as a million times what rounding explains and which
/// moves the local error of one step out of its range.
#[test]
fn a_weight_off_in_its_eighth_digit_fails_both_checks() {
    let problem = Problem::new();
    for (t, flow) in [
        (&MCLACHLAN_SB3A4, Flow::Drift),
        (&MCLACHLAN_SB3A4, Flow::Kick),
        (&MCLACHLAN_ATELA4, Flow::Kick),
        (&MCLACHLAN_ATELA4, Flow::Drift),
    ] {
        let p = t.meta.order as usize;
        let first = t.sequence().into_iter().find(|s| s.0 == flow).unwrap().1;
        let delta = 10f64.powf(first.abs().log10().floor() - 7.0);
        let seq = perturbed(t, flow, delta);
        let d = Defects::of(&problem, &seq, p + 1);
        let worst = (1..=p).map(|k| d.ratio(k)).fold(0.0, f64::max);
        let r = LocalErrorRatio::of(&problem, &seq, p);
        println!(
            "{} with a {flow:?} weight moved by {delta:e}: worst condition through h^{p} at {worst:.1e} times rounding; step ratio {:.3} against [{:.3}, {:.3}] at h = {}",
            t.meta.id, r.measured, r.low, r.high, r.h
        );
        assert!(worst > BEYOND_ORDER, "{}: {d:?}", t.meta.id);
        assert!(!r.holds(), "{}: {r:?}", t.meta.id);
    }
}

/// A plausible layout mistake is caught: McLachlan and Atela's weights with
/// drifts and kicks exchanged (the kick weights applied as drifts) are a
/// different method, of order 3 only.
#[test]
fn mclachlan_atela_with_drifts_and_kicks_exchanged_is_rejected() {
    let problem = Problem::new();
    let swapped: Vec<(Flow, f64)> = MCLACHLAN_ATELA4
        .sequence()
        .into_iter()
        .map(|(f, w)| {
            let other = if f == Flow::Kick {
                Flow::Drift
            } else {
                Flow::Kick
            };
            (other, w)
        })
        .collect();
    let d = Defects::of(&problem, &swapped, 5);
    assert!(!series_failures("swapped", 4, &d).is_empty(), "{d:?}");
    assert!(d.ratio(4) > BEYOND_ORDER, "{d:?}");
    assert!(!LocalErrorRatio::of(&problem, &swapped, 4).holds());
}

/// The crate's DPRKN6 table against the one typed apart for the held-out
/// batch, from the same paper.
#[test]
fn dprkn6_coefficients_match_the_independently_typed_table() {
    let typed = stepladder_lab::corpus::held_out::DPRKN6;
    let ours = stepladder::scheme::nystrom_rk::DPRKN6;
    for i in 0..6 {
        assert!((ours.c[i] - typed.c[i]).abs() < 2e-16, "c{i}");
        assert!((ours.b[i] - typed.b[i]).abs() < 2e-16, "b{i}");
        assert!((ours.b_bar[i] - typed.b_bar[i]).abs() < 2e-16, "b_bar{i}");
        for j in 0..6 {
            assert!((ours.a[i][j] - typed.a[i][j]).abs() < 4e-16, "a{i}{j}");
        }
    }
}

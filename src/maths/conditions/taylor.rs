//! The order conditions of `q'' = a(q)` itself, on a nonlinear test problem:
//! the check that applies to Runge-Kutta-Nyström tables and splittings whose
//! order holds only for second-order equations, which the generic-matrix
//! check rejects by design.
//!
//! The test problem: `D = 2`, a force `a(q)` with every monomial
//! `q1^i q2^j`, `i + j <= 7`, pseudo-random coefficients, and four initial
//! points. The local error of a method of order `p` for `q'' = a(q)` is
//! `sum_k E_k h^k` with `E_1 = .. = E_p = 0` for every force: each `E_k` is a
//! sum over Nyström trees of the trees' condition defects times their
//! elementary differentials, which involve derivatives of `a` of order at
//! most `k - 2`, all present in a generic polynomial of degree 7 up to
//! `k = 9`; with four points in two dimensions no nonzero defect hides by
//! accident.
//!
//! Two views of the same claim. The `E_k` themselves, as exact power series
//! in `h` evaluated in double-double: the method applied to series (a drift
//! adds `c h v`, a kick `c h a(q)` with the force on series; a Nyström stage
//! `a(q + c h v + h^2 sum a k)`) minus the Taylor series of the exact flow
//! (`Q_(k+2) = [a(q(t))]_k / ((k+1)(k+2))`). And, for splittings, the local
//! error of one numerical step at `h` and `h/2` against the summed Taylor
//! series, whose ratio must be `2^(p+1)` within what the expansion and
//! rounding allow.

use super::defect::{Defect, StepRatio, uniform};
use crate::maths::dd::{Dd, UNIT, moved_one_ulp};
use crate::scheme::Flow;

const D: usize = 2;
/// Degree of the force polynomial: every `E_k` up to `k = DEGREE + 2`
/// sees every elementary differential.
pub(super) const DEGREE: usize = 7;
const POINTS: usize = 4;

/// The force's degree for defects through `h^degree`: [`DEGREE`] (the
/// problem every check through `h^9` has always used, coefficients and
/// points included) unless more is needed, `degree - 2` beyond (11 for a
/// twelfth-order tableau and its condition beyond).
fn force_degree(degree: usize) -> usize {
    DEGREE.max(degree.saturating_sub(2))
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
    /// The force's degree.
    degree: usize,
    /// `coefficients[c][m]` multiplies monomial `m` in component `c`.
    coefficients: [Vec<f64>; D],
    /// Exponents `(i, j)` of each monomial `q1^i q2^j`, `i + j <= degree`.
    exponents: Vec<(usize, usize)>,
    starts: [([f64; D], [f64; D]); POINTS],
}

impl Problem {
    fn new(degree: usize) -> Self {
        let mut state = 0x5eed_0003;
        let exponents: Vec<(usize, usize)> = (0..=degree)
            .flat_map(|i| (0..=degree - i).map(move |j| (i, j)))
            .collect();
        // coefficients shrink with the degree so that the Taylor series of
        // the flow converge well beyond the steps used here
        let coefficients = std::array::from_fn(|_| {
            exponents
                .iter()
                .map(|&(i, j)| uniform(&mut state) / ((1 + i + j) * (1 + i + j)) as f64)
                .collect()
        });
        let starts = std::array::from_fn(|_| {
            (
                std::array::from_fn(|_| uniform(&mut state) / 2.0),
                std::array::from_fn(|_| uniform(&mut state) / 2.0),
            )
        });
        Problem {
            degree,
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
            for e in 1..=self.degree {
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
        let powers: [Vec<Dd>; D] = std::array::from_fn(|c| {
            let mut p = vec![Dd::of(1.0); self.degree + 1];
            for e in 1..=self.degree {
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

    /// One step of `method` applied to series in `h` from `point`:
    /// `(q1, q2, v1, v2)`.
    fn method_series(&self, method: &Method, point: usize, terms: usize) -> [Series; 2 * D] {
        let (q0, v0) = self.starts[point];
        let q0: [Series; D] = std::array::from_fn(|c| Series::constant(Dd::of(q0[c]), terms));
        let v0: [Series; D] = std::array::from_fn(|c| Series::constant(Dd::of(v0[c]), terms));
        let (mut q, mut v) = (q0.clone(), v0.clone());
        match method {
            Method::Flows(flows) => {
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
            }
            Method::Nystrom(t) => {
                let mut k: Vec<[Series; D]> = Vec::with_capacity(t.c.len());
                for i in 0..t.c.len() {
                    let stage: [Series; D] = std::array::from_fn(|c| {
                        let mut x = q0[c].clone();
                        x.add_scaled(&v0[c], t.c[i], 1);
                        for (kj, &aij) in k.iter().zip(&t.a[i][..i]) {
                            x.add_scaled(&kj[c], aij, 2);
                        }
                        x
                    });
                    k.push(self.force_series(&stage));
                }
                for c in 0..D {
                    q[c].add_scaled(&v0[c], 1.0, 1);
                    for (ki, (&bb, &b)) in k.iter().zip(t.b_bar.iter().zip(&t.b)) {
                        q[c].add_scaled(&ki[c], bb, 2);
                        v[c].add_scaled(&ki[c], b, 1);
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

/// An explicit Runge-Kutta-Nyström tableau: `c`, the strict lower triangle
/// of `a`, and one pair of weights `b_bar`, `b` (main or embedded).
#[derive(Clone, Debug)]
pub(super) struct Tableau {
    pub c: Vec<f64>,
    pub a: Vec<Vec<f64>>,
    pub b_bar: Vec<f64>,
    pub b: Vec<f64>,
}

/// A method for `q'' = a(q)` that can be applied to series.
#[derive(Clone, Debug)]
pub(super) enum Method {
    /// Drifts and kicks in order of application.
    Flows(Vec<(Flow, f64)>),
    /// A Runge-Kutta-Nyström tableau.
    Nystrom(Tableau),
}

impl Method {
    /// Every coefficient a double stands for: the weights, or `c`, the
    /// strict lower triangle of `a`, `b_bar` and `b`.
    fn coefficients(&self) -> Vec<f64> {
        match self {
            Method::Flows(flows) => flows.iter().map(|f| f.1).collect(),
            Method::Nystrom(t) => {
                let lower = t.a.iter().enumerate().flat_map(|(i, row)| &row[..i]);
                t.c.iter()
                    .chain(lower)
                    .chain(&t.b_bar)
                    .chain(&t.b)
                    .copied()
                    .collect()
            }
        }
    }

    /// The same method with the coefficients `x`, in the order of
    /// [`Method::coefficients`].
    fn with_coefficients(&self, x: &[f64]) -> Method {
        match self {
            Method::Flows(flows) => {
                Method::Flows(flows.iter().zip(x).map(|(f, &w)| (f.0, w)).collect())
            }
            Method::Nystrom(t) => {
                let s = t.c.len();
                let mut rest = x[s..].iter().copied();
                let a = (0..s)
                    .map(|i| {
                        let mut row = vec![0.0; s];
                        for r in &mut row[..i] {
                            *r = rest.next().unwrap_or_default();
                        }
                        row
                    })
                    .collect();
                let rest: Vec<f64> = rest.collect();
                Method::Nystrom(Tableau {
                    c: x[..s].to_vec(),
                    a,
                    b_bar: rest[..s].to_vec(),
                    b: rest[s..].to_vec(),
                })
            }
        }
    }

    /// The longest chain of double-double operations behind one entry of
    /// the step's series of `terms` terms. A force on series takes
    /// `degree + 1` products of `terms`-term series and a sum over the
    /// force's monomials; a splitting applies at most one per flow; a
    /// Nyström stage sums up to `S` earlier stages first, and the step sums
    /// the `S` stages at the end.
    fn operations(&self, problem: &Problem, terms: usize) -> usize {
        let force = problem.degree + 1 + terms + problem.exponents.len();
        match self {
            Method::Flows(flows) => flows.len() * force,
            Method::Nystrom(t) => {
                let s = t.c.len();
                s * (s + force) + s
            }
        }
    }
}

/// The local error expansion of one method: the defects `E_1 .. E_degree`
/// with their allowances, and `E_0 .. E_degree` at point 0 entry by entry
/// (`q1, q2, v1, v2`), which the numerical step is compared with.
struct Expansion {
    defects: Vec<Defect>,
    first_point: Vec<[f64; 2 * D]>,
}

/// `E_k` entries at every point for `method` given the exact series, and
/// the size bounds of the terms behind them, per `k`.
fn entries(
    problem: &Problem,
    exact: &[([Series; D], [Series; D])],
    method: &Method,
    terms: usize,
) -> (Vec<Vec<Dd>>, Vec<Vec<f64>>) {
    let mut entries = vec![Vec::new(); terms];
    let mut sizes = vec![Vec::new(); terms];
    for (point, (q, v)) in exact.iter().enumerate() {
        let m = problem.method_series(method, point, terms);
        for (i, e) in q.iter().chain(v.iter()).enumerate() {
            for k in 0..terms {
                entries[k].push(m[i].value[k].sub(e.value[k]));
                sizes[k].push(m[i].size[k] + e.size[k]);
            }
        }
    }
    (entries, sizes)
}

/// The defects `E_1 .. E_degree` of `method`, each the largest entry over
/// every `q` and `v` component at every point, with its allowance:
///
/// - rounding: the largest entry of the sum over every coefficient of the
///   change of `E_k` when that coefficient moves by one unit in the last
///   place: what rounding the coefficients to doubles can do to a condition
///   they satisfy exactly;
/// - noise: each double-double operation rounds at `2^-104` relative to the
///   terms it combines, along at most [`Method::operations`] of them; a
///   factor 8 on that count covers the worst-case accumulation (Higham,
///   Accuracy and Stability of Numerical Algorithms, 2002, 3.1), times the
///   largest size bound of the terms.
fn expansion(problem: &Problem, method: &Method, degree: usize) -> Expansion {
    let terms = degree + 1;
    let exact: Vec<_> = (0..POINTS).map(|p| problem.exact(p, terms)).collect();
    let (base, sizes) = entries(problem, &exact, method, terms);
    let max = |v: &[f64]| v.iter().fold(0.0f64, |a, &b| a.max(b));
    let mut rounding = vec![vec![0.0; base[0].len()]; terms];
    let coefficients = method.coefficients();
    for i in 0..coefficients.len() {
        let Some(w) = moved_one_ulp(coefficients[i]) else {
            continue;
        };
        let mut moved = coefficients.clone();
        moved[i] = w;
        let (d, _) = entries(problem, &exact, &method.with_coefficients(&moved), terms);
        for k in 0..terms {
            for (r, (x, y)) in rounding[k].iter_mut().zip(d[k].iter().zip(&base[k])) {
                *r += x.sub(*y).to_f64().abs();
            }
        }
    }
    let units = UNIT * 8.0 * method.operations(problem, terms) as f64;
    let scale = |k: usize| {
        exact
            .iter()
            .flat_map(|(q, v)| q.iter().chain(v.iter()))
            .fold(0.0f64, |a, s| a.max(s.value[k].to_f64().abs()))
    };
    Expansion {
        defects: (1..terms)
            .map(|k| Defect {
                degree: k,
                value: max(&base[k].iter().map(|x| x.to_f64().abs()).collect::<Vec<_>>()),
                allowance: max(&rounding[k]) + units * max(&sizes[k]),
                scale: scale(k),
            })
            .collect(),
        first_point: base
            .iter()
            .map(|e| std::array::from_fn(|i| e[i].to_f64()))
            .collect(),
    }
}

/// The defects `E_1 .. E_degree` of `method` on `q'' = a(q)`.
pub(super) fn defects(method: &Method, degree: usize) -> Vec<Defect> {
    expansion(&Problem::new(force_degree(degree)), method, degree).defects
}

/// Terms of the exact flow's Taylor series summed for the reference step
/// (what is left out is bounded by [`truncation`]).
const REFERENCE_TERMS: usize = 40;
/// Expansion terms beyond the leading one carried into the error bound.
const EXTRA_TERMS: usize = 4;

/// The Taylor series of the exact flow from point 0, `REFERENCE_TERMS`
/// coefficients of `q` and of `v`.
type Reference = ([Series; D], [Series; D]);

/// A bound on the terms of a series beyond its `last`, from the sizes
/// `term(k)` of its terms: twice the last, on the premise that the terms
/// fall at least by half per power from there on, as the last two do
/// (`None` where they do not).
fn tail(term: impl Fn(usize) -> f64, last: usize) -> Option<f64> {
    let (before, last) = (term(last - 1), term(last));
    (last <= before / 2.0).then_some(2.0 * last)
}

/// A bound on the Taylor terms of the exact flow left out of `reference` at
/// step `h` ([`tail`]; `None` where the premise fails, and the step is not
/// used).
fn truncation(reference: &Reference, h: f64) -> Option<f64> {
    let (q, v) = reference;
    let term = |k: usize| {
        q.iter()
            .chain(v.iter())
            .map(|s| s.value[k].to_f64().abs() * h.powi(k as i32))
            .fold(0.0, f64::max)
    };
    tail(term, REFERENCE_TERMS - 1)
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
            x.sub(exact).to_f64().abs()
        })
        .fold(0.0, f64::max)
}

/// The ratio `e(h) / e(h/2)` of one numerical step of `flows` against the
/// exact flow, with the range a method of order `p` allows it.
///
/// Why its range. The local error is `sum_k E_k h^k`, a vector; let `P(h)`
/// be the largest entry of `sum_(p<k<=K) E_k h^k` (the terms from the
/// leading one to `K = p + 1 + EXTRA_TERMS`, from the series). The triangle
/// inequality in the max norm gives `|e(h) - P(h)| <= R(h)`, with
/// `R(h) = sum_(k<=p) allowance_k h^k` (what the claimed order allows the
/// lower coefficients: rounding) `+ 2 |E_K| h^K` (the tail beyond `K`, on
/// the premise that its terms fall at least by half per power; steps at
/// which the last two kept terms do not are not used) `+` the double-double
/// rounding of the steps `+` the truncation of the reference series. Hence
/// `e(h)/e(h/2)` lies in
/// `[(P - R)(h) / (P + R)(h/2), (P + R)(h) / (P - R)(h/2)]`, which is near
/// `2^(p+1)` when the leading term dominates `P`. The step is the power of
/// two, at most 1/4, with the narrowest range: smaller steps see the
/// rounded weights, larger ones more of the higher terms. A weight off in
/// its 8th digit leaves some `E_k`, `k <= p`, near 1e-8 or above, which is
/// in neither `P` nor `R` and moves `e` outside. `None` when no step lets
/// the expansion dominate its bound.
pub(super) fn step_ratio(flows: &[(Flow, f64)], p: usize) -> Option<StepRatio> {
    // the expansion of this one force, whatever it does or does not see
    // beyond h^9, is what the step is compared with
    let problem = Problem::new(DEGREE);
    let top = p + 1 + EXTRA_TERMS;
    let d = expansion(&problem, &Method::Flows(flows.to_vec()), top);
    let power = |h: f64, k: usize| h.powi(k as i32);
    let allowance = |k: usize| d.defects[k - 1].allowance;
    let rounding = |h: f64| (1..=p).map(|k| allowance(k) * power(h, k)).sum::<f64>();
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
    let beyond = |h: f64| tail(|k| largest(k) * power(h, k), top);
    let (q0, v0) = problem.starts[0];
    let state_size = q0.iter().chain(&v0).fold(1.0f64, |a, &b| a.max(b.abs()));
    let step_noise = UNIT
        * 8.0
        * (flows.len() * (problem.degree + 1 + problem.exponents.len()) + REFERENCE_TERMS) as f64
        * state_size;
    let reference = problem.exact(0, REFERENCE_TERMS);
    // None where a premise on a tail fails
    let range = |h: f64| {
        let bound =
            |h: f64| Some(rounding(h) + beyond(h)? + step_noise + truncation(&reference, h)?);
        let (b1, b2) = (bound(h)?, bound(h / 2.0)?);
        let (p1, p2) = (predicted(h), predicted(h / 2.0));
        (p2 > b2).then(|| ((p1 - b1) / (p2 + b2), (p1 + b1) / (p2 - b2)))
    };
    let (h, (low, high)) = (2..60)
        .map(|j| 2f64.powi(-j))
        .filter_map(|h| Some((h, range(h)?)))
        .min_by(|x, y| (x.1.1 / x.1.0).total_cmp(&(y.1.1 / y.1.0)))?;
    let (e1, e2) = (
        local_error(&problem, &reference, flows, h),
        local_error(&problem, &reference, flows, h / 2.0),
    );
    Some(StepRatio {
        h,
        measured: e1 / e2,
        low,
        high,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The operation count behind the allowances' noise term, counted by
    /// hand from the chains its comment names. Degree 7 has 36 monomials
    /// `q1^i q2^j` (`i + j <= 7`), degree 11 has 78; a force on series of
    /// `t` terms is `degree + 1 + t + monomials` operations. Three flows
    /// on degree 7 with 10 terms: `3 (8 + 10 + 36) = 162`. Seventeen stages
    /// on degree 11 with 14 terms (DPRKN12 at `h^13`): each stage sums up
    /// to 17 earlier ones and applies the force of `12 + 14 + 78 = 104`
    /// operations, `17 (17 + 104) = 2057`, and the step sums the 17 stages:
    /// 2074. Past `h^9` this term is most of
    /// an allowance, so a miscount moves a printed figure.
    #[test]
    fn the_operation_count_follows_the_chains() {
        let flows = Method::Flows(vec![
            (Flow::Kick, 0.5),
            (Flow::Drift, 1.0),
            (Flow::Kick, 0.5),
        ]);
        assert_eq!(flows.operations(&Problem::new(7), 10), 162);
        let s = 17;
        let nystrom = Method::Nystrom(Tableau {
            c: vec![0.0; s],
            a: vec![vec![0.0; s]; s],
            b_bar: vec![0.0; s],
            b: vec![0.0; s],
        });
        assert_eq!(nystrom.operations(&Problem::new(11), 14), 2074);
    }

    /// The sizes are majorants: every coefficient of the exact flow's
    /// series, `q` and `v = q'` alike, is at most its size in magnitude
    /// (the allowances' noise term rests on that), and the bound is used
    /// and not vacuous: each size is finite.
    #[test]
    fn the_exact_series_sizes_bound_their_coefficients() {
        let problem = Problem::new(DEGREE);
        for point in 0..POINTS {
            let (q, v) = problem.exact(point, 12);
            for (name, series) in [("q", &q), ("v", &v)] {
                for (c, s) in series.iter().enumerate() {
                    for (k, (value, size)) in s.value.iter().zip(&s.size).enumerate() {
                        let value = value.to_f64().abs();
                        assert!(
                            size.is_finite() && value <= *size,
                            "{name}[{c}] at h^{k}, point {point}: |{value:e}| above {size:e}"
                        );
                    }
                }
            }
        }
    }

    /// A reference series whose coefficients are all zero but for `terms`
    /// (power, value).
    fn reference_with(terms: &[(usize, f64)]) -> Reference {
        let zero = || Series::constant(Dd::default(), REFERENCE_TERMS);
        let mut q: [Series; D] = std::array::from_fn(|_| zero());
        let v: [Series; D] = std::array::from_fn(|_| zero());
        for &(k, x) in terms {
            q[0].value[k] = Dd::of(x);
        }
        (q, v)
    }

    /// The truncation bound rests on the last two kept terms falling by at
    /// least half: where they do, it is twice the last; where they do not,
    /// no bound is claimed, however large an earlier term is.
    #[test]
    fn truncation_is_bounded_only_where_the_last_terms_fall() {
        let last = REFERENCE_TERMS - 1;
        let falling = reference_with(&[(20, 1e3), (last - 1, 1.0), (last, 0.25)]);
        assert_eq!(truncation(&falling, 1.0), Some(0.5));
        let flat = reference_with(&[(20, 1e3), (last - 1, 1.0), (last, 1.0)]);
        assert_eq!(truncation(&flat, 1.0), None);
        // the terms are the coefficients times h^k: at h = 1/2 the
        // coefficients 1 and 1/2 make terms 2^-(last-1) and 2^-(last+1),
        // falling by a quarter, so the bound is twice the last
        let halving = reference_with(&[(last - 1, 1.0), (last, 0.5)]);
        assert_eq!(truncation(&halving, 0.5), Some(0.5f64.powi(last as i32)));
    }

    /// Velocity Verlet's local error is `E_3 h^3 + ... + E_8 h^8` plus
    /// what the expansion leaves out. At `h = 2^-10` the tail beyond `h^8`
    /// is `h^5 ~ 1e-15` of the leading term, and the double-double rounding
    /// (`2^-104` per operation, some hundreds of them) is `1e-19` of it, so
    /// the narrowest range the ratio `e(h)/e(h/2)` is given must be far
    /// narrower than `1e-6` relative, and hold the measured ratio, near
    /// `2^3`. A tail bound that did not scale its terms by `h^k` would
    /// swamp the prediction at every step and leave no range at all.
    #[test]
    fn velocity_verlet_step_ratio_is_pinned_to_its_expansion() {
        let verlet = [(Flow::Kick, 0.5), (Flow::Drift, 1.0), (Flow::Kick, 0.5)];
        let r = step_ratio(&verlet, 2).unwrap();
        assert!(r.holds(), "{r:?}");
        assert!(r.high / r.low - 1.0 < 1e-6, "{r:?}");
        assert!((r.measured / 8.0 - 1.0).abs() < 1e-2, "{r:?}");
    }
}

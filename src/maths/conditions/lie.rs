//! The order conditions of a splitting of any two non-commuting flows: the
//! method's power series in `h` against `exp(h (A + B))` on two random
//! matrices, the drift the flow of `A`, the kick the flow of `B`.
//!
//! A table has order `p` exactly when its series agrees with
//! `exp(h (A + B))` through `h^p` for generic non-commuting `A`, `B` (the
//! local error is `O(h^(p+1))`; the conditions of a splitting of
//! `|v|^2/2 + V(q)` into its two exact flows are those of the free Lie
//! algebra of the two flows, which the random matrices see in full).

use super::defect::Defect;
use crate::maths::dd::{Dd, UNIT, moved_one_ulp};
use crate::scheme::Flow;
use nalgebra::SMatrix;

/// Size of the test matrices. By the Amitsur-Levitzki theorem the `n x n`
/// matrices satisfy no polynomial identity of degree below `2n`, so with
/// `n = 6` no order condition up to degree 11 can hold by accident of the
/// dimension: a Lie polynomial that is not zero is not zero at random
/// matrices either.
const N: usize = 6;
type Matrix = SMatrix<f64, N, N>;
type DdMatrix = [[Dd; N]; N];

/// Entries uniform in `[-1, 1]` from SplitMix64 with a fixed seed.
fn random_matrix(seed: u64) -> Matrix {
    let mut state = seed;
    Matrix::from_fn(|_, _| super::uniform(&mut state))
}

fn dd_matrix(m: &Matrix) -> DdMatrix {
    std::array::from_fn(|i| std::array::from_fn(|j| Dd::of(m[(i, j)])))
}

fn dd_identity() -> DdMatrix {
    std::array::from_fn(|i| std::array::from_fn(|j| Dd::of(if i == j { 1.0 } else { 0.0 })))
}

fn dd_mul(x: &DdMatrix, y: &DdMatrix) -> DdMatrix {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| (0..N).fold(Dd::default(), |acc, k| acc.add(x[i][k].mul(y[k][j]))))
    })
}

fn dd_add(x: &DdMatrix, y: &DdMatrix) -> DdMatrix {
    std::array::from_fn(|i| std::array::from_fn(|j| x[i][j].add(y[i][j])))
}

fn dd_sub(x: &DdMatrix, y: &DdMatrix) -> DdMatrix {
    std::array::from_fn(|i| std::array::from_fn(|j| x[i][j].sub(y[i][j])))
}

fn dd_scale(x: &DdMatrix, c: Dd) -> DdMatrix {
    x.map(|row| row.map(|e| e.mul(c)))
}

/// Largest entry in absolute value.
fn dd_max(m: &DdMatrix) -> f64 {
    m.iter()
        .flatten()
        .map(|e| e.to_f64().abs())
        .fold(0.0, f64::max)
}

/// A power series in `h` truncated after `h^degree` with matrix coefficients
/// in double-double, and beside it in doubles the same series built from
/// absolute values (`|c|`, `|A|` entrywise): its entries bound the sizes of
/// every term that went into the corresponding entry, hence its rounding.
#[derive(Clone)]
struct Series {
    value: Vec<DdMatrix>,
    size: Vec<Matrix>,
}

/// The powers `X^j / j!` of one generator, exactly as the series need them.
struct Powers {
    value: Vec<DdMatrix>,
    size: Vec<Matrix>,
}

impl Powers {
    fn of(x: &Matrix, degree: usize) -> Self {
        let (xd, xa) = (dd_matrix(x), x.abs());
        let mut value = vec![dd_identity()];
        let mut size = vec![Matrix::identity()];
        for j in 1..=degree {
            value.push(dd_scale(&dd_mul(&value[j - 1], &xd), Dd::recip(j as f64)));
            size.push(size[j - 1] * xa / j as f64);
        }
        Powers { value, size }
    }
}

impl Series {
    fn one(degree: usize) -> Self {
        let mut value = vec![[[Dd::default(); N]; N]; degree + 1];
        value[0] = dd_identity();
        let mut size = vec![Matrix::zeros(); degree + 1];
        size[0] = Matrix::identity();
        Self { value, size }
    }

    /// `exp(c h X) = sum c^j X^j / j! h^j`.
    fn exp(p: &Powers, c: f64) -> Self {
        let degree = p.value.len() - 1;
        let mut s = Self::one(degree);
        let mut cj = Dd::of(1.0);
        for j in 1..=degree {
            cj = cj.mul(Dd::of(c));
            s.value[j] = dd_scale(&p.value[j], cj);
            s.size[j] = p.size[j] * c.abs().powi(j as i32);
        }
        s
    }

    /// `self * right`, truncated.
    fn times(&self, right: &Series) -> Series {
        let degree = self.value.len() - 1;
        let mut out = Series {
            value: vec![[[Dd::default(); N]; N]; degree + 1],
            size: vec![Matrix::zeros(); degree + 1],
        };
        for i in 0..=degree {
            for j in 0..=degree - i {
                let p = dd_mul(&self.value[i], &right.value[j]);
                out.value[i + j] = dd_add(&out.value[i + j], &p);
                out.size[i + j] += self.size[i] * right.size[j];
            }
        }
        out
    }
}

/// The generic linear problem `y' = (A + B) y`.
struct Problem {
    a: Powers,
    b: Powers,
    exact: Series,
}

impl Problem {
    fn new(degree: usize) -> Self {
        let (a, b) = (random_matrix(0x5eed_0001), random_matrix(0x5eed_0002));
        // A + B in double-double: every entry's sum kept exactly
        let sum = dd_add(&dd_matrix(&a), &dd_matrix(&b));
        let mut exact = Series::one(degree);
        let abs = a.abs() + b.abs();
        for j in 1..=degree {
            exact.value[j] = dd_scale(&dd_mul(&exact.value[j - 1], &sum), Dd::recip(j as f64));
            exact.size[j] = exact.size[j - 1] * abs / j as f64;
        }
        Problem {
            a: Powers::of(&a, degree),
            b: Powers::of(&b, degree),
            exact,
        }
    }

    /// `exp(c_m h X_m) ... exp(c_1 h X_1)` for the flows in order of
    /// application, each later one multiplying from the left.
    fn method(&self, flows: &[(Flow, f64)]) -> Series {
        let degree = self.exact.value.len() - 1;
        flows
            .iter()
            .fold(Series::one(degree), |product, &(flow, c)| {
                let x = match flow {
                    Flow::Drift => &self.a,
                    Flow::Kick => &self.b,
                };
                Series::exp(x, c).times(&product)
            })
    }

    /// The method's coefficients minus the exact flow's, per power of `h`.
    fn defect(&self, flows: &[(Flow, f64)]) -> Vec<DdMatrix> {
        let m = self.method(flows);
        m.value
            .iter()
            .zip(&self.exact.value)
            .map(|(x, y)| dd_sub(x, y))
            .collect()
    }
}

/// The defects at `h^1 .. h^degree`, each with its allowance:
///
/// - `value`: the largest entry of the method's `h^k` coefficient minus
///   `exp(h (A + B))`'s;
/// - rounding: the largest entry of the sum, over every weight, of the
///   defect's change when that weight moves by one unit in the last place:
///   what rounding the weights to doubles can do to a condition they satisfy
///   exactly;
/// - noise: the double-double arithmetic's own rounding. Each operation
///   rounds at `2^-104` relative to the terms it combines, and an entry of
///   the `h^k` coefficient is reached along a path of at most
///   `flows + degree + N` operations (one product per flow, one factor
///   `1/j` per power, one sum of `N` products per matrix product); a factor
///   8 on that count covers the worst-case accumulation (Higham, Accuracy
///   and Stability of Numerical Algorithms, 2002, 3.1), times the largest
///   entry of the series of absolute values, which bounds every term.
///
/// The allowance is rounding plus noise.
pub(super) fn defects(flows: &[(Flow, f64)], degree: usize) -> Vec<Defect> {
    let problem = Problem::new(degree);
    let base = problem.defect(flows);
    let mut rounding = vec![[[0.0f64; N]; N]; degree + 1];
    for i in 0..flows.len() {
        let Some(w) = moved_one_ulp(flows[i].1) else {
            continue;
        };
        let mut moved = flows.to_vec();
        moved[i].1 = w;
        for (k, d) in problem.defect(&moved).iter().enumerate() {
            for r in 0..N {
                for c in 0..N {
                    rounding[k][r][c] += d[r][c].sub(base[k][r][c]).to_f64().abs();
                }
            }
        }
    }
    let size = problem.method(flows).size;
    let units = UNIT * 8.0 * (flows.len() + degree + N) as f64;
    (1..=degree)
        .map(|k| {
            let rounded = rounding[k].iter().flatten().fold(0.0f64, |a, &b| a.max(b));
            let noise = units * (size[k] + problem.exact.size[k]).max();
            Defect {
                degree: k,
                value: dd_max(&base[k]),
                allowance: rounded + noise,
                scale: dd_max(&problem.exact.value[k]),
            }
        })
        .collect()
}

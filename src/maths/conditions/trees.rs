//! Butcher's order conditions of a Runge-Kutta tableau `(a, b)` on a
//! first-order system `y' = f(y)`: for every rooted tree `t` with `n`
//! vertices, `sum_i b_i Phi_i(t) = 1 / gamma(t)`, the elementary weight
//! `Phi(t)` built from `a` by the tree's shape and `gamma(t)` its density
//! (Hairer, Norsett and Wanner, Solving Ordinary Differential Equations I,
//! 1993, II.2). Order `p` holds exactly when every tree with at most `p`
//! vertices does, for every `f`; the trees are independent conditions, so
//! there is no test problem to choose.

use super::defect::{Defect, TreeDefect};
use crate::maths::dd::{Dd, UNIT, moved_one_ulp};

/// Every rooted tree up to `max` vertices, smaller trees first: sizes and
/// children (indices of smaller trees, a non-decreasing multiset).
struct Trees {
    size: Vec<usize>,
    children: Vec<Vec<usize>>,
}

fn trees(max: usize) -> Trees {
    fn pick(
        t: &Trees,
        below: usize,
        from: usize,
        left: usize,
        current: &mut Vec<usize>,
        out: &mut Vec<Vec<usize>>,
    ) {
        if left == 0 {
            out.push(current.clone());
            return;
        }
        for i in from..below {
            if t.size[i] <= left {
                current.push(i);
                pick(t, below, i, left - t.size[i], current, out);
                current.pop();
            }
        }
    }
    let mut t = Trees {
        size: vec![1],
        children: vec![vec![]],
    };
    for n in 2..=max {
        let below = t.size.len();
        let mut out = Vec::new();
        pick(&t, below, 0, n - 1, &mut Vec::new(), &mut out);
        for ch in out {
            t.size.push(n);
            t.children.push(ch);
        }
    }
    t
}

/// The tree in bracket notation: `τ` the single vertex, `[t1,t2]` a root
/// with the subtrees `t1` and `t2` (so `[[τ]]` is the tall tree with three
/// vertices, `[τ,τ]` the bushy one).
fn name(t: &Trees, n: usize) -> String {
    if t.children[n].is_empty() {
        return "τ".into();
    }
    let inner: Vec<String> = t.children[n].iter().map(|&c| name(t, c)).collect();
    format!("[{}]", inner.join(","))
}

/// `sum b Phi(t) - 1/gamma(t)` for every tree, in double-double, and the
/// same sum built from `|a|`, `|b|`, which bounds every term behind it.
fn weights(a: &[Vec<f64>], b: &[f64], t: &Trees) -> Vec<(Dd, f64)> {
    let s = b.len();
    let mut phi: Vec<Vec<(Dd, f64)>> = Vec::with_capacity(t.size.len());
    let mut gamma: Vec<f64> = Vec::with_capacity(t.size.len());
    let mut out = Vec::with_capacity(t.size.len());
    for n in 0..t.size.len() {
        let mut p = vec![(Dd::of(1.0), 1.0); s];
        let mut g = t.size[n] as f64;
        for &ch in &t.children[n] {
            for (i, pi) in p.iter_mut().enumerate() {
                let (sum, size) = (0..s).fold((Dd::default(), 0.0), |(acc, size), j| {
                    (
                        acc.add(Dd::of(a[i][j]).mul(phi[ch][j].0)),
                        size + a[i][j].abs() * phi[ch][j].1,
                    )
                });
                *pi = (pi.0.mul(sum), pi.1 * size);
            }
            g *= gamma[ch];
        }
        let (weight, size) = b
            .iter()
            .zip(&p)
            .fold((Dd::default(), 0.0), |acc, (&bi, x)| {
                (acc.0.add(Dd::of(bi).mul(x.0)), acc.1 + bi.abs() * x.1)
            });
        out.push((weight.sub(Dd::recip(g)), size + 1.0 / g));
        phi.push(p);
        gamma.push(g);
    }
    out
}

/// Every tree's defect up to `degree` vertices, with its allowance:
///
/// - rounding: the sum over every nonzero coefficient of `a` and `b` of the
///   defect's change when that coefficient moves by one unit in the last
///   place: what rounding the coefficients to doubles can do to a condition
///   they satisfy exactly;
/// - noise: each double-double operation rounds at `2^-104` relative to the
///   terms it combines; the elementary weight of a tree of `n` vertices is
///   reached along at most `n (S + n) + S + 2` of them (at each vertex a sum
///   over `S` stages and a product with at most `n` siblings, at the root
///   the sum over the `S` weights, then `1/gamma` and the difference); a
///   factor 8 on that count covers the worst-case accumulation (Higham,
///   Accuracy and Stability of Numerical Algorithms, 2002, 3.1), times the
///   sum of absolute values, which bounds every term.
pub(super) fn defects(a: &[Vec<f64>], b: &[f64], degree: usize) -> Vec<TreeDefect> {
    let t = trees(degree);
    let s = b.len();
    let base = weights(a, b, &t);
    let mut rounding = vec![0.0; base.len()];
    let mut add_change = |a: &[Vec<f64>], b: &[f64]| {
        for (r, (x, y)) in rounding.iter_mut().zip(weights(a, b, &t).iter().zip(&base)) {
            *r += x.0.sub(y.0).to_f64().abs();
        }
    };
    for i in 0..s {
        for j in 0..s {
            if let Some(w) = moved_one_ulp(a[i][j]) {
                let mut moved = a.to_vec();
                moved[i][j] = w;
                add_change(&moved, b);
            }
        }
        if let Some(w) = moved_one_ulp(b[i]) {
            let mut moved = b.to_vec();
            moved[i] = w;
            add_change(a, &moved);
        }
    }
    base.iter()
        .zip(&rounding)
        .enumerate()
        .map(|(n, ((d, size), r))| {
            let order = t.size[n];
            let units = UNIT * 8.0 * (order * (s + order) + s + 2) as f64;
            TreeDefect {
                tree: name(&t, n),
                defect: Defect {
                    degree: order,
                    value: d.to_f64().abs(),
                    allowance: r + units * size,
                    // 1/gamma: size includes it, and the weight is as large
                    scale: 1.0 / tree_density(&t, n),
                },
                signed: d.to_f64(),
            }
        })
        .collect()
}

/// `gamma(t)`: the tree's order times its subtrees' densities.
fn tree_density(t: &Trees, n: usize) -> f64 {
    t.children[n]
        .iter()
        .fold(t.size[n] as f64, |g, &c| g * tree_density(t, c))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The number of rooted trees with `n` vertices (OEIS A000081).
    #[test]
    fn the_trees_are_counted_and_named() {
        let t = trees(9);
        let counts: Vec<usize> = (1..=9)
            .map(|n| t.size.iter().filter(|&&s| s == n).count())
            .collect();
        assert_eq!(counts, [1, 1, 2, 4, 9, 20, 48, 115, 286]);
        let names: Vec<String> = (0..4).map(|n| name(&t, n)).collect();
        assert_eq!(names, ["τ", "[τ]", "[τ,τ]", "[[τ]]"]);
        let gammas: Vec<f64> = (0..4).map(|n| tree_density(&t, n)).collect();
        assert_eq!(gammas, [1.0, 2.0, 3.0, 6.0]);
    }
}

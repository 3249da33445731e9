//! The weights and nodes of a step, recovered from its moments.
//!
//! The probe ([`super::probe`]) reads the step's velocity moments
//! `mu_m = sum b_i c_i^m` for any `m`, each with its allowance. They are the
//! moments of a discrete measure: weight `b_i` at node `c_i` (stages at one
//! node merge, a stage of weight zero is invisible). `K` distinct nodes are
//! recovered from `mu_0 .. mu_(2K-1)` as the roots of the polynomial
//! `x^K + p_(K-1) x^(K-1) + ... + p_0` whose coefficients solve the Hankel
//! system `sum_j mu_(i+j) p_j = -mu_(i+K)` (`i < K`), and the weights from
//! the Vandermonde system `sum_i b_i c_i^m = mu_m` (`m < K`).
//!
//! How many nodes the moments resolve. The Hankel matrix `H_K` of a
//! measure with fewer than `K` nodes is singular; the measured one differs
//! from the exact by `dH`, whose entries are at most the moments'
//! allowances, and by Weyl's inequality its smallest singular value moves
//! by at most `|dH|_2 <= |dH|_F`. So a smallest singular value above
//! `|dH|_F` proves at least `K` nodes. The recovery stops at the first `K`
//! that is not proven, or at the stages counted, and reports the largest
//! `K` before it whose rule has real nodes: a method with more nodes than
//! that resolution shows is reported as resolved to its `K`, whose rule is
//! then the `K`-node rule matching its first `2K` moments.
//!
//! The nodes' and weights' bounds are first order: each moment moved by
//! its allowance in turn, the fit made again, the changes summed.

use super::probe::{free_flight, velocity_moment};
use crate::scheme::Scheme;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// A step's quadrature: distinct nodes `c_i` and their weights `b_i`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RecoveredQuadrature {
    /// `sum b_i c_i^m` for `m = 0, 1, ...` and their allowances, as
    /// measured.
    pub moments: Vec<[f64; 2]>,
    /// The number of distinct nodes the moments prove (see the module).
    pub resolved: usize,
    /// The stages counted: the most nodes there can be.
    pub stages: usize,
    /// The nodes, ascending.
    pub nodes: Vec<f64>,
    /// Their first-order bounds.
    pub node_bounds: Vec<f64>,
    /// The weights, in the nodes' order.
    pub weights: Vec<f64>,
    /// Their first-order bounds.
    pub weight_bounds: Vec<f64>,
}

impl RecoveredQuadrature {
    /// The rule in one line: `c = (0 +- 1e-9, 0.5 +- 1e-8, 1 +- 1e-9), b
    /// = (...)`, resolved nodes of stages.
    pub fn describe(&self) -> String {
        let list = |x: &[f64], bounds: &[f64]| {
            x.iter()
                .zip(bounds)
                .map(|(x, e)| format!("{} +- {e:.0e}", crate::wording::figure(*x)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        format!(
            "{} distinct nodes resolved of at most {} (from sum b_i c_i^m, m = 0 .. {}): \
             c = ({}), b = ({})",
            self.resolved,
            self.stages,
            self.moments.len() - 1,
            list(&self.nodes, &self.node_bounds),
            list(&self.weights, &self.weight_bounds)
        )
    }
}

/// Recovers the weights and nodes of `scheme`'s step from its moments (see
/// the module), as far as its stages and the moments' allowances allow.
/// `None` when the scheme cannot take the probe's step or no node is
/// resolved.
///
/// ```
/// use stepladder::scheme::Rk4;
/// use stepladder::study::recover_quadrature;
///
/// // RK4: Simpson's rule, 1/6, 2/3, 1/6 at 0, 1/2, 1
/// let rule = recover_quadrature::<_, 1>(&Rk4).unwrap();
/// assert_eq!(rule.resolved, 3);
/// assert!((rule.nodes[1] - 0.5).abs() <= rule.node_bounds[1] + 1e-12);
/// assert!((rule.weights[1] - 2.0 / 3.0).abs() <= rule.weight_bounds[1] + 1e-12);
/// ```
pub fn recover_quadrature<M: Scheme, const D: usize>(scheme: &M) -> Option<RecoveredQuadrature> {
    let (_, evaluations, units) = free_flight::<M, D>(scheme)?;
    // a start may evaluate the force once more than the step
    let stages = usize::try_from(evaluations).ok()?.max(1);
    let mut moments: Vec<[f64; 2]> = Vec::new();
    let mut best: Option<(usize, Fit)> = None;
    for k in 1..=stages {
        while moments.len() < 2 * k {
            let (value, allowance) = velocity_moment::<M, D>(scheme, moments.len() as u32, units)?;
            moments.push([value, allowance]);
        }
        if !resolves(&moments, k) {
            break;
        }
        // a rule with fewer nodes than the measure may have complex ones
        // (Forest-Ruth's four kicks give no real three-node rule): go on
        if let Some(f) = fit(&moments, k) {
            best = Some((k, f));
        }
    }
    let (resolved, rule) = best?;
    moments.truncate(2 * resolved);
    let (node_bounds, weight_bounds) = bounds(&moments, resolved, &rule);
    Some(RecoveredQuadrature {
        moments,
        resolved,
        stages,
        nodes: rule.nodes,
        node_bounds,
        weights: rule.weights,
        weight_bounds,
    })
}

#[derive(Clone, Debug)]
struct Fit {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

fn hankel(moments: &[[f64; 2]], k: usize, column: usize) -> DMatrix<f64> {
    DMatrix::from_fn(k, k, |i, j| moments[i + j][column])
}

/// The measured `H_K`'s smallest singular value exceeds `|dH|_F`.
fn resolves(moments: &[[f64; 2]], k: usize) -> bool {
    let smallest = hankel(moments, k, 0).singular_values().min();
    smallest > hankel(moments, k, 1).norm()
}

/// The `k`-node rule with the first `2k` moments; `None` for a singular
/// system or roots off the real line by more than their size allows.
fn fit(moments: &[[f64; 2]], k: usize) -> Option<Fit> {
    let rhs = DVector::from_fn(k, |i, _| -moments[i + k][0]);
    let p = hankel(moments, k, 0).lu().solve(&rhs)?;
    // the companion matrix of x^k + p_(k-1) x^(k-1) + ... + p_0
    let companion = DMatrix::from_fn(k, k, |i, j| {
        if j == k - 1 {
            -p[i]
        } else if i == j + 1 {
            1.0
        } else {
            0.0
        }
    });
    let roots = companion.complex_eigenvalues();
    let mut nodes: Vec<f64> = roots.iter().map(|z| z.re).collect();
    let largest = nodes.iter().fold(1.0f64, |a, x| a.max(x.abs()));
    // complex pairs are no nodes; their imaginary parts would be rounding
    // only at a fraction of the moments' resolution
    if roots.iter().any(|z| z.im.abs() > 1e-6 * largest) {
        return None;
    }
    nodes.sort_by(f64::total_cmp);
    let vandermonde = DMatrix::from_fn(k, k, |m, i| nodes[i].powi(m as i32));
    let mu = DVector::from_fn(k, |m, _| moments[m][0]);
    let weights = vandermonde.lu().solve(&mu)?;
    Some(Fit {
        nodes,
        weights: weights.iter().copied().collect(),
    })
}

/// First-order bounds: the sum over the moments of the change each makes
/// when moved by its allowance (infinite where a moved fit fails).
fn bounds(moments: &[[f64; 2]], k: usize, rule: &Fit) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; k];
    let mut weights = vec![0.0; k];
    for m in 0..2 * k {
        let mut moved = moments.to_vec();
        moved[m][0] += moved[m][1];
        match fit(&moved, k) {
            Some(f) => {
                for i in 0..k {
                    nodes[i] += (f.nodes[i] - rule.nodes[i]).abs();
                    weights[i] += (f.weights[i] - rule.weights[i]).abs();
                }
            }
            None => {
                nodes.fill(f64::INFINITY);
                weights.fill(f64::INFINITY);
            }
        }
    }
    (nodes, weights)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scheme::{EULER_CROMER, FOREST_RUTH, Flow, VELOCITY_VERLET};

    /// Exact moments of a rule, with an allowance.
    fn moments_of(nodes: &[f64], weights: &[f64], count: usize, allowance: f64) -> Vec<[f64; 2]> {
        (0..count)
            .map(|m| {
                let mu = nodes
                    .iter()
                    .zip(weights)
                    .map(|(c, b)| b * c.powi(m as i32))
                    .sum();
                [mu, allowance]
            })
            .collect()
    }

    #[test]
    fn a_rule_is_resolved_to_its_number_of_nodes_and_no_further() {
        let (c, b) = ([0.0, 0.3, 0.8, 1.0], [0.1, 0.4, 0.3, 0.2]);
        let moments = moments_of(&c, &b, 10, 1e-12);
        for k in 1..=4 {
            assert!(resolves(&moments, k), "{k} nodes");
        }
        // five nodes of a four-node measure: H_5 is singular
        assert!(!resolves(&moments, 5));
        let rule = fit(&moments, 4).unwrap();
        let (node_bounds, weight_bounds) = bounds(&moments, 4, &rule);
        for i in 0..4 {
            assert!((rule.nodes[i] - c[i]).abs() <= node_bounds[i] + 1e-14);
            assert!((rule.weights[i] - b[i]).abs() <= weight_bounds[i] + 1e-14);
            assert!(node_bounds[i] < 1e-6 && weight_bounds[i] < 1e-6);
        }
    }

    /// Forest-Ruth's four kicks over half a step: nodes (1 - x)/2, 0, 1/2,
    /// x/2 (x = 1/(2 - 2^(1/3))) with weights -0.18, 0.68, 0.68, -0.18. The
    /// three-node rule with their first six moments has the nodes 1/4 and
    /// 1/4 +- 0.55 i, which is no rule; the four-node one is theirs.
    #[test]
    fn a_rule_with_complex_nodes_is_refused() {
        let x = 1.0 / (2.0 - 2f64.cbrt());
        let c = [(1.0 - x) / 2.0, 0.0, 0.5, x / 2.0];
        let b = [(1.0 - x) / 2.0, x / 2.0, x / 2.0, (1.0 - x) / 2.0];
        let moments = moments_of(&c, &b, 8, 1e-13);
        assert!(resolves(&moments, 3) && resolves(&moments, 4));
        assert!(fit(&moments, 3).is_none());
        let rule = fit(&moments, 4).unwrap();
        assert!((rule.nodes[0] - c[0]).abs() < 1e-9, "{rule:?}");
    }

    #[test]
    fn splittings_show_their_kicks() {
        // velocity Verlet: kicks 1/2 at 0 and 1
        let verlet = recover_quadrature::<_, 1>(&VELOCITY_VERLET).unwrap();
        assert_eq!(verlet.resolved, 2, "{}", verlet.describe());
        for (x, want) in verlet.nodes.iter().zip([0.0, 1.0]) {
            assert!((x - want).abs() < 1e-6, "{}", verlet.describe());
        }
        // Euler-Cromer: one kick of 1 at 0
        let cromer = recover_quadrature::<_, 1>(&EULER_CROMER).unwrap();
        assert_eq!(cromer.resolved, 1, "{}", cromer.describe());
        assert!(cromer.nodes[0].abs() < 1e-9 && (cromer.weights[0] - 1.0).abs() < 1e-9);
        // Forest-Ruth: each kick at the drifts' sum before it
        let mut want: Vec<(f64, f64)> = Vec::new();
        let mut at = 0.0;
        for (flow, weight) in FOREST_RUTH.sequence() {
            match flow {
                Flow::Drift => at += weight,
                Flow::Kick => want.push((at, weight)),
            }
        }
        want.sort_by(|x, y| x.0.total_cmp(&y.0));
        let fr = recover_quadrature::<_, 1>(&FOREST_RUTH).unwrap();
        assert_eq!(fr.resolved, want.len(), "{}", fr.describe());
        for (i, (c, b)) in want.iter().enumerate() {
            assert!(
                (fr.nodes[i] - c).abs() <= fr.node_bounds[i] + 1e-12
                    && (fr.weights[i] - b).abs() <= fr.weight_bounds[i] + 1e-12,
                "{}: want ({c}, {b})",
                fr.describe()
            );
        }
    }
}

//! The condition probe on black boxes whose tableau is known: the condition
//! it names, and its defect, must be the tableau's own, computed here from
//! the coefficients directly, in `f64` and in `f32`.

use std::ops::{Add, Mul};
use stepladder::prelude::*;
use stepladder::scene::KeplerCircular;
use stepladder::scheme::Float;
use stepladder::study::{
    ConditionProbe, OrderSpec, RecoveredQuadrature, global_order, probe_conditions,
    recover_quadrature,
};

/// An explicit Runge-Kutta tableau: `a` strictly lower triangular, row by
/// row, and the weights `b`.
struct Tableau {
    a: &'static [&'static [f64]],
    b: &'static [f64],
}

impl Tableau {
    /// The nodes an autonomous problem sees: the row sums of `a`.
    fn nodes(&self) -> Vec<f64> {
        self.a.iter().map(|row| row.iter().sum()).collect()
    }

    /// `sum b_i c_i^m - 1/(m+1)`, with `c` the row sums.
    fn bushy_defect(&self, m: i32) -> f64 {
        let c = self.nodes();
        self.b
            .iter()
            .zip(&c)
            .map(|(b, c)| b * c.powi(m))
            .sum::<f64>()
            - 1.0 / f64::from(m + 1)
    }

    /// `sum b_bar_i c_i^m - 1/((m+1)(m+2))`, with `b_bar = b A`.
    fn position_defect(&self, m: i32) -> f64 {
        let c = self.nodes();
        let b_bar = (0..self.b.len()).map(|j| {
            (j + 1..self.b.len())
                .map(|i| self.b[i] * self.a[i][j])
                .sum::<f64>()
        });
        b_bar.zip(&c).map(|(b, c)| b * c.powi(m)).sum::<f64>() - 1.0 / f64::from((m + 1) * (m + 2))
    }
}

/// One step of `tableau` on `y = [q, v]`, `y' = [v, a(q)]`, in `T`.
fn runge_kutta<T>(tableau: &Tableau, q: &mut [T], v: &mut [T], h: T, force: &Force<T>)
where
    T: Float + Add<Output = T> + Mul<Output = T>,
{
    let n = q.len();
    let stages = tableau.b.len();
    let (mut kq, mut kv) = ([[T::default(); 2]; 16], [[T::default(); 2]; 16]);
    for i in 0..stages {
        let (mut x, mut u) = ([T::default(); 2], [T::default(); 2]);
        for d in 0..n {
            x[d] = q[d];
            u[d] = v[d];
            for j in 0..i {
                let w = h * T::from_f64(tableau.a[i][j]);
                x[d] = x[d] + w * kq[j][d];
                u[d] = u[d] + w * kv[j][d];
            }
        }
        kq[i][..n].copy_from_slice(&u[..n]);
        force(&x[..n], &mut kv[i][..n]);
    }
    for d in 0..n {
        for i in 0..stages {
            let w = h * T::from_f64(tableau.b[i]);
            q[d] = q[d] + w * kq[i][d];
            v[d] = v[d] + w * kv[i][d];
        }
    }
}

const RK4: Tableau = Tableau {
    a: &[&[], &[0.5], &[0.0, 0.5], &[0.0, 0.0, 1.0]],
    b: &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
};

/// Dormand and Prince's 5(4) stages with the embedded fourth-order weights
/// in place of the fifth-order ones.
const DOPRI_EMBEDDED: Tableau = Tableau {
    a: &[
        &[],
        &[1.0 / 5.0],
        &[3.0 / 40.0, 9.0 / 40.0],
        &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
        &[
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
        ],
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
        &[
            35.0 / 384.0,
            0.0,
            500.0 / 1113.0,
            125.0 / 192.0,
            -2187.0 / 6784.0,
            11.0 / 84.0,
        ],
    ],
    b: &[
        5179.0 / 57600.0,
        0.0,
        7571.0 / 16695.0,
        393.0 / 640.0,
        -92097.0 / 339200.0,
        187.0 / 2100.0,
        1.0 / 40.0,
    ],
};

/// RK4 with its third row `a32 = 1/2 + 1e-4`: the third stage sits at
/// `c3 = 1/2 + 1e-4`, so `sum b c = 1/2 + 1e-4 / 3`.
const RK4_ROW_OFF: Tableau = Tableau {
    a: &[&[], &[0.5], &[0.0, 0.5 + 1e-4], &[0.0, 0.0, 1.0]],
    b: &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
};

fn meta(id: &'static str, order: u32, stages: u32) -> SchemeMeta {
    SchemeMeta::new(id, id, order).force_evaluations(stages)
}

fn probe64(tableau: &'static Tableau, order: u32, through: u32) -> ConditionProbe {
    let stages = tableau.b.len() as u32;
    let scheme = BlackBox::new(meta("rk-f64", order, stages), |q, v, h, f| {
        runge_kutta::<f64>(tableau, q, v, h, f)
    });
    probe_conditions::<_, 2>(&scheme, through).unwrap()
}

fn probe32(tableau: &'static Tableau, order: u32, through: u32) -> ConditionProbe {
    let stages = tableau.b.len() as u32;
    let scheme = BlackBox::new(meta("rk-f32", order, stages), |q, v, h, f| {
        runge_kutta::<f32>(tableau, q, v, h, f)
    });
    probe_conditions::<_, 2>(&scheme, through).unwrap()
}

/// The named condition is `sum b_i c_i^m = 1/(m+1)` and its defect is the
/// tableau's within the probe's allowance.
fn names_bushy(probe: &ConditionProbe, m: i32, expected: f64) {
    let first = probe
        .first_violated()
        .unwrap_or_else(|| panic!("{}", probe.describe()));
    let power = match m {
        1 => " c_i".to_string(),
        _ => format!(" c_i^{m}"),
    };
    assert_eq!(first.condition, format!("sum b_i{power} = 1/{}", m + 1));
    assert_eq!(first.order, (m + 1) as u32);
    assert!(
        (first.defect - expected).abs() <= first.allowance,
        "{}: expected a defect of {expected:e}",
        first.describe()
    );
}

#[test]
fn a_correct_tableau_holds_every_probed_condition_in_both_precisions() {
    for probe in [probe64(&RK4, 4, 4), probe32(&RK4, 4, 4)] {
        assert!(probe.first_violated().is_none(), "{}", probe.describe());
    }
    // single precision's allowance is the larger by about (eps_32 /
    // eps_64)^(2/3) = 6.6e5 for a first difference
    let wide = probe32(&RK4, 4, 4).conditions[2].allowance;
    let narrow = probe64(&RK4, 4, 4).conditions[2].allowance;
    assert!(wide > 1e4 * narrow, "{wide:e} against {narrow:e}");
}

#[test]
fn rk4_fails_first_the_fifth_order_bushy_condition_by_its_own_defect() {
    let expected = RK4.bushy_defect(4);
    assert!((expected - 1.0 / 120.0).abs() < 1e-15); // 5/24 - 1/5
    names_bushy(&probe64(&RK4, 4, 5), 4, expected);
    names_bushy(&probe32(&RK4, 4, 5), 4, expected);
}

#[test]
fn embedded_weights_in_place_of_the_fifth_order_ones_are_named() {
    // the fourth-order conditions hold, the first of the fifth fails
    let expected = DOPRI_EMBEDDED.bushy_defect(4);
    assert!((1e-4..1e-3).contains(&-expected), "{expected:e}");
    names_bushy(&probe64(&DOPRI_EMBEDDED, 5, 5), 4, expected);
    // In single precision the allowance (6e-4 or so) is of the size of the
    // defects: no condition of order 4 or less may fail, and both bushy
    // conditions of order 5 must read the tableau's values.
    let single = probe32(&DOPRI_EMBEDDED, 5, 5);
    assert!(single.holds_through() >= 4, "{}", single.describe());
    let read = |text: &str| {
        single
            .conditions
            .iter()
            .find(|c| c.condition == text)
            .unwrap()
    };
    for (condition, defect) in [
        (read("sum b_i c_i^4 = 1/5"), expected),
        (
            read("sum b_bar_i c_i^3 = 1/20"),
            DOPRI_EMBEDDED.position_defect(3),
        ),
    ] {
        assert!(
            (condition.defect - defect).abs() <= condition.allowance,
            "{}: the tableau's is {defect:e}",
            condition.describe()
        );
    }
}

#[test]
fn a_row_sum_off_its_node_is_named_at_order_two() {
    let expected = RK4_ROW_OFF.bushy_defect(1);
    assert!((expected - 1e-4 / 3.0).abs() < 1e-12);
    names_bushy(&probe64(&RK4_ROW_OFF, 4, 4), 1, expected);
}

/// A composition of velocity Verlet steps with weights `w`, on `f64`
/// slices: consistent only if the weights sum to 1.
fn composed(weights: &'static [f64]) -> impl Fn(&mut [f64], &mut [f64], f64, &Force<f64>) {
    move |q, v, h, force| {
        let n = q.len();
        let mut a = [0.0; 2];
        for w in weights {
            force(q, &mut a[..n]);
            for d in 0..n {
                v[d] += 0.5 * w * h * a[d];
                q[d] += w * h * v[d];
            }
            force(q, &mut a[..n]);
            for d in 0..n {
                v[d] += 0.5 * w * h * a[d];
            }
        }
    }
}

#[test]
fn weights_that_do_not_sum_to_one_are_named_as_inconsistency() {
    const W: &[f64] = &[0.7, -0.3, 0.7];
    let scheme = BlackBox::new(meta("short-composition", 4, 6), composed(W));
    let probe = probe_conditions::<_, 2>(&scheme, 4).unwrap();
    let first = probe.first_violated().unwrap();
    assert_eq!((first.order, first.condition.as_str()), (1, "consistency"));
    assert!((first.measured - 1.1).abs() < 1e-14, "{}", first.describe());
    assert!(
        first
            .describe()
            .contains("fails: the step advances positions by 1.1")
    );
    // and the order study's failure names it
    let record = global_order(&scheme, &KeplerCircular, &OrderSpec::default()).unwrap();
    assert!(!record.passed());
    assert!(
        record
            .reason
            .contains("consistency fails: the step advances positions by 1.1"),
        "{}",
        record.reason
    );
}

#[test]
fn a_step_rounded_to_single_precision_is_inconsistent_in_double() {
    // the step's size in f32, the rest in f64: W = fl32(h) / h
    let scheme = BlackBox::new(meta("verlet-f32-h", 2, 2), |q, v, h: f64, force| {
        composed(&[1.0])(q, v, f64::from(h as f32), force)
    });
    let probe = probe_conditions::<_, 2>(&scheme, 2).unwrap();
    let first = probe.first_violated().unwrap();
    let h = probe.h;
    assert_eq!(first.condition, "consistency");
    assert!((first.defect - (f64::from(h as f32) / h - 1.0)).abs() <= first.allowance);
}

/// The distinct nodes of `tableau` with a nonzero weight, and the weights
/// summed over the stages that share a node, ascending.
fn rule_of(tableau: &Tableau) -> Vec<(f64, f64)> {
    let mut rule: Vec<(f64, f64)> = Vec::new();
    for (c, b) in tableau.nodes().into_iter().zip(tableau.b) {
        match rule.iter_mut().find(|(x, _)| (x - c).abs() < 1e-12) {
            Some((_, w)) => *w += b,
            None => rule.push((c, *b)),
        }
    }
    rule.retain(|(_, b)| *b != 0.0);
    rule.sort_by(|x, y| x.0.total_cmp(&y.0));
    rule
}

#[test]
fn the_weights_and_nodes_of_a_black_box_are_recovered_from_its_moments() {
    for (tableau, name) in [(&RK4, "rk4"), (&DOPRI_EMBEDDED, "dopri-embedded")] {
        let stages = tableau.b.len() as u32;
        let scheme = BlackBox::new(meta(name, 4, stages), |q, v, h, f| {
            runge_kutta::<f64>(tableau, q, v, h, f)
        });
        let recovered = recover_quadrature::<_, 2>(&scheme).unwrap();
        let want = rule_of(tableau);
        // Dormand-Prince: 7 stages, 5 nodes of nonzero weight (b2 = 0, and
        // c6 = c7 = 1 merge)
        recovers(&recovered, &want);
    }
}

/// `recovered` resolves every node of `want` and holds each node and weight
/// within its bounds.
fn recovers(recovered: &RecoveredQuadrature, want: &[(f64, f64)]) {
    assert_eq!(recovered.resolved, want.len(), "{}", recovered.describe());
    for (i, (c, b)) in want.iter().enumerate() {
        assert!(
            (recovered.nodes[i] - c).abs() <= recovered.node_bounds[i]
                && (recovered.weights[i] - b).abs() <= recovered.weight_bounds[i],
            "{}: want ({c}, {b})",
            recovered.describe()
        );
    }
}

#[test]
fn single_precision_resolves_simpsons_rule_within_its_wider_bounds() {
    let scheme = BlackBox::new(meta("rk4-f32", 4, 4), |q, v, h, f| {
        runge_kutta::<f32>(&RK4, q, v, h, f)
    });
    let recovered = recover_quadrature::<_, 2>(&scheme).unwrap();
    recovers(&recovered, &rule_of(&RK4));
}

#[test]
fn a_probe_that_finds_nothing_says_so_and_how_far_it_looked() {
    let probe = probe64(&RK4, 4, 4);
    assert_eq!(probe.h, 0.9);
    // a black box's start evaluates nothing: the four stages of one step
    assert_eq!(probe.evaluations, 4);
    assert_eq!(probe.holds_through(), 4);
    // consistency, then per order the velocity's and the position's bushy
    // condition, and the chain conditions at orders 3 and 4: 1 + 1 + 2 + 3 + 3
    assert_eq!(probe.conditions.len(), 10);
    assert!(
        probe.describe().contains(
            "the 10 bushy and chain conditions through order 4 hold, so the fault lies in a \
             condition they do not separate"
        ),
        "{}",
        probe.describe()
    );
    assert!(
        probe.conditions[0]
            .describe()
            .starts_with("consistency holds: the step advances positions by 1.0")
    );
    assert!(
        probe.conditions[1]
            .describe()
            .starts_with("order 1 condition sum b_i = 1 holds, off by")
    );
    let beyond = probe64(&RK4, 4, 5);
    assert_eq!(beyond.holds_through(), 4);
    assert!(beyond.describe().starts_with(
        "probing the first step from a synchronised state: order 5 condition sum b_i c_i^4 = 1/5 fails by 8.3e-3"
    ));
}

#[test]
fn a_step_that_cannot_be_probed_gives_no_probe() {
    let panics = BlackBox::new(
        meta("panics", 2, 1),
        |_: &mut [f64], _: &mut [f64], _: f64, _: &Force<f64>| {
            if true {
                panic!("no step today")
            }
        },
    );
    assert!(probe_conditions::<_, 1>(&panics, 2).is_none());
    assert!(recover_quadrature::<_, 1>(&panics).is_none());
    let overflows = BlackBox::new(
        meta("overflows", 2, 1),
        |q: &mut [f64], _: &mut [f64], _: f64, _: &Force<f64>| {
            q[0] = f64::NAN;
        },
    );
    assert!(probe_conditions::<_, 1>(&overflows, 2).is_none());
    // a multistep scheme's first step from a synchronised state is its
    // starter, not its method
    assert!(probe_conditions::<_, 1>(&stepladder::scheme::QUINLAN_TREMAINE8, 8).is_none());
}

#[test]
fn a_recovered_rule_says_how_many_nodes_it_resolved_of_how_many() {
    let scheme = BlackBox::new(meta("rk4-f64", 4, 4), |q, v, h, f| {
        runge_kutta::<f64>(&RK4, q, v, h, f)
    });
    let rule = recover_quadrature::<_, 2>(&scheme).unwrap();
    assert_eq!((rule.resolved, rule.stages, rule.moments.len()), (3, 4, 6));
    assert!(
        rule.describe().starts_with(
            "3 distinct nodes resolved of at most 4 (from sum b_i c_i^m, m = 0 .. 5): c = ("
        ),
        "{}",
        rule.describe()
    );
}

/// RK4 with `b1` larger by 1.5e-9: `sum b = 1 + 1.5e-9`.
const RK4_WEIGHT_OFF: Tableau = Tableau {
    a: RK4.a,
    b: &[1.0 / 6.0 + 1.5e-9, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
};

/// RK4 with its third row moved along its own row sum, `a31 = -6e-9`,
/// `a32 = 1/2 + 6e-9`: every node stays, and `sum b_i a_ij c_j` (for a
/// first-order method both the chain condition `sum b_i a_bar_ij` and `sum
/// b_bar_i c_i`) moves by `b3 (6e-9 c2 - 6e-9 c1) = 6e-9 / 6 = 1e-9`.
const RK4_CHAIN_OFF: Tableau = Tableau {
    a: &[&[], &[0.5], &[-6e-9, 0.5 + 6e-9], &[0.0, 0.0, 1.0]],
    b: RK4.b,
};

/// The probe resolves defects of 1e-9, several allowances: `sum b = 1`
/// (allowance about 4e-10 for four evaluations in `f64`) and the order-3
/// chain condition (about 2e-11: its differences are taken from a state at
/// rest, whose velocity is of the force's size).
#[test]
fn defects_of_a_billionth_are_resolved() {
    let weight = probe64(&RK4_WEIGHT_OFF, 4, 4);
    let sum = weight
        .conditions
        .iter()
        .find(|c| c.condition == "sum b_i = 1")
        .unwrap();
    assert!(
        !sum.holds() && (sum.defect - 1.5e-9).abs() <= sum.allowance,
        "{}",
        sum.describe()
    );
    let chain = probe64(&RK4_CHAIN_OFF, 4, 4);
    for text in ["sum b_i a_bar_ij = 1/6", "sum b_bar_i c_i = 1/6"] {
        let c = chain
            .conditions
            .iter()
            .find(|c| c.condition == text)
            .unwrap();
        assert!(
            !c.holds() && (c.defect - 1e-9).abs() <= c.allowance,
            "{}",
            c.describe()
        );
    }
    // and nothing else of order 3 or less moves
    assert_eq!(
        chain.first_violated().unwrap().order,
        3,
        "{}",
        chain.describe()
    );
}

/// Every allowance holds at least what the derivation in
/// `probe_conditions` puts in it: the rounding of the differences at `c/2`
/// plus two thirds of the roundings at `c` and `c/2` that the truncation
/// estimate carries. With `units = (n + 1) eps` and a probed value `y`, the
/// rounding of a first difference at `c/2` is `units |2 y| / c` and at `c`
/// half that, so the allowance is at least `2 units |2 y| / c`; `y` is the
/// velocity, about 1, or the position, about `h`, and `c = units^(1/3)`.
/// For the chain conditions (second differences, `c = units^(1/4)`): from
/// rest the velocity is about `c h` at `c` (at least `4 units h / c`), the
/// position about 1 (at least `(11/6) 8 units / c^2`). Each is scaled by
/// `h^-order`, as its condition is.
#[test]
fn every_allowance_covers_the_rounding_of_its_differences() {
    let probe = probe64(&RK4, 4, 8);
    let units = 5.0 * f64::EPSILON; // four evaluations, one drift
    let h = probe.h;
    let (first, second) = (units.powf(1.0 / 3.0), units.powf(0.25));
    for c in &probe.conditions {
        let scale = h.powi(c.order as i32);
        let floor = match c.condition.as_str() {
            "consistency" => units,
            "sum b_i a_bar_ij = 1/6" => 4.0 * units * h / second / scale,
            "sum b_bar_i a_bar_ij = 1/24" => 11.0 / 6.0 * 8.0 * units / (second * second) / scale,
            text if text.starts_with("sum b_bar_i") => 4.0 * units * h / first / scale,
            _ => 4.0 * units / first / scale,
        };
        assert!(
            c.allowance >= floor * (1.0 - 1e-6),
            "{}: the derivation's floor is {floor:.3e}",
            c.describe()
        );
    }
    // consistency's allowance grows with the advance it measures: a
    // composition advancing by 1.1 h, three Verlet steps of two
    // evaluations each
    let scheme = BlackBox::new(meta("long-composition", 4, 6), composed(&[0.7, -0.3, 0.7]));
    let consistency = &probe_conditions::<_, 1>(&scheme, 1).unwrap().conditions[0];
    assert!(consistency.allowance >= 7.0 * f64::EPSILON * 1.1 * (1.0 - 1e-6));
}

/// The order study probes a failed claim only: a pass carries no probe, and
/// a breakdown (a step that panics below h = 1e-2, which the probe's step
/// of 0.9 would not meet) is reported as such, unprobed.
#[test]
fn only_a_failed_claim_without_a_breakdown_is_probed() {
    use stepladder::scene::Harmonic;
    let pass = global_order(
        &stepladder::scheme::VELOCITY_VERLET,
        &Harmonic::default(),
        &OrderSpec::default(),
    )
    .unwrap();
    assert!(pass.passed() && pass.probe.is_none(), "{}", pass.reason);
    assert!(!pass.reason.contains("probing"), "{}", pass.reason);
    let breaks = BlackBox::new(meta("breaks-below-1e-2", 2, 2), |q, v, h: f64, force| {
        assert!(h >= 1e-2, "a step of {h} is too small");
        composed(&[1.0])(q, v, h, force)
    });
    let record = global_order(&breaks, &Harmonic::default(), &OrderSpec::default()).unwrap();
    assert!(
        record.breakdown.is_some() && record.probe.is_none(),
        "{}",
        record.reason
    );
}

//! The order conditions of a scheme's one-step map, read off the step itself.
//!
//! [`crate::conditions`] checks a table; a black box has none to read. But
//! every one-step method for `q'' = a(q)` that uses the force only through
//! evaluations is, in its expansion in powers of `h`, a Runge-Kutta-Nyström
//! method: weights `b` (velocity), `b_bar` (position), nodes `c` and
//! coefficients `a_bar` (first-order Runge-Kutta methods included, with
//! `b_bar = b A`, `a_bar = A^2` and `c` the row sums of `A`; splittings
//! with `b` the kicks and `c` the drifts before each). Polynomial forces
//! give conditions separate signatures:
//!
//! All in `D` dimensions along the diagonal: every coordinate of the state
//! is the same `q` (or `v`), the force is `a_i = c qbar^m` with `qbar` the
//! coordinates' mean, and what is read is the mean of `q1` or `v1`. The
//! exact flow keeps the coordinates equal, so a step that treats one
//! coordinate differently (a kick missed on the last) shows in the mean.
//!
//! - **free flight** (`a = 0`) from `q = 0`, `v = 1`: `q1 = W h`, and
//!   consistency is `W = 1` (the step advances positions by `h v`);
//! - **`a = c q^m`** from `q = 0`, `v = 1`: every
//!   stage sits at `Q_i = c_i h + O(c)`, so the part of the step linear in
//!   the force's strength `c` is `v1 - 1 = c h^(m+1) sum b_i c_i^m` and
//!   `q1 - W h = c h^(m+2) sum b_bar_i c_i^m`, against the flow's
//!   `h^(m+1)/(m+1)` and `h^(m+2)/((m+1)(m+2))`: the bushy conditions,
//!   `sum b c^m = 1/(m+1)` of order `m+1` and `sum b_bar c^m =
//!   1/((m+1)(m+2))` of order `m+2`;
//! - **`a = c q`** from `q = 1`, `v = 0`: the part quadratic in `c` is
//!   `c^2 h^3 sum b_i a_bar_ij` in `v1` and `c^2 h^4 sum b_bar_i a_bar_ij`
//!   in `q1`, against `1/6` and `1/24` (the flow is `cosh`): the chain
//!   conditions of orders 3 and 4, where one force acts on another.
//!
//! Each part is taken from the step run at `+-c` by central differences,
//! with `c` chosen where truncation and rounding balance (see
//! [`probe_conditions`]). The step is `h = 0.9`: no binary float of fewer
//! than 53 bits holds it exactly, so a step rounded to a narrower type shows
//! as a consistency defect, and it is close enough to 1 that dividing the
//! `h^(m+1)` out does not magnify rounding much.
//!
//! What the probes cannot separate: conditions of the other Nyström trees
//! from order 4 on (`sum b_i c_i a_bar_ij`, ...), whose forces act on each
//! other in more than a chain. A scheme failing its order with every probed
//! condition holding has its defect there.

use crate::run::caught;
use crate::scene::{Counted, Scene, SceneMeta};
use crate::scheme::Scheme;
use crate::state::{Real, State};
use crate::wording::figure;
use nalgebra::SVector;
use serde::Serialize;

/// The step every probe takes (see the module's text).
pub const PROBE_STEP: f64 = 0.9;

/// One order condition of the one-step map, measured through the step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ProbedCondition {
    /// The lowest order that needs the condition.
    pub order: u32,
    /// The condition in Nyström notation (`sum b_i c_i^2 = 1/3`), or
    /// `consistency` for the position's advance in free flight.
    pub condition: String,
    /// The method's value of the condition's sum.
    pub measured: f64,
    /// The exact flow's value.
    pub exact: f64,
    /// `measured - exact`.
    pub defect: f64,
    /// The most rounding and the truncation of the differences can explain:
    /// a condition that holds has `|defect| <= allowance`.
    pub allowance: f64,
}

impl ProbedCondition {
    /// The defect lies within what rounding and truncation explain.
    pub fn holds(&self) -> bool {
        self.defect.abs() <= self.allowance
    }

    /// The condition and its defect in words: "consistency fails: the step
    /// advances positions by 0.2031 h" or "order 5 condition sum b_i c_i^4
    /// = 1/5 fails by -2.63e-4 (allowance 1.0e-9)".
    pub fn describe(&self) -> String {
        if self.condition == CONSISTENCY {
            format!(
                "consistency{}: the step advances positions by {} h in free flight (defect \
                 {:.1e}, allowance {:.1e})",
                if self.holds() { " holds" } else { " fails" },
                significant_digits(self.measured, self.defect, self.allowance),
                self.defect,
                self.allowance
            )
        } else {
            format!(
                "order {} condition {} {} by {:.1e} (allowance {:.1e})",
                self.order,
                self.condition,
                if self.holds() { "holds, off" } else { "fails" },
                self.defect,
                self.allowance
            )
        }
    }
}

/// `measured` with the digits its defect needs to show: enough that the
/// printed value differs from 1 where the defect exceeds the allowance.
fn significant_digits(measured: f64, defect: f64, allowance: f64) -> String {
    let resolve = defect.abs().max(allowance).max(f64::MIN_POSITIVE);
    let decimals = (-resolve.log10()).ceil().clamp(1.0, 16.0) as usize;
    format!("{measured:.decimals$}")
}

const CONSISTENCY: &str = "consistency";

/// Every condition probed, lowest order first.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ConditionProbe {
    /// The step of every probe.
    pub h: f64,
    /// Force evaluations of one start and step, counted: the rounding
    /// model's number of operations on the state (see [`probe_conditions`]).
    pub evaluations: u64,
    /// The conditions, by order, consistency first.
    pub conditions: Vec<ProbedCondition>,
}

impl ConditionProbe {
    /// The first condition, in order, that fails.
    pub fn first_violated(&self) -> Option<&ProbedCondition> {
        self.conditions.iter().find(|c| !c.holds())
    }

    /// The highest order through which every probed condition holds.
    pub fn holds_through(&self) -> u32 {
        match self.first_violated() {
            Some(c) => c.order - 1,
            None => self.conditions.iter().map(|c| c.order).max().unwrap_or(0),
        }
    }

    /// One sentence for a failure message: the first violated condition,
    /// or that every probed one holds.
    pub fn describe(&self) -> String {
        match self.first_violated() {
            Some(c) => format!(
                "probing the first step from a synchronised state: {}",
                c.describe()
            ),
            None => format!(
                "probing the first step from a synchronised state: the {} bushy and chain \
                 conditions through order {} hold, so the fault lies in a condition they do not \
                 separate or in what the probe forces do not exercise",
                self.conditions.len(),
                self.holds_through()
            ),
        }
    }
}

/// Probes the order conditions of `scheme`'s one-step map through order
/// `through`, on the `D`-dimensional probe forces (the scheme's own
/// dimension, so that an adapter of fixed size fits).
///
/// The rounding model: one start and step of `n` counted force evaluations
/// rounds the state at most `n + 1` times (once per kick or stage and once
/// for the drift), each by at most one unit `eps` of the step's arithmetic
/// ([`Scheme::epsilon`]) of the state's size, so a probed value carries at
/// most `rho = (n + 1) eps |y|`. A central difference at `+-c` divides it
/// by `c` (first differences) or `c^2` (second), while truncation leaves
/// `t c^2`: `c = rho_1^(1/3)` and `rho_1^(1/4)` (`rho_1 = (n + 1) eps`)
/// balance the two. The truncation is measured, not assumed: with `D(c) =
/// a + t c^2 + s c^4 + ...`, the differences at `c` and `c/2` differ by
/// `3 t c^2 / 4`, so a third of their gap (plus its rounding) estimates the
/// truncation `t c^2 / 4` at `c/2` to leading order. That estimate is off
/// by the next term, `s c^4`, which is no larger than the leading one while
/// `|s / t| <= c^-2`: `c^-2` is at least `6e2` (second differences in
/// `f32` with up to 20 evaluations; `1e7` in `f64`), while `s / t` is of
/// the size of `h^4` over a product of integers, below 1 (the flow's own
/// expansion in `c` has terms in `(c h^2)^j / (2j)!`). So the allowance
/// takes the estimate twice, on top of the rounding at `c/2`.
///
/// `None` when the scheme cannot take the probe's step (a failure, a panic,
/// a non-finite state), or is a multistep scheme, whose one step from a
/// synchronised state is its starter, not its method.
///
/// ```
/// use stepladder::study::probe_conditions;
/// use stepladder::scheme::{Rk4, VELOCITY_VERLET};
///
/// let probe = probe_conditions::<_, 1>(&Rk4, 4).unwrap();
/// assert!(probe.first_violated().is_none(), "{}", probe.describe());
/// // velocity Verlet is of order 2: its order-3 conditions fail
/// let verlet = probe_conditions::<_, 1>(&VELOCITY_VERLET, 3).unwrap();
/// assert_eq!(verlet.first_violated().unwrap().order, 3);
/// ```
pub fn probe_conditions<M: Scheme, const D: usize>(
    scheme: &M,
    through: u32,
) -> Option<ConditionProbe> {
    let h = PROBE_STEP;
    let moving = probe_state::<D>(0.0, 1.0);
    let at_rest = probe_state::<D>(1.0, 0.0);
    let (flight, evaluations, units) = free_flight::<M, D>(scheme)?;

    let mut conditions = Vec::new();
    let w = mean(&flight.q) / h;
    conditions.push(ProbedCondition {
        order: 1,
        condition: CONSISTENCY.to_string(),
        measured: w,
        exact: 1.0,
        defect: w - 1.0,
        allowance: units * w.abs().max(1.0),
    });
    for order in 1..=through {
        let m = order - 1;
        // the velocity's bushy condition of this order, then the position's
        let (value, allowance) = velocity_moment::<M, D>(scheme, m, units)?;
        conditions.push(ProbedCondition {
            order,
            condition: format!("sum b_i{} = {}", node_power(m), one_over(order)),
            measured: value,
            exact: 1.0 / f64::from(order),
            defect: value - 1.0 / f64::from(order),
            allowance,
        });
        if order >= 2 {
            let position = part(scheme, &moving, h, m - 1, 1, units, |s| mean(&s.q))?;
            conditions.push(condition(
                order,
                format!("sum b_bar_i{} = 1/{}", node_power(m - 1), m * (m + 1)),
                position,
                h.powi(order as i32),
                1.0 / f64::from(m * (m + 1)),
            ));
        }
        if order == 3 {
            let chain = part(scheme, &at_rest, h, 1, 2, units, |s| mean(&s.v))?;
            conditions.push(condition(
                3,
                "sum b_i a_bar_ij = 1/6".to_string(),
                chain,
                h.powi(3),
                1.0 / 6.0,
            ));
        }
        if order == 4 {
            let chain = part(scheme, &at_rest, h, 1, 2, units, |s| mean(&s.q))?;
            conditions.push(condition(
                4,
                "sum b_bar_i a_bar_ij = 1/24".to_string(),
                chain,
                h.powi(4),
                1.0 / 24.0,
            ));
        }
    }
    Some(ConditionProbe {
        h,
        evaluations,
        conditions,
    })
}

/// One free flight from `q = 0`, `v = 1`, with the force evaluations it
/// counted and the rounding units `(n + 1) eps` they give (see
/// [`probe_conditions`]); `None` if the scheme cannot take the step.
pub(super) fn free_flight<M: Scheme, const D: usize>(scheme: &M) -> Option<(State<D>, u64, f64)> {
    if D == 0 || scheme.recurrence_on_oscillator(0.5).is_some() {
        return None;
    }
    let free = Counted::new(ProbeForce::<D> { c: 0.0, power: 0 });
    let flight = one_step(scheme, &free, &probe_state(0.0, 1.0), PROBE_STEP)?;
    let evaluations = free.evaluations();
    Some((
        flight,
        evaluations,
        (evaluations + 1) as f64 * scheme.epsilon(),
    ))
}

/// The step's velocity moment `sum b_i c_i^m`, from the part of `v1`
/// linear in `c` under `a = c q^m`, with its allowance.
pub(super) fn velocity_moment<M: Scheme, const D: usize>(
    scheme: &M,
    m: u32,
    units: f64,
) -> Option<(f64, f64)> {
    let h = PROBE_STEP;
    let part = part(scheme, &probe_state::<D>(0.0, 1.0), h, m, 1, units, |s| {
        mean(&s.v)
    })?;
    let scale = h.powi(m as i32 + 1);
    Some((part.value / scale, part.allowance / scale))
}

/// `c_i^m` as the condition prints it.
fn node_power(m: u32) -> String {
    match m {
        0 => String::new(),
        1 => " c_i".to_string(),
        _ => format!(" c_i^{m}"),
    }
}

fn condition(
    order: u32,
    text: String,
    part: Coefficient,
    h_power: f64,
    exact: f64,
) -> ProbedCondition {
    let measured = part.value / h_power;
    ProbedCondition {
        order,
        condition: text,
        measured,
        exact,
        defect: measured - exact,
        allowance: part.allowance / h_power,
    }
}

/// A coefficient of the step's expansion in the force's strength, with what
/// can explain an error in it.
#[derive(Clone, Copy, Debug)]
struct Coefficient {
    value: f64,
    allowance: f64,
}

/// The `c^k` coefficient (`k` 1 or 2) of `read(step)` under the force
/// `c q^power`, by central differences at `c` and `c/2` (see
/// [`probe_conditions`] for the error model).
fn part<M: Scheme, const D: usize>(
    scheme: &M,
    start: &State<D>,
    h: f64,
    power: u32,
    k: i32,
    units: f64,
    read: impl Fn(&State<D>) -> f64,
) -> Option<Coefficient> {
    let sample = |c: f64| -> Option<f64> {
        let scene = ProbeForce::<D> { c, power };
        one_step(scheme, &scene, start, h).map(|s| read(&s))
    };
    let at = |c: f64| -> Option<(f64, f64)> {
        let (plus, minus) = (sample(c)?, sample(-c)?);
        Some(if k == 1 {
            (
                (plus - minus) / (2.0 * c),
                units * (plus.abs() + minus.abs()) / (2.0 * c),
            )
        } else {
            let zero = sample(0.0)?;
            (
                (plus + minus - 2.0 * zero) / (2.0 * c * c),
                units * (plus.abs() + minus.abs() + 2.0 * zero.abs()) / (2.0 * c * c),
            )
        })
    };
    let c = units.powf(1.0 / f64::from(k + 2));
    let (coarse, coarse_rounding) = at(c)?;
    let (fine, fine_rounding) = at(c / 2.0)?;
    Some(Coefficient {
        value: fine,
        allowance: fine_rounding
            + 2.0 * ((coarse - fine).abs() + coarse_rounding + fine_rounding) / 3.0,
    })
}

/// `1/n`, or `1`.
fn one_over(n: u32) -> String {
    if n == 1 {
        "1".to_string()
    } else {
        format!("1/{n}")
    }
}

/// The state with every coordinate of the position `q` and of the
/// velocity `v`.
fn probe_state<const D: usize>(q: f64, v: f64) -> State<D> {
    State::new(SVector::repeat(q), SVector::repeat(v))
}

/// The mean of the coordinates.
fn mean<const D: usize>(x: &SVector<f64, D>) -> f64 {
    x.sum() / D as f64
}

/// One start and step of `h` from `state`, or `None` if it fails, panics
/// or leaves a non-finite state.
fn one_step<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    state: &State<D>,
    h: f64,
) -> Option<State<D>> {
    let stepped = caught(|| {
        let mut carry = scheme.start(scene, state, h);
        scheme.step(scene, &mut carry, h).ok()?;
        Some(scheme.state(&carry, h))
    })
    .ok()??;
    stepped.is_finite().then_some(stepped)
}

/// The probe force `a_i = c qbar^power` (`qbar` the coordinates' mean):
/// polynomial, so each part of the step in powers of `c` is one family of
/// conditions, and the gradient of `V = -c D qbar^(power + 1) / (power + 1)`.
#[derive(Clone, Copy, Debug)]
struct ProbeForce<const D: usize> {
    c: f64,
    power: u32,
}

impl<const D: usize> Scene<D> for ProbeForce<D> {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "condition-probe",
            name: "polynomial probe force",
            dimension: D,
            parameters: format!("a = {} q^{}", figure(self.c), self.power),
            reference: "",
        }
    }
    fn initial(&self) -> State<D> {
        probe_state(0.0, 1.0)
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, D>) -> SVector<R, D> {
        SVector::repeat(R::of(self.c) * diagonal(q).powi(self.power as i32))
    }
    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R {
        let n = self.power + 1;
        -R::of(self.c * D as f64) * diagonal(q).powi(n as i32) / R::of(f64::from(n))
    }
    fn period(&self) -> f64 {
        PROBE_STEP
    }
    fn exact(&self, _: f64) -> Option<State<D>> {
        None
    }
}

/// The coordinates' mean, in the step's scalar.
fn diagonal<R: Real, const D: usize>(q: &SVector<R, D>) -> R {
    (0..D).fold(R::zero(), |sum, i| sum + q[i]) / R::of(D as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scheme::{EULER_CROMER, Euler, FOREST_RUTH, PEFRL, Rk4, VELOCITY_VERLET};

    /// The probe force is minus the gradient of its potential (checked by
    /// central differences along each coordinate), in every dimension.
    #[test]
    fn the_probe_force_is_its_potentials_gradient() {
        fn check<const D: usize>() {
            let force = ProbeForce::<D> { c: 0.3, power: 3 };
            let q = SVector::<f64, D>::from_fn(|i, _| 0.2 + 0.1 * i as f64);
            let a = force.acceleration(&q);
            for i in 0..D {
                let step = 1e-5;
                let (mut up, mut down) = (q, q);
                up[i] += step;
                down[i] -= step;
                let slope = (force.potential(&up) - force.potential(&down)) / (2.0 * step);
                assert!(
                    (a[i] + slope).abs() < 1e-9,
                    "D = {D}, i = {i}: {} against {slope}",
                    a[i]
                );
            }
        }
        check::<1>();
        check::<3>();
    }

    #[test]
    fn the_catalogue_holds_every_condition_through_its_order() {
        let verlet = probe_conditions::<_, 1>(&VELOCITY_VERLET, 2).unwrap();
        assert!(verlet.first_violated().is_none(), "{}", verlet.describe());
        let rk4 = probe_conditions::<_, 2>(&Rk4, 4).unwrap();
        assert!(rk4.first_violated().is_none(), "{}", rk4.describe());
        let pefrl = probe_conditions::<_, 1>(&PEFRL, 4).unwrap();
        assert!(pefrl.first_violated().is_none(), "{}", pefrl.describe());
    }

    #[test]
    fn the_first_condition_beyond_the_order_fails() {
        // Euler-Cromer (kick then drift): sum b c = 0, sum b_bar = 1.
        let cromer = probe_conditions::<_, 1>(&EULER_CROMER, 2).unwrap();
        let first = cromer.first_violated().unwrap();
        assert_eq!(
            (first.order, first.condition.as_str()),
            (2, "sum b_i c_i = 1/2")
        );
        assert!((first.defect + 0.5).abs() < 1e-9, "{}", first.describe());
        // explicit Euler: the velocity's condition holds only at c = 0
        let euler = probe_conditions::<_, 1>(&Euler, 2).unwrap();
        assert!((euler.first_violated().unwrap().defect + 0.5).abs() < 1e-9);
        // Forest-Ruth is of order 4 exactly: a fifth-order condition fails
        let fr = probe_conditions::<_, 1>(&FOREST_RUTH, 5).unwrap();
        assert_eq!(fr.first_violated().unwrap().order, 5, "{}", fr.describe());
    }
}

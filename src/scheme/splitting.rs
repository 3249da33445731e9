//! Splitting methods as data: one drift/kick stepper over coefficient tables.
//!
//! A drift `q += c h v` and a kick `v += c h a(q)` are each exact flows of a
//! part of the Hamiltonian `|v|^2/2 + V(q)`, hence symplectic; any sequence of
//! them is a symplectic scheme, and a palindromic sequence is time-symmetric.
//! A table lists the drift and kick weights in the order they are applied.
//! Compositions of velocity Verlet (see [`super::composition`]) are turned into
//! such tables at compile time and run by the same stepper.

use super::summation::{Rounded, Summable, Summation, rounded_scheme};
use super::{Scheme, SchemeMeta, StepFailure, VERLET_PHASE};
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::SVector;

/// Which flow a splitting applies first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// `q += c h v`.
    Drift,
    /// `v += c h a(q)`.
    Kick,
}

/// A splitting scheme: alternating drifts and kicks with these weights,
/// starting with `first`. The longer list may exceed the other by one.
#[derive(Clone, Copy, Debug)]
pub struct SplittingTable {
    /// The scheme's claims; `force_evaluations` is derived from the weights.
    pub meta: SchemeMeta,
    /// The flow applied first.
    pub first: Flow,
    /// Drift weights, in order of application.
    pub drift: &'static [f64],
    /// Kick weights, in order of application.
    pub kick: &'static [f64],
    /// The weights `w_1..w_s` when the table is velocity Verlet composed with
    /// them (see [`super::composition::VerletComposition`]); `None` for a
    /// splitting given by its drift and kick weights directly.
    pub composition: Option<&'static [f64]>,
    /// The weights satisfy the order conditions only for `q'' = a(q)`, not
    /// for the splitting of any two non-commuting flows. With the kick `B`
    /// (its field depends on `q` alone) and the drift `A` (its field linear
    /// in `v`), `[B, [B, [B, A]]] = 0` for every force, which removes order
    /// conditions; Runge-Kutta-Nystrom splittings spend the freed weights on
    /// a smaller error. Every scene here is `q'' = a(q)`, so the claimed
    /// order is the order on every scene; only the algebraic check with
    /// generic matrices does not apply. Set by
    /// [`SplittingTable::only_for_nystrom`].
    pub nystrom_only: bool,
}

impl SplittingTable {
    /// True when the step starts and ends with a kick: the final kick's
    /// acceleration is the next step's first, so it is evaluated once
    /// ("first same as last").
    pub const fn reuses_acceleration(&self) -> bool {
        matches!(self.first, Flow::Kick) && self.kick.len() == self.drift.len() + 1
    }

    /// A table from its claims and weights. `meta.force_evaluations` is
    /// derived here from the weights (one per kick, less a reused one), so
    /// whatever the caller wrote there is replaced.
    pub const fn new(
        mut meta: SchemeMeta,
        first: Flow,
        drift: &'static [f64],
        kick: &'static [f64],
    ) -> Self {
        let table = Self {
            meta,
            first,
            drift,
            kick,
            composition: None,
            nystrom_only: false,
        };
        meta.force_evaluations = kick.len() as u32 - table.reuses_acceleration() as u32;
        Self { meta, ..table }
    }

    /// The same table, marked as having its claimed order only for
    /// `q'' = a(q)` (see the field `nystrom_only`).
    pub const fn only_for_nystrom(self) -> Self {
        Self {
            nystrom_only: true,
            ..self
        }
    }

    /// The flows in order of application with their weights.
    pub fn sequence(&self) -> Vec<(Flow, f64)> {
        let (lead, lag, other) = match self.first {
            Flow::Drift => (self.drift, self.kick, Flow::Kick),
            Flow::Kick => (self.kick, self.drift, Flow::Drift),
        };
        let mut ops = Vec::with_capacity(lead.len() + lag.len());
        for (i, &c) in lead.iter().enumerate() {
            ops.push((self.first, c));
            if let Some(&d) = lag.get(i) {
                ops.push((other, d));
            }
        }
        ops
    }
}

/// Position and velocity, summed by `S`, and the acceleration a
/// first-same-as-last table reuses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KickDrift<R: Real, const D: usize, S: Summation = Rounded> {
    /// Position.
    pub q: S::Sum<R, D>,
    /// Velocity.
    pub v: S::Sum<R, D>,
    /// `a(q)` at the rounded position, when the table reuses it.
    pub a: SVector<R, D>,
}

impl Summable for SplittingTable {
    type Carry<R: Real, const D: usize, S: Summation> = KickDrift<R, D, S>;

    fn start_summed<S: Summation, R: Real, const D: usize, Sc: Scene<D>>(
        &self,
        scene: &Sc,
        state: &State<D, R>,
        _: R,
    ) -> KickDrift<R, D, S> {
        let a = if self.reuses_acceleration() {
            scene.acceleration(&state.q)
        } else {
            SVector::zeros()
        };
        KickDrift {
            q: S::new(state.q),
            v: S::new(state.v),
            a,
        }
    }

    #[inline(always)]
    fn step_summed<S: Summation, R: Real, const D: usize, Sc: Scene<D>>(
        &self,
        scene: &Sc,
        c: &mut KickDrift<R, D, S>,
        h: R,
    ) -> Result<(), StepFailure> {
        match self.first {
            Flow::Kick => {
                let mut a = if self.reuses_acceleration() {
                    c.a
                } else {
                    scene.acceleration(&S::value(&c.q))
                };
                for (i, &b) in self.kick.iter().enumerate() {
                    if i > 0 {
                        a = scene.acceleration(&S::value(&c.q));
                    }
                    S::add(&mut c.v, a * (h * R::of(b)));
                    if let Some(&d) = self.drift.get(i) {
                        S::add(&mut c.q, S::value(&c.v) * (h * R::of(d)));
                    }
                }
                c.a = a;
            }
            Flow::Drift => {
                for (i, &d) in self.drift.iter().enumerate() {
                    S::add(&mut c.q, S::value(&c.v) * (h * R::of(d)));
                    if let Some(&b) = self.kick.get(i) {
                        let a = scene.acceleration(&S::value(&c.q));
                        S::add(&mut c.v, a * (h * R::of(b)));
                    }
                }
            }
        }
        Ok(())
    }

    fn state_summed<S: Summation, R: Real, const D: usize>(
        &self,
        c: &KickDrift<R, D, S>,
        _: R,
    ) -> State<D, R> {
        State::new(S::value(&c.q), S::value(&c.v))
    }
    fn compensation_summed<S: Summation, R: Real, const D: usize>(
        &self,
        c: &KickDrift<R, D, S>,
        _: R,
    ) -> State<D, R> {
        State::new(S::low(&c.q), S::low(&c.v))
    }
}

rounded_scheme!(SplittingTable, |table| &table.meta);

/// Euler-Cromer (symplectic Euler): `v' = v + h a(q)`, then `q' = q + h v'`.
pub const EULER_CROMER: SplittingTable = SplittingTable::new(
    SchemeMeta {
        id: "euler-cromer",
        name: "Euler-Cromer (symplectic Euler)",
        order: 1,
        symplectic: true,
        symmetric: false,
        reference: "A. Cromer, Am. J. Phys. 49, 455 (1981); course notes' Euler-Cromer method",
        force_evaluations: 0, // derived by `new`
        implicit: false,
        phase_error: VERLET_PHASE,
    },
    Flow::Kick,
    &[1.0],
    &[1.0],
);

/// Velocity Verlet, kick-drift-kick: `v += h/2 a(q)`, `q += h v`, `v += h/2 a(q)`,
/// with the last acceleration reused as the next step's first.
pub const VELOCITY_VERLET: SplittingTable = SplittingTable::new(
    SchemeMeta {
        id: "velocity-verlet",
        name: "velocity Verlet (kick-drift-kick)",
        order: 2,
        symplectic: true,
        symmetric: true,
        reference: "W. C. Swope et al., J. Chem. Phys. 76, 637 (1982); course notes' velocity Verlet",
        force_evaluations: 0, // derived by `new`
        implicit: false,
        phase_error: VERLET_PHASE,
    },
    Flow::Kick,
    &[1.0],
    &[0.5, 0.5],
);

/// Position Verlet, drift-kick-drift: `q += h/2 v`, `v += h a(q)`, `q += h/2 v`.
pub const POSITION_VERLET: SplittingTable = SplittingTable::new(
    SchemeMeta {
        id: "position-verlet",
        name: "position Verlet (drift-kick-drift)",
        order: 2,
        symplectic: true,
        symmetric: true,
        reference: "E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration (2006), I.3.1",
        force_evaluations: 0, // derived by `new`
        implicit: false,
        phase_error: VERLET_PHASE,
    },
    Flow::Drift,
    &[0.5, 0.5],
    &[1.0],
);

/// Omelyan, Mryglod and Folk's position-extended Forest-Ruth-like method
/// (PEFRL): five drifts and four kicks, drift first,
/// `D(xi) K((1-2 lambda)/2) D(chi) K(lambda) D(1-2(chi+xi)) K(lambda) D(chi) K((1-2 lambda)/2) D(xi)`.
///
/// Fourth order with one free parameter left by the order conditions, chosen
/// to minimise the fifth-order error terms, which end up more than an order of
/// magnitude below Forest-Ruth's for one more force evaluation per step. The
/// published 16 digits satisfy the order conditions to 7e-17; the weights here
/// are the exact solution nearest to them (Newton iteration with minimum-norm
/// steps, `tests/refine_coefficients.py`), 3e-17 away, rounded to doubles.
pub const PEFRL: SplittingTable = SplittingTable::new(
    SchemeMeta {
        id: "pefrl",
        name: "position-extended Forest-Ruth-like (PEFRL)",
        order: 4,
        symplectic: true,
        symmetric: true,
        reference: "I. P. Omelyan, I. M. Mryglod, R. Folk, Comput. Phys. Commun. 146, 188 (2002)",
        phase_error: None,    // measured only: no hand-derived leading term
        force_evaluations: 0, // derived by `new`
        implicit: false,
    },
    Flow::Drift,
    &[
        pefrl::XI,
        pefrl::CHI,
        1.0 - 2.0 * (pefrl::CHI + pefrl::XI),
        pefrl::CHI,
        pefrl::XI,
    ],
    &[
        0.5 - pefrl::LAMBDA,
        pefrl::LAMBDA,
        pefrl::LAMBDA,
        0.5 - pefrl::LAMBDA,
    ],
);

/// PEFRL's coefficients (Omelyan, Mryglod & Folk 2002), to full double precision.
mod pefrl {
    /// Published 0.1786178958448091.
    pub const XI: f64 = 0.17861789584480905;
    /// Published -0.2123418310626054.
    pub const LAMBDA: f64 = -0.2123418310626054;
    /// Published -0.06626458266981849.
    pub const CHI: f64 = -0.0662645826698185;
}

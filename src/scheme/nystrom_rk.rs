//! Explicit Runge-Kutta-Nyström methods as data: one stepper over tableaux.
//!
//! For `q'' = a(q)` a Nyström method integrates the second-order equation
//! directly:
//! `k_i = a(q + c_i h v + h^2 sum_(j<i) a_ij k_j)`,
//! `q' = q + h v + h^2 sum b_bar_i k_i`, `v' = v + h sum b_i k_i`.
//! Since the right-hand side does not depend on `v`, the order conditions are
//! far fewer than for a Runge-Kutta method on `(q, v)`, so fewer stages buy
//! the same order (three for order four, five for order six). None of these
//! methods is symplectic or symmetric: they are the non-geometric baseline
//! of the high orders, and DPRKN6 and DPRKN8 carry embedded fourth- and
//! sixth-order solutions for step-size control (see
//! [`crate::scheme::EmbeddedPair`]). The tables themselves are data, in
//! `nystrom_tables.rs`.

use super::summation::{Summable, Summation};
use super::{Scheme, SchemeMeta, StepFailure, WithAcceleration};
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::SVector;

/// The weights of a lower-order solution computed from the same stages: the
/// difference to the main solution estimates the local error of the
/// lower-order one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Embedded<const S: usize> {
    /// Order of the embedded solution.
    pub order: u32,
    /// Its position weights.
    pub b_bar: [f64; S],
    /// Its velocity weights.
    pub b: [f64; S],
}

/// An explicit Runge-Kutta-Nyström tableau with `S` stages.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NystromTable<const S: usize> {
    /// The claims; `force_evaluations` is derived by [`NystromTable::new`].
    pub meta: SchemeMeta,
    /// The nodes; `c_1 = 0`, so the first stage is the force at the step's
    /// start.
    pub c: [f64; S],
    /// The `h^2` coefficients of the stage positions (strict lower triangle).
    pub a: [[f64; S]; S],
    /// Position weights.
    pub b_bar: [f64; S],
    /// Velocity weights.
    pub b: [f64; S],
    /// The embedded solution, for a pair.
    pub embedded: Option<Embedded<S>>,
}

/// The stages, the new state and, for a pair, the local error estimate of
/// one step (what a step-size controller needs).
#[derive(Clone, Copy, Debug)]
pub struct NystromStep<R: Real, const D: usize> {
    /// The main solution after the step.
    pub state: State<D, R>,
    /// `a(state.q)` when the tableau is first same as last, else unused.
    pub a_end: SVector<R, D>,
    /// Main minus embedded solution, in position and velocity (zero without
    /// an embedded solution).
    pub error: State<D, R>,
}

impl<const S: usize> NystromTable<S> {
    /// A table from its claims and coefficients. `meta.force_evaluations` is
    /// derived here (one per stage, less the last when it is the next step's
    /// first), so whatever the caller wrote there is replaced.
    pub const fn new(
        mut meta: SchemeMeta,
        c: [f64; S],
        a: [[f64; S]; S],
        b_bar: [f64; S],
        b: [f64; S],
        embedded: Option<Embedded<S>>,
    ) -> Self {
        assert!(c[0] == 0.0, "the first stage is the force at the start");
        let table = Self {
            meta,
            c,
            a,
            b_bar,
            b,
            embedded,
        };
        meta.force_evaluations = S as u32 - table.first_same_as_last() as u32;
        Self { meta, ..table }
    }

    /// True when the last stage is evaluated at the new position
    /// (`c_S = 1`, `a_Sj = b_bar_j`, `b_bar_S = 0`): its force is the next
    /// step's first stage and is evaluated once ("first same as last").
    pub const fn first_same_as_last(&self) -> bool {
        let last = S - 1;
        if self.c[last] != 1.0 || self.b_bar[last] != 0.0 {
            return false;
        }
        let mut j = 0;
        while j < last {
            if self.a[last][j] != self.b_bar[j] {
                return false;
            }
            j += 1;
        }
        true
    }

    /// `q + c h v + h^2 sum_j w_j k_j` over the first `n` stages: the one
    /// formula for stage positions and the new position, so that a first-
    /// same-as-last stage is bit for bit the next step's start.
    #[inline(always)]
    fn position<R: Real, const D: usize>(
        s: &State<D, R>,
        k: &[SVector<R, D>; S],
        w: &[f64; S],
        n: usize,
        ch: R,
        h2: R,
    ) -> SVector<R, D> {
        let mut q = s.q + s.v * ch;
        for (kj, &wj) in k[..n].iter().zip(w) {
            if wj != 0.0 {
                q += kj * (h2 * R::of(wj));
            }
        }
        q
    }

    /// One step from `s` with `a0 = a(s.q)`: the new state, the force at it
    /// (first same as last) and the embedded error estimate. `S - 1` force
    /// evaluations; no allocation.
    #[inline(always)]
    pub fn attempt<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        a0: SVector<R, D>,
        h: R,
    ) -> NystromStep<R, D> {
        let h2 = h * h;
        let (k, last_position) = self.stages(scene, s, a0, h);
        let q = if self.first_same_as_last() {
            last_position
        } else {
            Self::position(s, &k, &self.b_bar, S, h, h2)
        };
        let mut dv = SVector::<R, D>::zeros();
        for (ki, &bi) in k.iter().zip(&self.b) {
            dv += ki * R::of(bi);
        }
        NystromStep {
            state: State::new(q, s.v + dv * h),
            a_end: k[S - 1],
            error: self.estimate(&k, h),
        }
    }

    /// The stages `k_1 .. k_S` of a step from `s` with `k_1 = a0`, and the
    /// last stage's position.
    #[inline(always)]
    fn stages<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        s: &State<D, R>,
        a0: SVector<R, D>,
        h: R,
    ) -> ([SVector<R, D>; S], SVector<R, D>) {
        let h2 = h * h;
        let mut k = [SVector::<R, D>::zeros(); S];
        k[0] = a0;
        let mut last_position = s.q;
        for i in 1..S {
            last_position = Self::position(s, &k, &self.a[i], i, h * R::of(self.c[i]), h2);
            k[i] = scene.acceleration(&last_position);
        }
        (k, last_position)
    }

    /// Main minus embedded solution from the stages (zero without one).
    #[inline(always)]
    fn estimate<R: Real, const D: usize>(&self, k: &[SVector<R, D>; S], h: R) -> State<D, R> {
        let mut error = State::new(SVector::zeros(), SVector::zeros());
        if let Some(e) = &self.embedded {
            for (i, ki) in k.iter().enumerate() {
                error.q += ki * R::of(self.b_bar[i] - e.b_bar[i]);
                error.v += ki * R::of(self.b[i] - e.b[i]);
            }
            error.q *= h * h;
            error.v *= h;
        }
        error
    }

    /// One step with the coordinates carried as `M`'s sums: the stages from
    /// the rounded coordinates, then the increments `h v + h^2 sum b_bar_i
    /// k_i` and `h sum b_i k_i`, each summed on its own (its rounding is
    /// relative to itself, `h w` times smaller than the coordinate's), added
    /// to the coordinates by `M`. With [`super::Kahan`] sums the step loses
    /// the rounding of the increments and of the forces at rounded stage
    /// positions, not the `eps |q|` per step of adding a small increment to
    /// a large coordinate. The force at the new position, for a
    /// first-same-as-last table, is the last stage's, at the rounded sum of
    /// the same increment: it differs from the force at the compensated
    /// coordinate by that rounding, the same size as every stage's. `S - 1`
    /// force evaluations; no allocation.
    #[inline(always)]
    pub fn attempt_summed<M: Summation, R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        q: &mut M::Sum<R, D>,
        v: &mut M::Sum<R, D>,
        a0: SVector<R, D>,
        h: R,
    ) -> SummedStep<R, D> {
        let start = State::new(M::value(q), M::value(v));
        let (k, _) = self.stages(scene, &start, a0, h);
        let (hr, h2) = (h, h * h);
        let mut dq = start.v * hr;
        let mut dv = SVector::<R, D>::zeros();
        for (ki, (&bb, &b)) in k.iter().zip(self.b_bar.iter().zip(&self.b)) {
            if bb != 0.0 {
                dq += ki * (h2 * R::of(bb));
            }
            dv += ki * (hr * R::of(b));
        }
        M::add(q, dq);
        M::add(v, dv);
        SummedStep {
            a_end: k[S - 1],
            error: self.estimate(&k, h),
        }
    }
}

/// What [`NystromTable::attempt_summed`] returns beside the updated sums.
#[derive(Clone, Copy, Debug)]
pub struct SummedStep<R: Real, const D: usize> {
    /// The last stage's force: the next step's first for a
    /// first-same-as-last table.
    pub a_end: SVector<R, D>,
    /// Main minus embedded solution (zero without an embedded solution).
    pub error: State<D, R>,
}

/// A step's coordinates as `M`'s sums, with the force the next step starts
/// from (first same as last) or zero.
#[derive(Clone, Copy, Debug)]
pub struct SummedCarry<R: Real, const D: usize, M: Summation> {
    /// The position.
    pub q: M::Sum<R, D>,
    /// The velocity.
    pub v: M::Sum<R, D>,
    /// `a(q)` for a first-same-as-last table.
    pub a: SVector<R, D>,
}

/// The fixed-step method with its coordinate updates summed by any
/// [`Summation`]: wrapped in [`super::Compensated`] it is the tableau with
/// compensated sums. With [`super::Rounded`] sums it is the tableau's map
/// with the increments summed before they are added, so it differs from the
/// plain [`Scheme`] (which adds each term to the position in turn) in the
/// last bits of each step.
impl<const S: usize> Summable for NystromTable<S> {
    type Carry<R: Real, const D: usize, M: Summation> = SummedCarry<R, D, M>;

    fn start_summed<M: Summation, R: Real, const D: usize, Sc: Scene<D>>(
        &self,
        scene: &Sc,
        state: &State<D, R>,
        _: R,
    ) -> SummedCarry<R, D, M> {
        let a = if self.first_same_as_last() {
            scene.acceleration(&state.q)
        } else {
            SVector::zeros()
        };
        SummedCarry {
            q: M::new(state.q),
            v: M::new(state.v),
            a,
        }
    }

    #[inline(always)]
    fn step_summed<M: Summation, R: Real, const D: usize, Sc: Scene<D>>(
        &self,
        scene: &Sc,
        c: &mut SummedCarry<R, D, M>,
        h: R,
    ) -> Result<(), StepFailure> {
        let a0 = if self.first_same_as_last() {
            c.a
        } else {
            scene.acceleration(&M::value(&c.q))
        };
        c.a = self
            .attempt_summed::<M, R, D, Sc>(scene, &mut c.q, &mut c.v, a0, h)
            .a_end;
        Ok(())
    }

    fn state_summed<M: Summation, R: Real, const D: usize>(
        &self,
        c: &SummedCarry<R, D, M>,
        _: R,
    ) -> State<D, R> {
        State::new(M::value(&c.q), M::value(&c.v))
    }
    fn compensation_summed<M: Summation, R: Real, const D: usize>(
        &self,
        c: &SummedCarry<R, D, M>,
        _: R,
    ) -> State<D, R> {
        State::new(M::low(&c.q), M::low(&c.v))
    }
}

impl<const S: usize> Scheme for NystromTable<S> {
    type Carry<R: Real, const D: usize> = WithAcceleration<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        state: &State<D, R>,
        _: R,
    ) -> WithAcceleration<R, D> {
        let a = if self.first_same_as_last() {
            scene.acceleration(&state.q)
        } else {
            SVector::zeros()
        };
        WithAcceleration { state: *state, a }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, P: Scene<D>>(
        &self,
        scene: &P,
        c: &mut WithAcceleration<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        let a0 = if self.first_same_as_last() {
            c.a
        } else {
            scene.acceleration(&c.state.q)
        };
        let next = self.attempt(scene, &c.state, a0, h);
        c.state = next.state;
        c.a = next.a_end;
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &WithAcceleration<R, D>, _: R) -> State<D, R> {
        c.state
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conditions;
    use crate::scene::{Harmonic, KeplerCircular};
    use crate::scheme::nystrom_tables::R8581;
    use crate::scheme::{DPRKN6, DPRKN8, NYSTROM4};

    #[test]
    fn the_surd_is_the_square_root_of_8581() {
        assert!((R8581 * R8581 - 8581.0).abs() < 4e-12);
    }

    /// Every Nyström order condition through `h^7`: the main solutions of
    /// DPRKN6 and Nyström's method have their orders and fail the next, and
    /// the embedded solution is fourth order and fails order five (an
    /// embedded solution of order five would make the estimate useless).
    #[test]
    fn the_main_solutions_have_their_order_and_the_embedded_one_fails_order_five() {
        let c = conditions::nystrom(&DPRKN6).unwrap();
        println!(
            "dprkn6 {}
       embedded {}",
            c.main,
            c.embedded.as_ref().unwrap()
        );
        assert!(c.main.confirms(6), "{}", c.main);
        assert!(c.embedded.unwrap().confirms(4));
        // rows sum to c^2/2 (the stage positions are consistent)
        for i in 0..6 {
            let row: f64 = DPRKN6.a[i].iter().sum();
            assert!((row - DPRKN6.c[i].powi(2) / 2.0).abs() < 1e-16, "row {i}");
        }
        let c = conditions::nystrom(&NYSTROM4).unwrap();
        assert!(c.main.confirms(4), "{}", c.main);
    }

    /// DPRKN8's every Nyström order condition through `h^8` (its estimate's
    /// through `h^6`) and none beyond, its rows summing to `c^2/2`, and its
    /// local error on the Kepler orbit falling like `h^9` (halving `h`
    /// divides it by 512), its estimate's like `h^7` (by 128). The same
    /// trees are checked in exact rationals by
    /// `tests/check_nystrom_rk_orders.py`.
    #[test]
    fn dprkn8_has_order_eight_and_its_estimate_order_six() {
        let t = &DPRKN8;
        for i in 0..9 {
            let row: f64 = t.a[i].iter().sum();
            assert!((row - t.c[i].powi(2) / 2.0).abs() < 4e-16, "row {i}: {row}");
        }
        let c = conditions::nystrom(t).unwrap();
        println!(
            "dprkn8 {}
       embedded {}",
            c.main,
            c.embedded.as_ref().unwrap()
        );
        assert!(c.main.confirms(8), "{}", c.main);
        assert!(c.embedded.unwrap().confirms(6));
        assert!(t.first_same_as_last());
        assert_eq!(t.meta.force_evaluations, 8);
        let scene = KeplerCircular;
        let s = scene.initial();
        let a0 = scene.acceleration(&s.q);
        let local = |h: f64| {
            let x = t.attempt(&scene, &s, a0, h).state;
            scene.phase_distance(&x, &scene.exact(h).unwrap())
        };
        let estimate = |h: f64| {
            let e = t.attempt(&scene, &s, a0, h).error;
            (e.q.norm_squared() + e.v.norm_squared()).sqrt()
        };
        for h in [0.08, 0.04] {
            let r = local(h) / local(h / 2.0);
            assert!((r / 512.0 - 1.0).abs() < 0.15, "h = {h}: local ratio {r}");
            let r = estimate(h) / estimate(h / 2.0);
            assert!(
                (r / 128.0 - 1.0).abs() < 0.15,
                "h = {h}: estimate ratio {r}"
            );
        }
    }

    #[test]
    fn dprkn6_is_first_same_as_last_and_nystrom4_is_not() {
        assert!(DPRKN6.first_same_as_last());
        assert_eq!(DPRKN6.meta.force_evaluations, 5);
        assert!(!NYSTROM4.first_same_as_last());
        assert_eq!(NYSTROM4.meta.force_evaluations, 3);
    }

    /// The reused force is bit for bit the force at the new position: the
    /// FSAL step computes the same map as a step that evaluates it afresh.
    #[test]
    fn the_reused_force_is_the_force_at_the_new_position() {
        let scene = KeplerCircular;
        let mut c = DPRKN6.start(&scene, &scene.initial(), 0.1);
        for _ in 0..50 {
            DPRKN6.step(&scene, &mut c, 0.1).unwrap();
            assert_eq!(c.a, scene.acceleration(&c.state.q));
        }
    }

    /// The error estimate is the difference of a sixth- and a fourth-order
    /// solution: its local size falls like `h^5` (halving `h` divides it by
    /// 32), the main solution's local error like `h^7`.
    #[test]
    fn the_error_estimate_scales_like_h_to_the_fifth() {
        let scene = Harmonic::default();
        let s = scene.initial();
        let a0 = scene.acceleration(&s.q);
        let size = |h: f64| {
            let e = DPRKN6.attempt(&scene, &s, a0, h).error;
            (e.q.norm_squared() + e.v.norm_squared()).sqrt()
        };
        for h in [0.02, 0.01] {
            let ratio = size(h) / size(h / 2.0);
            assert!((ratio / 32.0 - 1.0).abs() < 0.1, "h = {h}: ratio {ratio}");
        }
        let local = |h: f64| {
            let x = DPRKN6.attempt(&scene, &s, a0, h).state;
            scene.phase_distance(&x, &scene.exact(h).unwrap())
        };
        let ratio = local(0.2) / local(0.1);
        assert!((ratio / 128.0 - 1.0).abs() < 0.1, "{ratio}");
    }
}

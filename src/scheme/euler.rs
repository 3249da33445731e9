//! Explicit (forward) Euler.

use super::{OneStep, PhaseError, SchemeMeta, StepFailure};
use crate::scene::Scene;
use crate::state::{Real, State};

/// Explicit Euler: `q' = q + h v`, `v' = v + h a(q)`, both from the old state.
///
/// First order, neither symplectic nor symmetric: on the oscillator each step
/// multiplies the energy by `1 + (h w0)^2`, so orbits spiral outwards.
#[derive(Clone, Copy, Debug, Default)]
pub struct Euler;

impl Euler {
    /// What explicit Euler claims.
    pub const META: SchemeMeta = SchemeMeta {
        id: "euler",
        name: "explicit Euler",
        order: 1,
        symplectic: false,
        symmetric: false,
        force_evaluations: 1,
        implicit: false,
        reference: "L. Euler, Institutionum calculi integralis (1768); course notes' Earth-Sun code",
        // eigenvalues 1 -+ i z: w_num h = atan z = z - z^3/3 + ...
        phase_error: Some(PhaseError {
            coefficient: -1.0 / 3.0,
            power: 2,
        }),
    };
}

impl OneStep for Euler {
    fn meta(&self) -> &SchemeMeta {
        &Self::META
    }

    #[inline(always)]
    fn advance<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let a = scene.acceleration(&s.q);
        s.q += s.v * h;
        s.v += a * h;
        Ok(())
    }
}

//! Compensated-summation variants of the three Verlet forms: the same maps in
//! exact arithmetic, with the round-off of their position and velocity
//! updates carried along instead of lost.
//!
//! A step adds a small increment (`h v`, `h a` or `h^2 a`) to a much larger
//! coordinate. Rounded to the coordinate's precision, the increment loses its
//! low bits: about `eps |q|` per step, whatever the step, so the error a run
//! accumulates grows as the step shrinks. Here each updated coordinate is
//! carried as a pair `value + low`, where `low` holds exactly what rounding
//! `value` dropped, and is added back with the next increment (Kahan's
//! compensated summation). The rounding error of each addition is obtained
//! exactly by Knuth's TwoSum, which, unlike Kahan's three-operation form,
//! needs no assumption on which operand is larger: on the oscillator the
//! position passes through zero twice a period, where the increment exceeds it.
//!
//! What is left is the rounding of the increments themselves and of the force
//! evaluated at the rounded position, `eps h w |q|` per step: smaller by the
//! factor `h w` than what the plain forms lose. Every carry keeps the low
//! parts beside the values; nothing is allocated and every scalar type works
//! (dual numbers carry the same compensation in their derivative parts).
//!
//! These variants are not in the main [`super::catalogue`]: at the steps the
//! catalogue's studies use, their results are those of their plain twins to
//! within round-off a million times below the truncation error, so they would
//! add rows that differ only in digits the studies do not resolve. They are
//! measured by the round-off studies ([`crate::study::round_off::floor`],
//! [`crate::study::round_off::longrun`]), which is where they differ, and their order,
//! symplecticity and time symmetry are tested like any catalogue scheme's.

use super::splitting::{Flow, SplittingTable, VELOCITY_VERLET};
use super::verlet::{Leapfrog, StormerVerlet};
use super::{Scheme, SchemeMeta, SchemeVisitor, StepFailure, scheme_ids};
use crate::error::Error;
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::SVector;

/// `(s, e)` with `s = fl(a + b)` and `s + e = a + b` exactly, componentwise
/// (Knuth's TwoSum: six operations, no comparison, exact for any magnitudes
/// in round-to-nearest binary arithmetic without overflow).
#[inline(always)]
pub fn two_sum<R: Real, const D: usize>(
    a: SVector<R, D>,
    b: SVector<R, D>,
) -> (SVector<R, D>, SVector<R, D>) {
    let s = a + b;
    let b_virtual = s - a;
    let a_virtual = s - b_virtual;
    (s, (a - a_virtual) + (b - b_virtual))
}

/// A coordinate carried as `value + low`: `value` is what a plain scheme would
/// hold, `low` the part of the exact running sum that rounding `value` lost
/// (at most half an ulp of `value`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summed<R: Real, const D: usize> {
    /// The rounded coordinate.
    pub value: SVector<R, D>,
    /// What rounding it dropped.
    pub low: SVector<R, D>,
}

impl<R: Real, const D: usize> Summed<R, D> {
    /// A coordinate with nothing lost yet.
    #[inline(always)]
    pub fn new(value: SVector<R, D>) -> Self {
        Self {
            value,
            low: SVector::zeros(),
        }
    }

    /// Adds `increment` with compensation: the low part lost so far rides
    /// along with the increment, and what this addition loses becomes the new
    /// low part.
    #[inline(always)]
    pub fn add(&mut self, increment: SVector<R, D>) {
        let (value, low) = two_sum(self.value, increment + self.low);
        self.value = value;
        self.low = low;
    }
}

/// The two-step Störmer-Verlet scheme, `q(n+1) = 2 q(n) - q(n-1) + h^2 a(q(n))`,
/// with both positions carried as `value + low` and the recurrence evaluated
/// in that form: `2 q(n) - q(n-1)` of the values exactly (TwoSum), then the
/// low parts and `h^2 a` added to its error term, then one TwoSum back to a
/// value and a low part. The central-difference velocity
/// `(q(n+1) - q(n-1)) / 2h` subtracts the values and the low parts
/// separately, so it no longer divides a difference rounded at `eps |q|` by `2h`.
///
/// Start-up and read-out are those of [`StormerVerlet`].
#[derive(Clone, Copy, Debug, Default)]
pub struct StormerVerletCompensated;

/// Two successive positions, each with its low part, and the acceleration at
/// the later one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoStepCompensated<R: Real, const D: usize> {
    /// `q(n-1)`.
    pub previous: Summed<R, D>,
    /// `q(n)`.
    pub current: Summed<R, D>,
    /// `a(q(n))`, at the rounded position.
    pub a: SVector<R, D>,
}

impl<R: Real, const D: usize> TwoStepCompensated<R, D> {
    /// `q(n+1) = 2 q(n) - q(n-1) + h^2 a(q(n))` in compensated form.
    #[inline(always)]
    fn next(&self, h: R) -> Summed<R, D> {
        let two = R::of(2.0);
        let (value, error) = two_sum(self.current.value * two, -self.previous.value);
        let small = error + (self.current.low * two - self.previous.low) + self.a * (h * h);
        let (value, low) = two_sum(value, small);
        Summed { value, low }
    }
}

impl StormerVerletCompensated {
    /// What the compensated two-step scheme claims: the same as [`StormerVerlet`].
    pub const META: SchemeMeta = SchemeMeta {
        id: "stormer-verlet-compensated",
        name: "Störmer-Verlet (two-step), compensated summation",
        reference: "StormerVerlet with positions carried to twice the working precision: W. Kahan, Commun. ACM 8, 40 (1965); D. E. Knuth, The Art of Computer Programming 2, 4.2.2",
        ..StormerVerlet::META
    };
}

impl Scheme for StormerVerletCompensated {
    type Carry<R: Real, const D: usize> = TwoStepCompensated<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &Self::META
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &State<D, R>,
        h: R,
    ) -> TwoStepCompensated<R, D> {
        let a = scene.acceleration(&s.q);
        let mut previous = Summed::new(s.q);
        previous.add(a * (h * h * R::of(0.5)) - s.v * h);
        TwoStepCompensated {
            previous,
            current: Summed::new(s.q),
            a,
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        c: &mut TwoStepCompensated<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        let next = c.next(h);
        c.previous = c.current;
        c.current = next;
        c.a = scene.acceleration(&next.value);
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &TwoStepCompensated<R, D>, h: R) -> State<D, R> {
        let next = c.next(h);
        let difference = (next.value - c.previous.value) + (next.low - c.previous.low);
        State::new(c.current.value, difference / (h * R::of(2.0)))
    }
}

/// Leap-frog, `q(n+1) = q(n) + h v(n+1/2)`, `v(n+3/2) = v(n+1/2) + h a(q(n+1))`,
/// with the position and the half-step velocity each carried as
/// `value + low`. Start-up and read-out are those of [`Leapfrog`].
#[derive(Clone, Copy, Debug, Default)]
pub struct LeapfrogCompensated;

/// A whole-step position and the velocity half a step later, each with its
/// low part, and `a(q)` at the rounded position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaggeredCompensated<R: Real, const D: usize> {
    /// `q(n)`.
    pub q: Summed<R, D>,
    /// `v(n + 1/2)`.
    pub v_half: Summed<R, D>,
    /// `a(q(n))`.
    pub a: SVector<R, D>,
}

impl LeapfrogCompensated {
    /// What compensated leap-frog claims: the same as [`Leapfrog`].
    pub const META: SchemeMeta = SchemeMeta {
        id: "leapfrog-compensated",
        name: "leap-frog, compensated summation",
        reference: "Leapfrog with compensated position and velocity sums: W. Kahan, Commun. ACM 8, 40 (1965); D. E. Knuth, The Art of Computer Programming 2, 4.2.2",
        ..Leapfrog::META
    };
}

impl Scheme for LeapfrogCompensated {
    type Carry<R: Real, const D: usize> = StaggeredCompensated<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &Self::META
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &State<D, R>,
        h: R,
    ) -> StaggeredCompensated<R, D> {
        let a = scene.acceleration(&s.q);
        let mut v_half = Summed::new(s.v);
        v_half.add(a * (h * R::of(0.5)));
        StaggeredCompensated {
            q: Summed::new(s.q),
            v_half,
            a,
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        c: &mut StaggeredCompensated<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        c.q.add(c.v_half.value * h);
        c.a = scene.acceleration(&c.q.value);
        c.v_half.add(c.a * h);
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &StaggeredCompensated<R, D>, h: R) -> State<D, R> {
        State::new(
            c.q.value,
            c.v_half.value + (c.v_half.low - c.a * (h * R::of(0.5))),
        )
    }
}

/// A splitting scheme (see [`SplittingTable`]) whose drifts and kicks add to
/// compensated sums: the same drift and kick weights, the same force
/// evaluations, `q` and `v` each carried as `value + low`.
#[derive(Clone, Copy, Debug)]
pub struct CompensatedSplitting {
    /// The variant's claims (those of the table, under its own id).
    pub meta: SchemeMeta,
    /// The splitting it runs.
    pub table: &'static SplittingTable,
}

/// The carry of a compensated splitting: position and velocity with their
/// low parts, and the acceleration reused by a first-same-as-last table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplittingCompensated<R: Real, const D: usize> {
    /// Position.
    pub q: Summed<R, D>,
    /// Velocity.
    pub v: Summed<R, D>,
    /// `a(q)` at the rounded position, when the table reuses it.
    pub a: SVector<R, D>,
}

impl Scheme for CompensatedSplitting {
    type Carry<R: Real, const D: usize> = SplittingCompensated<R, D>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &State<D, R>,
        _: R,
    ) -> SplittingCompensated<R, D> {
        let a = if self.table.reuses_acceleration() {
            scene.acceleration(&s.q)
        } else {
            SVector::zeros()
        };
        SplittingCompensated {
            q: Summed::new(s.q),
            v: Summed::new(s.v),
            a,
        }
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        c: &mut SplittingCompensated<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        let t = self.table;
        match t.first {
            Flow::Kick => {
                let mut a = if t.reuses_acceleration() {
                    c.a
                } else {
                    scene.acceleration(&c.q.value)
                };
                for (i, &b) in t.kick.iter().enumerate() {
                    if i > 0 {
                        a = scene.acceleration(&c.q.value);
                    }
                    c.v.add(a * (h * R::of(b)));
                    if let Some(&d) = t.drift.get(i) {
                        c.q.add(c.v.value * (h * R::of(d)));
                    }
                }
                c.a = a;
            }
            Flow::Drift => {
                for (i, &d) in t.drift.iter().enumerate() {
                    c.q.add(c.v.value * (h * R::of(d)));
                    if let Some(&b) = t.kick.get(i) {
                        c.v.add(scene.acceleration(&c.q.value) * (h * R::of(b)));
                    }
                }
            }
        }
        Ok(())
    }

    fn state<R: Real, const D: usize>(&self, c: &SplittingCompensated<R, D>, _: R) -> State<D, R> {
        State::new(c.q.value, c.v.value)
    }
}

/// Velocity Verlet (kick-drift-kick) with compensated position and velocity sums.
pub const VELOCITY_VERLET_COMPENSATED: CompensatedSplitting = CompensatedSplitting {
    meta: SchemeMeta {
        id: "velocity-verlet-compensated",
        name: "velocity Verlet (kick-drift-kick), compensated summation",
        reference: "VELOCITY_VERLET with compensated position and velocity sums: W. Kahan, Commun. ACM 8, 40 (1965); D. E. Knuth, The Art of Computer Programming 2, 4.2.2",
        ..VELOCITY_VERLET.meta
    },
    table: &VELOCITY_VERLET,
};

/// Something to do with a plain Verlet form and its compensated variant
/// together, whatever their types.
pub trait PairVisitor {
    /// What the visit produces.
    type Output;
    /// Called with the plain scheme and its compensated twin.
    fn visit<P: Scheme + Sync + 'static, C: Scheme + Sync + 'static>(
        self,
        plain: &'static P,
        compensated: &'static C,
    ) -> Self::Output;
}

macro_rules! pairs {
    ($(($plain:expr, $compensated:expr)),* $(,)?) => {
        /// The metadata of every compensated variant, in pair order.
        pub fn variants() -> Vec<&'static SchemeMeta> {
            vec![$( $compensated.meta() ),*]
        }

        /// The ids of the plain schemes that have a compensated variant, in pair order.
        pub fn paired_ids() -> Vec<&'static str> {
            vec![$( $plain.meta().id ),*]
        }

        /// Runs `visitor` on the pair whose plain or compensated member has this id.
        pub fn visit_pair<V: PairVisitor>(id: &str, visitor: V) -> Result<V::Output, Error> {
            $(
                if $plain.meta().id == id || $compensated.meta().id == id {
                    return Ok(visitor.visit(&$plain, &$compensated));
                }
            )*
            Err(Error::UnknownScheme { id: id.to_string(), valid: pair_ids().join(", ") })
        }

        /// Runs `visitor` on the compensated variant with this id.
        pub fn visit_variant<V: SchemeVisitor>(id: &str, visitor: V) -> Result<V::Output, Error> {
            $( if $compensated.meta().id == id { return Ok(visitor.visit(&$compensated)); } )*
            Err(Error::UnknownScheme { id: id.to_string(), valid: any_scheme_ids().join(", ") })
        }
    };
}

pairs![
    (StormerVerlet, StormerVerletCompensated),
    (Leapfrog, LeapfrogCompensated),
    (VELOCITY_VERLET, VELOCITY_VERLET_COMPENSATED),
];

/// Every id of a pair's member: the plain schemes, then their variants.
pub fn pair_ids() -> Vec<&'static str> {
    paired_ids()
        .into_iter()
        .chain(variants().into_iter().map(|m| m.id))
        .collect()
}

/// Every scheme id the single-case commands accept: the catalogue, then the
/// compensated variants.
pub fn any_scheme_ids() -> Vec<&'static str> {
    scheme_ids()
        .into_iter()
        .chain(variants().into_iter().map(|m| m.id))
        .collect()
}

/// Runs `visitor` on the catalogue scheme or compensated variant with this id.
pub fn visit_any_scheme<V: SchemeVisitor>(id: &str, visitor: V) -> Result<V::Output, Error> {
    if variants().iter().any(|m| m.id == id) {
        visit_variant(id, visitor)
    } else {
        super::visit_scheme(id, visitor).map_err(|_| Error::UnknownScheme {
            id: id.to_string(),
            valid: any_scheme_ids().join(", "),
        })
    }
}

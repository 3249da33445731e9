//! Compensated summation of a scheme's coordinate updates, and the
//! compensated variants of the three Verlet forms.
//!
//! A step adds a small increment (`h v`, `h a` or `h^2 a`) to a much larger
//! coordinate. Rounded to the coordinate's precision, the increment loses its
//! low bits: about `eps |q|` per step, whatever the step, so the error a run
//! accumulates grows as the step shrinks. Compensated, each updated coordinate
//! is carried as a pair `value + low`, where `low` holds exactly what rounding
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
//! Each Verlet form is written once, generic over a [`Summation`]: with
//! [`Rounded`] it is the catalogue's scheme, bit for bit, and wrapped in
//! [`Compensated`] it runs the same code with [`Kahan`] sums.
//!
//! The variants are not in the main [`super::catalogue`]: at the steps the
//! catalogue's studies use, their results are those of their plain twins to
//! within round-off a million times below the truncation error, so they would
//! add rows that differ only in digits the studies do not resolve. They are
//! measured by the round-off studies ([`crate::study::round_off::floor`],
//! [`crate::study::round_off::longrun`]), which is where they differ, and their order,
//! symplecticity and time symmetry are tested like any catalogue scheme's.

use super::splitting::{SplittingTable, VELOCITY_VERLET};
use super::verlet::{Leapfrog, StormerVerlet};
use super::{Scheme, SchemeMeta, SchemeVisitor, StepFailure, scheme_ids};
use crate::error::Error;
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::SVector;
use std::fmt::Debug;

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

/// How a scheme accumulates increments into a coordinate: the few operations
/// the Verlet forms are written in, so that one code path runs both rounded
/// and compensated.
pub trait Summation: Copy + Debug + Default + PartialEq + Send + Sync + 'static {
    /// A coordinate as this summation carries it.
    type Sum<R: Real, const D: usize>: Copy + Debug + PartialEq;

    /// A coordinate with nothing lost yet.
    fn new<R: Real, const D: usize>(value: SVector<R, D>) -> Self::Sum<R, D>;

    /// The coordinate rounded to working precision.
    fn value<R: Real, const D: usize>(sum: &Self::Sum<R, D>) -> SVector<R, D>;

    /// Adds `increment` to the coordinate.
    fn add<R: Real, const D: usize>(sum: &mut Self::Sum<R, D>, increment: SVector<R, D>);

    /// `sum + increment`, rounded once, without changing `sum`.
    fn plus<R: Real, const D: usize>(
        sum: &Self::Sum<R, D>,
        increment: SVector<R, D>,
    ) -> SVector<R, D>;

    /// `a - b`, rounded once.
    fn difference<R: Real, const D: usize>(
        a: &Self::Sum<R, D>,
        b: &Self::Sum<R, D>,
    ) -> SVector<R, D>;

    /// `2 current - previous + increment`: the two-step recurrence.
    fn two_step<R: Real, const D: usize>(
        current: &Self::Sum<R, D>,
        previous: &Self::Sum<R, D>,
        increment: SVector<R, D>,
    ) -> Self::Sum<R, D>;
}

/// Every addition rounded to working precision: the plain schemes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rounded;

impl Summation for Rounded {
    type Sum<R: Real, const D: usize> = SVector<R, D>;

    #[inline(always)]
    fn new<R: Real, const D: usize>(value: SVector<R, D>) -> SVector<R, D> {
        value
    }

    #[inline(always)]
    fn value<R: Real, const D: usize>(sum: &SVector<R, D>) -> SVector<R, D> {
        *sum
    }

    #[inline(always)]
    fn add<R: Real, const D: usize>(sum: &mut SVector<R, D>, increment: SVector<R, D>) {
        *sum += increment;
    }

    #[inline(always)]
    fn plus<R: Real, const D: usize>(
        sum: &SVector<R, D>,
        increment: SVector<R, D>,
    ) -> SVector<R, D> {
        sum + increment
    }

    #[inline(always)]
    fn difference<R: Real, const D: usize>(a: &SVector<R, D>, b: &SVector<R, D>) -> SVector<R, D> {
        a - b
    }

    #[inline(always)]
    fn two_step<R: Real, const D: usize>(
        current: &SVector<R, D>,
        previous: &SVector<R, D>,
        increment: SVector<R, D>,
    ) -> SVector<R, D> {
        (current * R::of(2.0) - previous) + increment
    }
}

/// Kahan's compensated summation with Knuth's TwoSum: each coordinate carried
/// as a [`Summed`] pair.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Kahan;

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

impl Summation for Kahan {
    type Sum<R: Real, const D: usize> = Summed<R, D>;

    #[inline(always)]
    fn new<R: Real, const D: usize>(value: SVector<R, D>) -> Summed<R, D> {
        Summed {
            value,
            low: SVector::zeros(),
        }
    }

    #[inline(always)]
    fn value<R: Real, const D: usize>(sum: &Summed<R, D>) -> SVector<R, D> {
        sum.value
    }

    /// The low part lost so far rides along with the increment, and what this
    /// addition loses becomes the new low part.
    #[inline(always)]
    fn add<R: Real, const D: usize>(sum: &mut Summed<R, D>, increment: SVector<R, D>) {
        let (value, low) = two_sum(sum.value, increment + sum.low);
        *sum = Summed { value, low };
    }

    #[inline(always)]
    fn plus<R: Real, const D: usize>(
        sum: &Summed<R, D>,
        increment: SVector<R, D>,
    ) -> SVector<R, D> {
        sum.value + (sum.low + increment)
    }

    /// The values and the low parts subtracted separately, so a difference of
    /// nearby coordinates keeps the bits rounding would have cancelled.
    #[inline(always)]
    fn difference<R: Real, const D: usize>(a: &Summed<R, D>, b: &Summed<R, D>) -> SVector<R, D> {
        (a.value - b.value) + (a.low - b.low)
    }

    /// `2 current - previous` of the values exactly (TwoSum), then the low
    /// parts and the increment added to its error term, then one TwoSum back
    /// to a value and a low part.
    #[inline(always)]
    fn two_step<R: Real, const D: usize>(
        current: &Summed<R, D>,
        previous: &Summed<R, D>,
        increment: SVector<R, D>,
    ) -> Summed<R, D> {
        let two = R::of(2.0);
        let (value, error) = two_sum(current.value * two, -previous.value);
        let small = error + (current.low * two - previous.low) + increment;
        let (value, low) = two_sum(value, small);
        Summed { value, low }
    }
}

/// A scheme written once for any [`Summation`]: the same steps, with its
/// coordinates carried as that summation's sums. With [`Rounded`] it is the
/// scheme itself; [`Compensated`] runs it with [`Kahan`].
pub trait Summable: Sync + 'static {
    /// What the scheme keeps between steps, its coordinates summed by `S`.
    type Carry<R: Real, const D: usize, S: Summation>: Clone + Debug;

    /// [`Scheme::start`] with sums `S`.
    fn start_summed<S: Summation, R: Real, const D: usize, Sc: Scene<D>>(
        &self,
        scene: &Sc,
        state: &State<D, R>,
        h: R,
    ) -> Self::Carry<R, D, S>;

    /// [`Scheme::step`] with sums `S`.
    fn step_summed<S: Summation, R: Real, const D: usize, Sc: Scene<D>>(
        &self,
        scene: &Sc,
        carry: &mut Self::Carry<R, D, S>,
        h: R,
    ) -> Result<(), StepFailure>;

    /// [`Scheme::state`] with sums `S`.
    fn state_summed<S: Summation, R: Real, const D: usize>(
        &self,
        carry: &Self::Carry<R, D, S>,
        h: R,
    ) -> State<D, R>;
}

/// Makes a [`Summable`] type a [`Scheme`] with every addition [`Rounded`]:
/// `rounded_scheme!(Type, |scheme| claims)`, where `claims` is the
/// `&SchemeMeta` of `scheme: &Type`.
macro_rules! rounded_scheme {
    ($ty:ty, |$scheme:ident| $meta:expr) => {
        impl Scheme for $ty {
            type Carry<R: Real, const D: usize> = <$ty as Summable>::Carry<R, D, Rounded>;

            fn meta(&self) -> &SchemeMeta {
                let $scheme = self;
                $meta
            }

            fn start<R: Real, const D: usize, S: Scene<D>>(
                &self,
                scene: &S,
                state: &State<D, R>,
                h: R,
            ) -> Self::Carry<R, D> {
                self.start_summed::<Rounded, R, D, S>(scene, state, h)
            }

            #[inline(always)]
            fn step<R: Real, const D: usize, S: Scene<D>>(
                &self,
                scene: &S,
                carry: &mut Self::Carry<R, D>,
                h: R,
            ) -> Result<(), StepFailure> {
                self.step_summed::<Rounded, R, D, S>(scene, carry, h)
            }

            fn state<R: Real, const D: usize>(
                &self,
                carry: &Self::Carry<R, D>,
                h: R,
            ) -> State<D, R> {
                self.state_summed::<Rounded, R, D>(carry, h)
            }
        }
    };
}

pub(super) use rounded_scheme;

/// A [`Summable`] scheme run with compensated ([`Kahan`]) sums under its own
/// id: the same map in exact arithmetic, the same claims and force
/// evaluations, with the round-off of its coordinate updates carried along
/// instead of lost.
#[derive(Clone, Copy, Debug)]
pub struct Compensated<P> {
    /// The variant's claims (those of `plain`, under its own id).
    pub meta: SchemeMeta,
    /// The scheme it runs.
    pub plain: P,
}

impl<P: Summable> Scheme for Compensated<P> {
    type Carry<R: Real, const D: usize> = P::Carry<R, D, Kahan>;

    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }

    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        state: &State<D, R>,
        h: R,
    ) -> Self::Carry<R, D> {
        self.plain.start_summed::<Kahan, R, D, S>(scene, state, h)
    }

    #[inline(always)]
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        carry: &mut Self::Carry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        self.plain.step_summed::<Kahan, R, D, S>(scene, carry, h)
    }

    fn state<R: Real, const D: usize>(&self, carry: &Self::Carry<R, D>, h: R) -> State<D, R> {
        self.plain.state_summed::<Kahan, R, D>(carry, h)
    }
}

/// The two-step Störmer-Verlet scheme with both positions carried as
/// `value + low`; its central-difference velocity subtracts the values and
/// the low parts separately, so it no longer divides a difference rounded at
/// `eps |q|` by `2h`. Start-up and read-out are those of [`StormerVerlet`].
pub const STORMER_VERLET_COMPENSATED: Compensated<StormerVerlet> = Compensated {
    meta: SchemeMeta {
        id: "stormer-verlet-compensated",
        name: "Störmer-Verlet (two-step), compensated summation",
        reference: "StormerVerlet with positions carried to twice the working precision: W. Kahan, Commun. ACM 8, 40 (1965); D. E. Knuth, The Art of Computer Programming 2, 4.2.2",
        ..StormerVerlet::META
    },
    plain: StormerVerlet,
};

/// Leap-frog with the position and the half-step velocity each carried as
/// `value + low`. Start-up and read-out are those of [`Leapfrog`].
pub const LEAPFROG_COMPENSATED: Compensated<Leapfrog> = Compensated {
    meta: SchemeMeta {
        id: "leapfrog-compensated",
        name: "leap-frog, compensated summation",
        reference: "Leapfrog with compensated position and velocity sums: W. Kahan, Commun. ACM 8, 40 (1965); D. E. Knuth, The Art of Computer Programming 2, 4.2.2",
        ..Leapfrog::META
    },
    plain: Leapfrog,
};

/// Velocity Verlet (kick-drift-kick) with compensated position and velocity sums.
pub const VELOCITY_VERLET_COMPENSATED: Compensated<SplittingTable> = Compensated {
    meta: SchemeMeta {
        id: "velocity-verlet-compensated",
        name: "velocity Verlet (kick-drift-kick), compensated summation",
        reference: "VELOCITY_VERLET with compensated position and velocity sums: W. Kahan, Commun. ACM 8, 40 (1965); D. E. Knuth, The Art of Computer Programming 2, 4.2.2",
        ..VELOCITY_VERLET.meta
    },
    plain: VELOCITY_VERLET,
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
    (StormerVerlet, STORMER_VERLET_COMPENSATED),
    (Leapfrog, LEAPFROG_COMPENSATED),
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

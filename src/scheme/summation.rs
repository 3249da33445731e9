//! How a scheme adds an increment to a coordinate: rounded, or compensated.
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
//! factor `h w` than what rounded sums lose. Every carry keeps the low parts
//! beside the values; nothing is allocated and every scalar type works (dual
//! numbers carry the same compensation in their derivative parts).
//!
//! A scheme written once over a [`Summation`] ([`Summable`]: the Verlet
//! forms) is the catalogue's scheme with [`Rounded`] sums, bit for bit, and
//! wrapped in [`Compensated`] runs the same code with [`Kahan`] sums.

use super::{Scheme, SchemeMeta, StepFailure};
use crate::scene::Scene;
use crate::state::{Real, State};
use nalgebra::SVector;
use std::fmt::Debug;

/// `(s, e)` with `s = fl(a + b)` and `s + e = a + b` exactly, componentwise
/// (Knuth's TwoSum: six operations, no comparison, exact for any magnitudes
/// in round-to-nearest binary arithmetic without overflow).
#[inline(always)]
pub(super) fn two_sum<R: Real, const D: usize>(
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

    /// What rounding the coordinate to working precision dropped: zero for
    /// a rounded sum, the low part for a compensated one.
    fn low<R: Real, const D: usize>(sum: &Self::Sum<R, D>) -> SVector<R, D>;

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
    fn low<R: Real, const D: usize>(_: &SVector<R, D>) -> SVector<R, D> {
        SVector::zeros()
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

    #[inline(always)]
    fn low<R: Real, const D: usize>(sum: &Summed<R, D>) -> SVector<R, D> {
        sum.low
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

    /// [`Scheme::compensation`] with sums `S`: the low parts of the
    /// coordinates the state is read from.
    fn compensation_summed<S: Summation, R: Real, const D: usize>(
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

    fn compensation<R: Real, const D: usize>(
        &self,
        carry: &Self::Carry<R, D>,
        h: R,
    ) -> State<D, R> {
        self.plain.compensation_summed::<Kahan, R, D>(carry, h)
    }
}

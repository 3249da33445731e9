//! The compensated variants of the three Verlet forms, and their pairing
//! with the plain forms for the round-off studies.
//!
//! Each variant is its plain twin's code run with compensated sums
//! ([`super::Summation`]). The variants are not in the main
//! [`super::catalogue`]: at the steps the catalogue's studies use, their
//! results are those of their plain twins to within round-off a million
//! times below the truncation error, so they would add rows that differ only
//! in digits the studies do not resolve. They are measured by the round-off
//! studies ([`crate::study::round_off::floor`],
//! [`crate::study::round_off::longrun`]), which is where they differ, and
//! their order, symplecticity and time symmetry are tested like any
//! catalogue scheme's.

use super::splitting::{SplittingTable, VELOCITY_VERLET};
use super::summation::Compensated;
use super::verlet::{Leapfrog, StormerVerlet};
use super::{Scheme, SchemeMeta, SchemeVisitor, scheme_ids};
use crate::error::Error;

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

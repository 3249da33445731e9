//! The one registry of every scheme. Adding a scheme is one file (or one
//! table) plus one line here; every test, study and report loops over it.

use super::composition::{FOREST_RUTH, KAHAN_LI8, YOSHIDA6};
use super::nystrom_splitting::{
    BLANES_MOAN_SRKN11, MCLACHLAN_ATELA4, MCLACHLAN_SB3A4, MCLACHLAN_SB3A5,
};
use super::nystrom_tables::{DPRKN6, NYSTROM4};
use super::splitting::{EULER_CROMER, PEFRL, POSITION_VERLET, SplittingTable, VELOCITY_VERLET};
use super::{Euler, ImplicitMidpoint, Leapfrog, Rk4, Scheme, SchemeMeta, StormerVerlet};
use crate::error::Error;

/// Something to do with one scheme, whatever its concrete type: the way to
/// run generic, statically dispatched code on a scheme chosen at run time.
pub trait SchemeVisitor {
    /// What the visit produces.
    type Output;
    /// Called with the chosen scheme.
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output;
}

macro_rules! catalogue {
    ($($scheme:expr),* $(,)?) => {
        /// The metadata of every scheme in the catalogue, in catalogue order.
        pub fn catalogue() -> Vec<&'static SchemeMeta> {
            vec![$( $scheme.meta() ),*]
        }

        /// Runs `visitor` on the scheme with this id.
        pub fn visit_scheme<V: SchemeVisitor>(id: &str, visitor: V) -> Result<V::Output, Error> {
            $( if $scheme.meta().id == id { return Ok(visitor.visit(&$scheme)); } )*
            Err(Error::UnknownScheme { id: id.to_string(), valid: scheme_ids().join(", ") })
        }
    };
}

catalogue![
    Euler,
    EULER_CROMER,
    StormerVerlet,
    Leapfrog,
    VELOCITY_VERLET,
    POSITION_VERLET,
    ImplicitMidpoint,
    Rk4,
    FOREST_RUTH,
    PEFRL,
    YOSHIDA6,
    KAHAN_LI8,
    MCLACHLAN_ATELA4,
    MCLACHLAN_SB3A4,
    MCLACHLAN_SB3A5,
    BLANES_MOAN_SRKN11,
    NYSTROM4,
    DPRKN6,
];

/// Every scheme id, in catalogue order.
pub fn scheme_ids() -> Vec<&'static str> {
    catalogue().iter().map(|m| m.id).collect()
}

/// Every splitting table of the catalogue, compositions included: the one
/// list that tests of weights, symmetry and order conditions loop over.
pub const TABLES: &[&SplittingTable] = &[
    &EULER_CROMER,
    &VELOCITY_VERLET,
    &POSITION_VERLET,
    &PEFRL,
    &FOREST_RUTH,
    &YOSHIDA6,
    &KAHAN_LI8,
    &MCLACHLAN_ATELA4,
    &MCLACHLAN_SB3A4,
    &MCLACHLAN_SB3A5,
    &BLANES_MOAN_SRKN11,
];

//! The shared mathematics under the studies: least-squares fits of power
//! laws and orders with their intervals ([`fit`]), the choice of the rungs a
//! fit may use ([`window`]), the tangent map of a step ([`tangent`]), and
//! the order conditions of a tableau ([`conditions`], public as
//! `stepladder::conditions`), and double-double arithmetic for the sums
//! that doubles cannot resolve ([`dd`]). Nothing here knows a study; every study builds
//! on it.

pub mod conditions;
pub mod dd;
pub mod fit;
pub mod tangent;
pub mod window;

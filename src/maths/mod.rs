//! The shared mathematics under the studies: least-squares fits of power
//! laws and orders with their intervals ([`fit`]), the choice of the rungs a
//! fit may use ([`window`]), the tangent map of a step ([`tangent`]).
//! Nothing here knows a study; every study builds on it.

pub mod fit;
pub mod tangent;
pub mod window;

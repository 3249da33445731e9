//! The harness's own tests, in one binary so that the catalogue x scenes
//! suite, which several of them judge, runs once (see [`common::suite`]).

mod adaptive;
mod audit;
mod bad_input;
mod broken;
mod catalogue;
mod cli;
mod common;
mod corpus;
mod figures;
mod geometry;
mod hard;
mod implicit;
mod input_properties;
mod lab_units;
mod nbody;
mod nystrom_conditions;
mod order;
mod order_conditions;
mod pins;
mod properties;
mod race;
mod report;
mod roundoff;
mod sensitivity;
mod snapshots;
mod speed;
mod stability;

//! The lab's own pieces checked from outside: the corpus's tables against
//! their order conditions and stated defects, its scenes, the held-out
//! batch, and the report's Markdown. They live in the harness, not in the
//! lab's source, so that the lab is compiled once (for the command and this
//! binary) rather than a second time as its own test crate.

mod broken;
mod correct;
mod dd_reference;
mod held_out;
mod markdown;
mod peer;
mod reached_for_good;
mod resolution;
mod scenes;

//! Nothing here: the crate exists for its tests, which guard integrators with
//! stepladder as any downstream crate would.

//! A held-out batch of the verdict corpus: integrators and scenes written
//! apart from the harness and from the other batches ([`super::correct`],
//! [`super::broken`]), each pair with the verdict theory says a correct
//! harness must give.
//!
//! Scenes (all here, each checked by the scene check in the tests): a
//! Lennard-Jones trimer vibrating about its equilateral minimum (`D = 6`),
//! the three-dimensional Kepler problem on an inclined eccentric orbit with
//! its exact solution from Kepler's equation (`D = 3`), the periodic Toda
//! lattice of three particles (integrable, `D = 3`), the double well
//! `V = (x^2 - 1)^2` on an orbit above the barrier with its exact solution
//! `x = A cn(w t, m)` (`D = 1`), two coupled oscillators with incommensurate
//! normal frequencies and their exact solution (`D = 2`), and a planar star
//! with three planets in mass-weighted coordinates (`D = 8`).
//!
//! Schemes: Beeman's algorithm, the fourth-order Adams-Bashforth-Moulton
//! predictor-corrector with a Runge-Kutta start-up, the three-stage Lobatto
//! IIIA-IIIB partitioned pair, Butcher's sixth-order seven-stage
//! Runge-Kutta method, Runge's third-order method, Kutta's 3/8 rule, the
//! Dormand-Prince RKN6(4)6FD Runge-Kutta-Nyström method, the Candy-Rozmus
//! (drift-first) fourth-order composition and Blanes and Moan's symplectic
//! RKN method `SRKN_6^b`; and plausible bugs in them (a sign typo in Beeman,
//! swapped corrector weights, a cold multistep start, a conjugate pair of
//! weights swapped, a force lagging one drift behind, a flipped weight, the
//! wrong tableau in half a partitioned pair, a stale closing force, swapped
//! stage coefficients, velocities from a first-order difference).
//!
//! Notation: `z = h w` with `w` the scene's angular frequency `2 pi / T`;
//! "relative" errors are phase-space distances divided by the scene's
//! [`stepladder::scene::Scene::scale`].

mod scenes;
mod schemes;

pub use scenes::*;
pub use schemes::*;

use crate::corpus::{Entry, Expect, Expected};

// ======================================================================= entries

/// Broken on the order claim only; the other claims not judged.
const ORDER_FAILS: Expected = Expected::ANY.order(Expect::Fail);

/// Broken on the order, symplecticity and symmetry claims; the energy not
/// judged (the long run blows up or its solve fails).
const STALE_FORCE: Expected = Expected::ANY
    .order(Expect::Fail)
    .symplectic(Expect::Fail)
    .reversible(Expect::Fail);

/// The held-out entries: 17 correct pairs and 20 broken ones (a data list,
/// one entry per pair).
pub fn entries() -> Vec<Entry> {
    vec![
        // ------------------------------------------------------------ correct
        Entry::correct(
            &BEEMAN,
            LjTrimer,
            "Beeman's positions are exactly the Störmer-Verlet recursion and its velocities a local formula of them: global order 2 (measured 2.00 on the trimer); it claims neither symplecticity nor symmetry, so nothing is promised of its energy or tangent map and every claim must pass.",
        ),
        Entry::correct(
            &BEEMAN,
            DoubleWell,
            "Order 2 on any smooth scene (measured 2.00 against the cn solution); its one-step map is neither symplectic (det - 1 = -0.40 at h = 0.3) nor reversible, but it claims neither, so every claim must pass.",
        ),
        Entry::correct(
            &ABM4,
            Kepler3d,
            "AB4 predictor, AM4 corrector (PECE) with an RK4 start-up of local order 5: global order 4 (4.03 on the oscillator, 4.7 pre-asymptotically on this orbit); a multistep method claiming nothing geometric, so even its energy wander over 10^4 periods (|dE| up to 0.5) must not fail it.",
        ),
        Entry::correct(
            &ABM4,
            CoupledOscillators,
            "Order 4 on this linear scene (measured 4.1); PECE Adams methods are weakly unstable on the imaginary axis and its energy creeps up over the long run, but it claims neither symplecticity nor symmetry: every claim must pass.",
        ),
        Entry::correct(
            &LOBATTO_IIIA_IIIB,
            DoubleWell,
            "The three-stage Lobatto IIIA-IIIB pair is order 4, symplectic (b_i av_ij + b_j aq_ji = b_i b_j exactly) and symmetric, its implicit stage solved to round-off (det - 1 = 4e-12, return 7e-15); the energy error stays bounded (7.7e-6 in the first and last thousand periods): every claim must pass.",
        ),
        Entry::correct(
            &LOBATTO_IIIA_IIIB,
            Toda3,
            "Order 4 (measured 4.00), symplectic and symmetric; on the integrable Toda lattice its energy error stays bounded (6.6e-8 over 10^4 linearised periods): every claim must pass.",
        ),
        Entry::correct(
            &BUTCHER6,
            CoupledOscillators,
            "Butcher's seven-stage method satisfies all 37 order conditions up to six exactly and fails at seven: order 6 (measured 6.00 on this linear scene); explicit, it claims neither symplecticity nor symmetry.",
        ),
        Entry::correct(
            &BUTCHER6,
            Planets4,
            "Order 6 on a smooth, collision-free four-body orbit (measured 6.4 against a fine reference between T/25 and T/50); it claims nothing geometric, so every claim must pass.",
        ),
        Entry::correct(
            &RUNGE3,
            Kepler3d,
            "Runge's four-stage method is exactly third order (sum b c a c = 1/6, not 1/8, blocks order four; measured 3.01 on the orbit); it claims nothing geometric.",
        ),
        Entry::correct(
            &RUNGE3,
            LjTrimer,
            "Third order (measured 3.02 on the trimer vibration); explicit, claiming neither symplecticity nor symmetry: every claim must pass.",
        ),
        Entry::correct(
            &CANDY_ROZMUS4,
            Kepler3d,
            "The drift-first triple jump of position Verlet is order 4 (its series matches exp(h(A+B)) to h^4), symplectic and symmetric; on the eccentric orbit its energy error stays bounded (5.3e-5 in the first and last thousand periods).",
        ),
        Entry::correct(
            &CANDY_ROZMUS4,
            Planets4,
            "Order 4 (measured 3.96), symplectic, symmetric; the hierarchical system stays regular (neighbouring planets never closer than 1.0 over 10^4 inner periods) and the energy error bounded (1e-11).",
        ),
        Entry::correct(
            &DPRKN6,
            Kepler3d,
            "Dormand-Prince RKN6(4)6FD, coefficients matching the published closed forms in sqrt(8581) to round-off: order 6 (6.00 on the oscillator, 6.8 pre-asymptotically on this orbit); it claims nothing geometric.",
        ),
        Entry::correct(
            &DPRKN6,
            Toda3,
            "Order 6 (measured 6.06 against a fine reference); an explicit Nyström method claiming neither symplecticity nor symmetry: every claim must pass.",
        ),
        Entry::correct(
            &SRKN6B,
            LjTrimer,
            "Blanes-Moan SRKN_6^b is a palindromic composition of exact flows of order 4 (series checked to h^4): symplectic and symmetric, with a bounded energy error (1e-10) on the regular small-amplitude vibration.",
        ),
        Entry::correct(
            &SRKN6B,
            DoubleWell,
            "Order 4 (measured 4.09), symplectic and symmetric; on the 1-D orbit above the barrier its energy error stays bounded (4.2e-8 over 10^4 periods): every claim must pass.",
        ),
        Entry::correct(
            &KUTTA38,
            Toda3,
            "Kutta's 3/8 rule satisfies all eight trees up to order four and fails at five: order 4 (measured 4.04 on the lattice); it claims nothing geometric.",
        ),
        // ------------------------------------------------------------- broken
        Entry::broken(
            &BEEMAN_SIGN_TYPO,
            LjTrimer,
            ORDER_FAILS,
            "Typing +a(n-1) in Beeman's position update makes the h^2 coefficient 5/6: Störmer's recursion perturbed by -(h/3) da/dt plus an O(h) start error, ORDER 1 < 2, with a relative error of 1.1e-3 at T/1000 (measured order 0.99), far above 1e-7.",
        ),
        Entry::broken(
            &BEEMAN_SIGN_TYPO,
            Toda3,
            ORDER_FAILS,
            "The +a(n-1) typo makes Beeman first order (an -(h/3) da/dt force perturbation): relative error 2.3e-2 at T/1000, measured order 0.97, so the claim of order 2 must fail.",
        ),
        Entry::broken(
            &BEEMAN_CLAIMS_SYMMETRIC,
            DoubleWell,
            Expected::PASS.reversible(Expect::Fail),
            "Beeman's (q, v) map is not time-symmetric (50 steps of h = 0.1 there and back miss by 0.18 on a scale of 1.6), so the claim must fail; its positions are Störmer-Verlet's and its velocities a local formula of them, so the energy error stays a bounded oscillation (7.5e-3 in the first and last thousand periods) and order 2 and the energy pass, symplecticity not being claimed.",
        ),
        Entry::broken(
            &ABM4_SWAPPED,
            CoupledOscillators,
            ORDER_FAILS,
            "Corrector weights (19, 9, -5, 1)/24 still sum to one but have first moment 22/24, not 1/2: a local error (5/12) h^2 f', ORDER 1 < 4 (relative error 0.12 at T/1000, measured order 0.92).",
        ),
        Entry::broken(
            &ABM4_SWAPPED,
            Toda3,
            ORDER_FAILS,
            "The swapped corrector weights leave a consistent but first-order method: relative error 5.4e-2 at T/1000, measured order 0.95, against the claimed 4.",
        ),
        Entry::broken(
            &ABM4_COLD_START,
            Kepler3d,
            ORDER_FAILS,
            "Past slopes set to f(y0) are O(h) wrong and enter the first steps multiplied by h: O(h^2) start errors carried along the orbit, ORDER 2 < 4 (relative error 3.9e-3 at T/1000, measured order 2.00).",
        ),
        Entry::broken(
            &ABM4_COLD_START,
            Planets4,
            ORDER_FAILS,
            "The cold start caps the fourth-order Adams pair at ORDER 2: relative error 1.7e-4 at T/1000 against a fine reference, measured order 2.00.",
        ),
        Entry::broken(
            &DPRKN6_SWAPPED,
            Kepler3d,
            ORDER_FAILS,
            "Swapping the conjugate weights (84119543 +- 366727 sqrt(8581))/409622616 of b_bar keeps sum b_bar = 1/2 but makes sum b_bar c = 1/6 + 0.068: a local position error 0.068 h^3 a' v, ORDER 2 < 6 (relative error 6.1e-4 at T/1000, measured order 1.84).",
        ),
        Entry::broken(
            &DPRKN6_SWAPPED,
            LjTrimer,
            ORDER_FAILS,
            "The b_bar sign typo leaves ORDER 2: relative error 1.3e-6 at T/1000 (measured order 2.00), thirteen times the 1e-7 threshold and far above round-off.",
        ),
        Entry::broken(
            &CANDY_ROZMUS4_LAGGED,
            Toda3,
            STALE_FORCE,
            "Kicks with the force from before the preceding drift miss the impulse by 0.9746 h^2 a' v a step: ORDER 1 < 4 (relative error 6.7e-2 at T/1000, order 1.06), and no longer exact flows, so NOT symplectic and NOT symmetric (det = 1 + 0.975 z^2 on the oscillator); the long run blows up, so its energy verdict is left open.",
        ),
        Entry::broken(
            &CANDY_ROZMUS4_LAGGED,
            LjTrimer,
            STALE_FORCE.energy(Expect::Fail),
            "The lagged force makes the composition ORDER 1 (relative error 3.2e-3 at T/1000, order 1.07), neither symplectic nor symmetric; its determinant above one pumps energy in until the trimer dissociates within the long run (|dE| = 3.2 against a vibrational energy of 0.086), so the energy claim fails too.",
        ),
        Entry::broken(
            &SRKN6B_SIGN_FLIPPED,
            Kepler3d,
            ORDER_FAILS
                .energy(Expect::Pass)
                .symplectic(Expect::Pass)
                .reversible(Expect::Pass),
            "Flipping b3 (with b4 recomputed from the sum) keeps consistency, the palindrome and exact flows, hence symplecticity, symmetry and a bounded energy, but breaks the third-order condition: ORDER 2 < 4, relative error 2.9e-4 at T/1000 (measured order 2.00); only the order must fail.",
        ),
        Entry::broken(
            &SRKN6B_SIGN_FLIPPED,
            Planets4,
            ORDER_FAILS
                .energy(Expect::Pass)
                .symplectic(Expect::Pass)
                .reversible(Expect::Pass),
            "Still a symplectic, symmetric palindrome of exact flows (energy error bounded at 3e-10) but only ORDER 2 after the sign flip: relative error 3.0e-5 at T/1000, measured order 2.00, against the claimed 4.",
        ),
        Entry::broken(
            &LOBATTO_IIIA_BOTH,
            DoubleWell,
            Expected::PASS.symplectic(Expect::Fail),
            "Lobatto IIIA alone is order 4 and symmetric but not symplectic (2 b1 a11 = 0 against b1^2 = 1/36; det - 1 = 6.4e-4 at h = 0.3 on this nonlinear well): the symplectic claim must fail, while the order, reversibility and energy (a symmetric method on a reversible periodic orbit: bounded, 4.9e-6) pass.",
        ),
        Entry::broken(
            &LOBATTO_IIIA_BOTH,
            Toda3,
            Expected::PASS.symplectic(Expect::Fail),
            "IIIA for the velocities too: order 4 and symmetric, but its tangent map is not symplectic on the nonlinear lattice (|J^T W J - W| = 3e-4 at h = T/10); symmetric on a reversible integrable scene, so no energy drift (4.1e-8 over 10^4 periods): only symplecticity must fail.",
        ),
        Entry::broken(
            &BUTCHER6_SWAPPED,
            CoupledOscillators,
            ORDER_FAILS,
            "Swapping a42 and a43 keeps the row sums but breaks the tall third-order tree sum b a c by 3/32, which linear problems see: ORDER 2 < 6 (relative error 3.0e-4 at T/1000, measured order 2.00).",
        ),
        Entry::broken(
            &BUTCHER6_SWAPPED,
            Planets4,
            ORDER_FAILS,
            "The a42/a43 swap leaves ORDER 2 (the tall third-order tree off by 3/32): relative error 1.6e-4 at T/1000 against a fine reference, measured order 1.99, against the claimed 6.",
        ),
        Entry::broken(
            &BUTCHER6_DIFFERENCED,
            Kepler3d,
            ORDER_FAILS,
            "Positions from the sixth-order method but velocities reported as (q(n) - q(n-1))/h = v - h/2 a + O(h^2): ORDER 1 < 6 in phase space (relative error 7.8e-3 at T/1000, measured order 1.00).",
        ),
        Entry::broken(
            &LOBATTO_STALE_CLOSING_FORCE,
            Toda3,
            STALE_FORCE,
            "Closing the velocity with k1 in place of k3 makes the velocity weights (1/3, 2/3, 0): sum b c = 1/3, ORDER 1 < 4 (relative error 1.1e-2 at T/1000, measured order 1.01), and the step is neither symplectic nor symmetric (det = 1 + z^2/6 on the oscillator); the long run blows up until the solve fails, so the energy is left open.",
        ),
        Entry::broken(
            &LOBATTO_STALE_CLOSING_FORCE,
            DoubleWell,
            STALE_FORCE,
            "The start-of-step closing force leaves ORDER 1 (relative error 0.27 at T/1000, measured order 0.98) and destroys symplecticity (det - 1 = 0.12 at h = 0.3) and symmetry (return error 4.7 after 50 steps there and back); energy left open (the run blows up).",
        ),
    ]
}

//! The corpus's pairs: each scheme on the scenes that test it, with the
//! verdicts theory requires and why.

use super::broken::*;
use super::correct::*;
use super::scenes::{FigureEight, FputChain, HenonHeiles, Morse, Pendulum};
use super::{Entry, Expect, Expected};
use stepladder::scene::{Anharmonic, Harmonic, Hidden, KeplerCircular, KeplerEccentric};
use stepladder::scheme::{
    EULER_CROMER, Euler, FOREST_RUTH, ImplicitMidpoint, KAHAN_LI8, Leapfrog, PEFRL, Rk4,
    StormerVerlet, VELOCITY_VERLET, YOSHIDA6,
};

fn eccentric(e: f64) -> KeplerEccentric {
    KeplerEccentric::new(e).expect("a valid eccentricity")
}

fn well(x0: f64) -> Anharmonic {
    Anharmonic::new(1.0, 1.0, x0, 0.0).expect("a trapped orbit")
}

const ORDER: Expected = Expected::ANY.order(Expect::Fail);

/// Correct pairs: every claim holds, so every verdict must pass. A data
/// list, one entry per pair, long by design.
pub fn correct() -> Vec<Entry> {
    vec![
        Entry::correct(
            &FSAL_VERLET,
            KeplerEccentric::default(),
            "velocity Verlet as a stateful black box that keeps its last force: every claim holds when each run starts from a fresh state",
        ),
        Entry::correct(
            &FSAL_VERLET,
            FigureEight,
            "the same on the figure-eight, without an exact solution",
        ),
        Entry::correct(
            &HEUN,
            eccentric(0.5),
            "explicit trapezoidal RK2: order 2 (Butcher conditions), neither symplectic nor symmetric; nothing geometric is claimed",
        ),
        Entry::correct(
            &HEUN,
            Hidden(well(0.8)),
            "order 2 on a smooth trapped orbit, measured without the exact solution",
        ),
        Entry::correct(
            &EXPLICIT_MIDPOINT,
            Harmonic::new(7.0, 0.2, 1.0).expect("valid"),
            "explicit midpoint RK2, order 2, on an oscillator of other units",
        ),
        Entry::correct(
            &KUTTA3,
            eccentric(0.6),
            "Kutta's third-order RK: odd order 3 on an eccentric orbit, where the h^4 term dominates at coarse steps and the ladder must run on to see h^3",
        ),
        Entry::correct(
            &KUTTA3,
            Pendulum::default(),
            "order 3 on the pendulum near its separatrix, no exact solution",
        ),
        Entry::correct(
            &KUTTA3,
            FigureEight,
            "order 3 on a six-dimensional three-body choreography",
        ),
        Entry::correct(
            &RUTH3,
            KeplerCircular,
            "Ruth's method: order 3, symplectic (a splitting), not symmetric; bounded energy",
        ),
        Entry::correct(
            &RUTH3,
            HenonHeiles,
            "non-symmetric symplectic, order 3, on a regular non-integrable orbit",
        ),
        Entry::correct(&RUTH3, well(0.9), "order 3 near the well's separatrix"),
        Entry::correct(
            &DORMAND_PRINCE5,
            eccentric(0.7),
            "Dormand-Prince fifth-order solution at fixed step: odd order 5",
        ),
        Entry::correct(
            &DORMAND_PRINCE5,
            FigureEight,
            "order 5 in six dimensions without an exact solution",
        ),
        Entry::correct(
            &DORMAND_PRINCE5,
            Morse::default(),
            "order 5 on an exact scene the harness has never seen",
        ),
        Entry::correct(
            &DORMAND_PRINCE5,
            Harmonic::new(50.0, 1.0, 0.0).expect("valid"),
            "order 5 on a stiff-frequency oscillator (the time scale follows w0)",
        ),
        Entry::correct(
            &RKN4,
            Pendulum::default(),
            "classical Runge-Kutta-Nystrom, order 4 with three forces a step",
        ),
        Entry::correct(&RKN4, FputChain, "order 4 on a four-mass FPUT chain"),
        Entry::correct(
            &TRAPEZOIDAL,
            eccentric(0.5),
            "implicit trapezoidal rule: symmetric, not symplectic, order 2; a symmetric scheme has no secular drift on a reversible integrable problem (GNI XI)",
        ),
        Entry::correct(
            &TRAPEZOIDAL,
            well(0.7),
            "symmetric non-symplectic implicit scheme on a nonlinear 1-D well: bounded energy, returns on reversal",
        ),
        Entry::correct(
            &TRAPEZOIDAL,
            HenonHeiles,
            "symmetric non-symplectic on a regular orbit of a near-integrable problem: no secular drift",
        ),
        Entry::correct(
            &GAUSS4,
            eccentric(0.8),
            "two-stage Gauss collocation: implicit, symplectic, symmetric, order 4",
        ),
        Entry::correct(
            &GAUSS4,
            Pendulum::default(),
            "Gauss order 4 near the pendulum's separatrix",
        ),
        Entry::correct(
            &GAUSS4,
            Hidden(well(0.5)),
            "Gauss order 4 measured without the exact solution",
        ),
        Entry::correct(
            &LOBATTO_IIIA4,
            KeplerCircular,
            "three-stage Lobatto IIIA: implicit, symmetric, not symplectic, order 4",
        ),
        Entry::correct(
            &LOBATTO_IIIA4,
            Morse::default(),
            "symmetric non-symplectic order 4 on an anharmonic exact scene",
        ),
        Entry::correct(
            &SUZUKI4,
            FigureEight,
            "Suzuki's fractal composition: order 4, symplectic, symmetric, in six dimensions",
        ),
        Entry::correct(
            &SUZUKI4,
            well(0.95),
            "order 4 close to the well's separatrix",
        ),
        Entry::correct(
            &YOSHIDA6_RECURSIVE,
            eccentric(0.9),
            "Yoshida's recursive sixth order (nine stages) on a sharp pericentre",
        ),
        Entry::correct(&YOSHIDA6_RECURSIVE, FputChain, "order 6 on the FPUT chain"),
        Entry::correct(
            &Rk4,
            well(0.95),
            "RK4 near the separatrix, where its error terms cancel at the default end time (the harness must still decide)",
        ),
        Entry::correct(
            &KAHAN_LI8,
            well(0.95),
            "order 8 near the separatrix, where round-off is magnified by the shear of the flow",
        ),
        Entry::correct(
            &Euler,
            well(0.95),
            "first order on a slow orbit: it must resolve it within the step cap",
        ),
        Entry::correct(
            &Rk4,
            FigureEight,
            "RK4 in six dimensions without an exact solution",
        ),
        Entry::correct(&PEFRL, FigureEight, "PEFRL order 4 in six dimensions"),
        Entry::correct(&YOSHIDA6, FigureEight, "order 6 in six dimensions"),
        Entry::correct(&KAHAN_LI8, FigureEight, "order 8 in six dimensions"),
        Entry::correct(
            &Rk4,
            Pendulum::default(),
            "RK4 on the pendulum at large amplitude",
        ),
        Entry::correct(
            &PEFRL,
            Pendulum::default(),
            "PEFRL on the pendulum at large amplitude",
        ),
        Entry::correct(
            &YOSHIDA6,
            HenonHeiles,
            "order 6 on a regular Hénon-Heiles orbit",
        ),
        Entry::correct(
            &KAHAN_LI8,
            HenonHeiles,
            "order 8 on a regular Hénon-Heiles orbit",
        ),
        Entry::correct(
            &Euler,
            Pendulum::default(),
            "explicit Euler, order 1, without an exact solution",
        ),
        Entry::correct(
            &VELOCITY_VERLET,
            FputChain,
            "velocity Verlet on the FPUT chain",
        ),
        Entry::correct(
            &Leapfrog,
            Morse::default(),
            "leap-frog on the Morse oscillator",
        ),
        Entry::correct(
            &StormerVerlet,
            eccentric(0.9),
            "the two-step form on a sharp pericentre, its round-off growing as N^(3/2)",
        ),
        Entry::correct(
            &ImplicitMidpoint,
            HenonHeiles,
            "implicit midpoint on a regular non-integrable orbit",
        ),
        Entry::correct(
            &EULER_CROMER,
            FigureEight,
            "symplectic Euler in six dimensions",
        ),
        Entry::correct(
            &FOREST_RUTH,
            Morse::default(),
            "Forest-Ruth on the Morse oscillator",
        ),
        Entry::correct(
            &Rk4,
            Hidden(KeplerCircular),
            "RK4 on the circular orbit with its exact solution withheld",
        ),
        Entry::correct(
            &VERLET_CLAIMS_ORDER1,
            Harmonic::default(),
            "an order claim is a lower bound: velocity Verlet is at least first order, so the claim holds",
        ),
        Entry::correct(
            &TRAPEZOIDAL_CLAIMS_SYMPLECTIC,
            Harmonic::default(),
            "on a linear scene the trapezoidal rule is the midpoint rule, which is symplectic: on this scene the claim holds",
        ),
    ]
}

/// Broken pairs: at least one claim is false on the scene and visible in
/// double precision, and its verdict must fail. A data list, one entry per
/// pair, long by design.
pub fn broken() -> Vec<Entry> {
    vec![
        Entry::broken(
            &UNDER_CLAIMED_VERLET,
            KeplerCircular,
            Expected::PASS.evaluations(Expect::Fail),
            "two force evaluations a step, one claimed: the map is velocity Verlet's, so order, energy, symplecticity and symmetry all hold, and only the count refutes the cost",
        ),
        Entry::broken(
            &UNDER_CLAIMED_VERLET,
            FigureEight,
            Expected::PASS.evaluations(Expect::Fail),
            "the same on the figure-eight, where each evaluation is the three bodies' forces",
        ),
        Entry::broken(
            &FIRST_COMPONENT_KICK,
            FigureEight,
            ORDER,
            "every component kicked with the first one's force: order 2 towards the solution of another equation, which the half-step comparison cannot tell from the scene's; its energy does not return to its initial value as h -> 0",
        ),
        Entry::broken(
            &SCALED_LAST_KICK,
            FigureEight,
            ORDER,
            "the last component's force scaled by 0.999: another equation, solved at order 2; the energy and momenta change by limits of order 1e-3 that do not shrink with h",
        ),
        Entry::broken(
            &SCALED_LAST_KICK,
            crate::corpus::held_out::Planets4,
            ORDER,
            "the same on a star with three planets in mass-weighted coordinates: the outer planet's force 0.1% weak",
        ),
        Entry::broken(
            &F32_STEP_VERLET,
            Harmonic::default(),
            ORDER,
            "the step rounded to f32: a phase error of up to 6e-8 w t that does not shrink with h, so the error stalls near 1e-8, far above the f64 round-off floor",
        ),
        Entry::broken(
            &F32_STEP_VERLET,
            KeplerCircular,
            ORDER,
            "the same stall on the circular orbit",
        ),
        Entry::broken(
            &FOREST_RUTH_4_DECIMALS,
            Harmonic::default(),
            ORDER,
            "weights retyped with four decimals: sum w^3 = 4.6e-5, so order 2; the h^2 term overtakes the h^4 one near T/1200, at errors around 1e-9",
        ),
        Entry::broken(
            &FOREST_RUTH_4_DECIMALS,
            well(0.5),
            ORDER,
            "the same order reduction on the anharmonic well",
        ),
        Entry::broken(
            &FOREST_RUTH_4_DECIMALS,
            KeplerCircular,
            ORDER,
            "the same on the circular orbit",
        ),
        Entry::broken(
            &FOREST_RUTH_4_DECIMALS,
            Pendulum::default(),
            ORDER,
            "the same without an exact solution",
        ),
        Entry::broken(
            &FOREST_RUTH_4_DECIMALS,
            Hidden(well(0.5)),
            ORDER,
            "the same with the exact solution withheld",
        ),
        Entry::broken(
            &YOSHIDA6_FIRST_WEIGHT,
            Harmonic::default(),
            ORDER,
            "one weight off by 1e-8: sum w = 1 + 1e-8, the flow of a time rescaled by 1 + 1e-8, order 0 (an error of 1.8e-7 at every step)",
        ),
        Entry::broken(
            &YOSHIDA6_FIRST_WEIGHT,
            eccentric(0.6),
            ORDER,
            "order 0 on the eccentric orbit",
        ),
        Entry::broken(
            &YOSHIDA6_PALINDROME,
            Harmonic::default(),
            ORDER,
            "outer weights +1e-8, middle -2e-8: symmetric, sum w^3 = -6.7e-8, order 2 below T/400 at errors of 1e-11 to 1e-13",
        ),
        Entry::broken(
            &YOSHIDA6_PALINDROME,
            well(0.5),
            ORDER,
            "the same order-2 defect on the well",
        ),
        Entry::broken(
            &KAHAN_LI8_8_DIGITS,
            Harmonic::default(),
            ORDER,
            "weights rounded to 8 digits: sum w - 1 = 1e-8, order 0",
        ),
        Entry::broken(
            &KAHAN_LI8_8_DIGITS,
            KeplerCircular,
            ORDER,
            "order 0 on the orbit",
        ),
        Entry::broken(
            &KAHAN_LI8_8_DIGITS,
            FigureEight,
            ORDER,
            "order 0 in six dimensions",
        ),
        Entry::broken(
            &KAHAN_LI8_8_DIGITS,
            Hidden(eccentric(0.6)),
            ORDER,
            "order 0 with the exact solution withheld: the scheme converges, to the wrong solution",
        ),
        Entry::broken(
            &RUTH3_SWAPPED_DRIFTS,
            KeplerCircular,
            ORDER,
            "two drift weights swapped: the order-2 condition fails, order 1",
        ),
        Entry::broken(
            &RUTH3_SWAPPED_DRIFTS,
            HenonHeiles,
            ORDER,
            "order 1 on Hénon-Heiles",
        ),
        Entry::broken(
            &RK4_STAGE3_TYPO,
            eccentric(0.5),
            ORDER,
            "third stage from the first stage's slopes: sum b a c = 1/12, not 1/6, order 2",
        ),
        Entry::broken(
            &RK4_STAGE3_TYPO,
            Pendulum::default(),
            ORDER,
            "order 2 on the pendulum",
        ),
        Entry::broken(
            &RK4_STAGE3_TYPO,
            Hidden(Harmonic::default()),
            ORDER,
            "order 2 with the exact solution withheld",
        ),
        Entry::broken(
            &RK4_WEIGHTS_TYPO,
            Harmonic::default(),
            ORDER,
            "weights (1, 2, 1, 2)/6: sum b c = 7/12, order 1",
        ),
        Entry::broken(
            &RK4_WEIGHTS_TYPO,
            FigureEight,
            ORDER,
            "order 1 in six dimensions",
        ),
        Entry::broken(
            &DORMAND_PRINCE5_ROUNDED_WEIGHT,
            Morse::default(),
            ORDER,
            "b1 rounded to four decimals: sum b = 1 - 4.6e-5, order 0",
        ),
        Entry::broken(
            &DORMAND_PRINCE5_ROUNDED_WEIGHT,
            FputChain,
            ORDER,
            "order 0 on the FPUT chain",
        ),
        Entry::broken(
            &GAUSS4_ROUNDED,
            Harmonic::default(),
            ORDER,
            "sqrt(3)/6 typed 0.2887: the order-3 conditions miss by 1.4e-5, order 2",
        ),
        Entry::broken(
            &GAUSS4_ROUNDED,
            KeplerCircular,
            ORDER,
            "order 2 on the orbit",
        ),
        Entry::broken(
            &STALE_KICK_VERLET,
            Harmonic::default(),
            Expected::ANY
                .order(Expect::Fail)
                .symplectic(Expect::Fail)
                .reversible(Expect::Fail)
                .energy(Expect::Fail),
            "the closing half kick reuses a(q_n): order 1, det J = 1 + (h w)^2/2, neither symplectic nor symmetric; the oscillator's energy grows",
        ),
        Entry::broken(
            &STALE_KICK_VERLET,
            KeplerCircular,
            Expected::ANY
                .order(Expect::Fail)
                .symplectic(Expect::Fail)
                .reversible(Expect::Fail),
            "the same bug on the orbit",
        ),
        Entry::broken(
            &STALE_KICK_VERLET,
            FigureEight,
            ORDER.symplectic(Expect::Fail),
            "the same bug in six dimensions",
        ),
        Entry::broken(
            &LEAPFROG_HALF_STEP_OUTPUT,
            KeplerCircular,
            ORDER.reversible(Expect::Fail).symplectic(Expect::Pass),
            "half-step velocity handed out as the whole-step one: order 1 in v; the (q, v) map is still symplectic but no longer symmetric",
        ),
        Entry::broken(
            &LEAPFROG_HALF_STEP_OUTPUT,
            FigureEight,
            ORDER,
            "unsynchronised output in six dimensions",
        ),
        Entry::broken(
            &LEAPFROG_NO_HALF_KICK,
            well(0.5),
            ORDER.reversible(Expect::Fail),
            "leap-frog started without its half kick: order 1, not symmetric",
        ),
        Entry::broken(
            &STORMER_EULER_START,
            eccentric(0.5),
            ORDER,
            "two-step form started with q1 = q0 + h v0: order 1",
        ),
        Entry::broken(
            &STORMER_EULER_START,
            HenonHeiles,
            ORDER,
            "the same start-up bug without an exact solution",
        ),
        Entry::broken(
            &MIDPOINT_TWO_ITERATIONS,
            eccentric(0.6),
            Expected::ANY
                .order(Expect::Pass)
                .symplectic(Expect::Fail)
                .reversible(Expect::Fail)
                .energy(Expect::Fail),
            "the midpoint rule cut to two fixed-point iterations: still order 2, but neither symplectic nor symmetric, so its energy drifts",
        ),
        Entry::broken(
            &MIDPOINT_TWO_ITERATIONS,
            Harmonic::default(),
            Expected::ANY
                .symplectic(Expect::Fail)
                .reversible(Expect::Fail)
                .energy(Expect::Fail),
            "det J = 1 - z^4/4 + z^6/16 on the oscillator: the energy decays secularly",
        ),
        Entry::broken(
            &VERLET_SIGN_FLIPPED,
            Harmonic::default(),
            ORDER,
            "solves x'' = +x: blows up at every step, though the exact motion is bounded",
        ),
        Entry::broken(
            &VERLET_SIGN_FLIPPED,
            KeplerCircular,
            ORDER,
            "a repulsive Sun: the runs converge, to the wrong motion",
        ),
        Entry::broken(
            &VERLET_SIGN_FLIPPED,
            well(0.5),
            ORDER,
            "the flipped well is a double well: a bounded wrong motion",
        ),
        Entry::broken(
            &RK4_CLAIMS_SYMPLECTIC,
            eccentric(0.6),
            Expected::ANY.symplectic(Expect::Fail).energy(Expect::Fail),
            "correct RK4 steps under a false claim of symplecticity: the tangent map is not symplectic and the energy drifts",
        ),
        Entry::broken(
            &RK4_CLAIMS_SYMPLECTIC,
            Harmonic::default(),
            Expected::ANY.symplectic(Expect::Fail).energy(Expect::Fail),
            "det J = 1 - z^6/72 on the oscillator: the energy decays",
        ),
        Entry::broken(
            &EULER_CROMER_CLAIMS_SYMMETRIC,
            KeplerCircular,
            Expected::ANY.reversible(Expect::Fail).energy(Expect::Pass),
            "a false claim of time symmetry; still symplectic, so its energy stays bounded",
        ),
        Entry::broken(
            &EULER_CROMER_CLAIMS_SYMMETRIC,
            Harmonic::default(),
            Expected::ANY.reversible(Expect::Fail),
            "the same false claim on the oscillator",
        ),
        Entry::broken(
            &TRAPEZOIDAL_CLAIMS_SYMPLECTIC,
            well(0.8),
            Expected::ANY.symplectic(Expect::Fail),
            "a false claim of symplecticity, refuted on a nonlinear scene",
        ),
        Entry::broken(
            &TRAPEZOIDAL_CLAIMS_SYMPLECTIC,
            eccentric(0.6),
            Expected::ANY.symplectic(Expect::Fail),
            "the same on the eccentric orbit",
        ),
        Entry::broken(
            &VERLET_CLAIMS_ORDER3,
            Pendulum::default(),
            ORDER,
            "velocity Verlet claiming order 3: its error falls as h^2",
        ),
        Entry::broken(
            &VERLET_CLAIMS_ORDER3,
            FputChain,
            ORDER,
            "the overclaim on the FPUT chain",
        ),
    ]
}

/// Every pair: the correct ones, then the broken ones, then the held-out
/// batch (written apart from the harness's rules, see [`super::held_out`]).
pub fn entries() -> Vec<Entry> {
    let mut all = correct();
    all.extend(broken());
    all.extend(super::held_out::entries());
    all
}

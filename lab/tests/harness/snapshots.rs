//! Change detectors: the suite's tables, rounded so they are identical on any
//! machine, pinned with insta in the top-level `snapshots/` folder. A diff
//! here means a refactor changed a result: review it with `cargo insta review`.

use super::common::settings;
use stepladder_lab::report::{
    adaptive_summary_table, geometry_table, order_table, phase_table, stability_table,
};

#[test]
fn suite_tables_are_unchanged() {
    let records = super::common::suite();
    settings(
        "Measured global order of every scheme on every scene (3 decimals), its interval, the \
         fitted window with its step sizes, the straight-line slope and the verdict.",
    )
    .bind(|| insta::assert_snapshot!("order_table", order_table(&records.order())));
    settings(
        "Energy class and largest relative energy error over 10^4 periods with the growth \
         exponent; det(J) - 1 and symplectic residual of the exact tangent map (round-off \
         shown as a bound); return error after 1000 steps forward and back; the verdicts.",
    )
    .bind(|| insta::assert_snapshot!("geometry_table", geometry_table(&records.cases)));
    settings("Leading relative phase error on the oscillator, measured and analytic.")
        .bind(|| insta::assert_snapshot!("phase_table", phase_table(&records.phase)));
    settings(
        "Linear stability on the oscillator: the largest stable z = h w0 (bisected to 1e-10, \
         shown to 6 decimals), the limit per force evaluation, every stable interval on a \
         scan to z = 1e6 and the growth per step below which round-off hides a growth; then, \
         for maps unstable at every step, the law det M - 1 = c z^k and the growth per step / \
         per period at z = 0.1 to 3. The Verlet family, Euler, RK4, Forest-Ruth and implicit \
         midpoint are also tested against their analytic limits, Euler's and DPRKN6's growth \
         against exact values (sqrt(1 + z^2); tests/check_dprkn6_stability.py); for the other \
         compositions this measurement is the answer.",
    )
    .bind(|| insta::assert_snapshot!("stability_table", stability_table(&records.stability)));
    settings(
        "Tolerance ladders of the adaptive integrators (own DPRKN6(4), DPRKN8(6) and \
         DPRKN12(10) pairs, the last two also compensated, ode_solvers Dop853, numeris RKV98NoInterp) on every scene: the fitted exponent of error ~ TOL^k with its interval and \
         theory, evaluations and error at three tolerances, the energy class of a long run \
         and the round trip at TOL = 1e-8, the verdict.",
    )
    .bind(|| {
        insta::assert_snapshot!(
            "adaptive_table",
            adaptive_summary_table(&records.adaptive.ladders)
        )
    });
}

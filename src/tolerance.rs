//! Every pass/fail bound and every threshold a study uses, each a formula with
//! its reason, in one place.

/// A state farther than this from the origin in phase space (length units,
/// see [`crate::scene::Scene::phase_distance`]) has blown up: a million times
/// the size of the motion is far beyond any bounded orbit yet far from
/// overflow, so an unstable run is stopped within a few dozen steps of leaving
/// the orbit instead of after it overflows.
pub fn blow_up_bound(scale: f64) -> f64 {
    1e6 * scale
}

/// Largest distance between measured and theoretical order that still passes.
///
/// Orders are integers, so 0.1 separates a correct scheme from one that lost
/// or gained an order with a factor of ten to spare, while leaving room for
/// the residual bias of a finite ladder on hard scenes.
pub const ORDER_TOLERANCE: f64 = 0.1;

/// An error that falls slower than `h^STALL_ORDER` over the finest clean
/// rungs has stalled. Orders are integers: a stalled error has order 0, and
/// the slowest convergence any claim allows is order 1, whose error an
/// order-1 scheme's fit may put a little below 1 by chance (0.99 in [0.98,
/// 1.00] is seen). The boundary between the two hypotheses is halfway, in
/// the exponent: an error must fall slower than `h^(1/2)` with its whole
/// interval, and its medians too, to be called stalled.
pub const STALL_ORDER: f64 = 0.5;

/// Fewest rungs an order fit may use. The fit has four coefficients (see
/// [`crate::maths::fit`]); six rungs leave two degrees of freedom for the
/// interval, and a window shorter than that says too little to trust.
pub const MIN_WINDOW: usize = 6;

/// A rung whose error exceeds this fraction of the scene's size is not
/// asymptotic: the error expansion `C h^p (1 + ...)` assumes the numerical
/// orbit is a small perturbation of the exact one. A phase error `d` shows as
/// a distance `2 sin(d/2) = d (1 - d^2/24 + ...)`, still within 0.4% of
/// linear at 0.3 of the orbit; beyond it, errors saturate (a point on the
/// wrong side of the orbit) and stop following any power of `h`. Within the
/// ceiling, the window's local-order test still rejects rungs whose errors
/// are not yet asymptotic.
pub const ERROR_CEILING: f64 = 0.3;

/// The most radians of the motion's fastest local rate one step may cover
/// for the step to resolve it. A step `h` of a scheme of order `p` errs
/// locally by about `C (h w)^(p+1)` of the state, where `w` is the rate at
/// which the force turns or pulls nearby orbits apart (the square root of
/// the largest eigenvalue of `|d a / d q|`); the expansion needs `h w` below
/// one, and so do the linear stability limits of the explicit one-step
/// schemes of the catalogue (2 for the Verlet forms, `2 sqrt 2` for RK4 on
/// the oscillator). Where even the finest rung takes more than one radian
/// of the fastest motion a step (a near-parabolic orbit's pericentre), a
/// correct scheme can blow up on every rung, and that says nothing of it.
pub const RESOLVED_STEP_RADIANS: f64 = 1.0;

/// Largest part of a rung's error that round-off may be for the rung to be
/// clean, for a rung `ln(h_prev / h) = log_ratio` finer than its neighbour
/// and a local order `local` there.
///
/// A rung's error carries its round-off `r`, a fraction `f = r / e` of it; a
/// local order `ln(e1 / e2) / log_ratio` moves by at most `(f1 + f2) /
/// log_ratio` when both rungs carry theirs. Keeping that within half the
/// [`plateau_tolerance`] gives `f <= plateau_tolerance(local) log_ratio /
/// 4`: round-off alone can then neither break a plateau of local orders nor
/// fake a fall out of one (an order reduction must fall by a whole plateau
/// tolerance). On a ladder of four rungs a halving that is 0.2% of a
/// second-order error, 0.9% of an eighth-order one. Past it the rung is on
/// the floor. (The fitted order moves far less than a local order: the
/// finest rung's shift enters the slope of a window of `W` rungs with a
/// weight of about `6 / W^2`.)
pub fn clean_fraction(log_ratio: f64, local: f64) -> f64 {
    plateau_tolerance(local) * log_ratio / 4.0
}

/// Every rung has a twin run in units of length this much smaller
/// ([`crate::scene::Scaled`]), so that its round-off is a second,
/// independent sample of the rung's.
///
/// The twin must round differently at every operation, and differ from the
/// rung by nothing else. A start moved by one unit of round-off does not do
/// the first: the operations of a step then differ in their last bit only,
/// most roundings come out the same, and the two runs stay a unit apart
/// while their common round-off grows a thousandfold (leap-frog on the
/// anharmonic well, 1e6 steps). A slightly longer step does not either for
/// the two-step Störmer form, whose round-off is the rounding of the tiny
/// `h^2 a` into the last bit of `q`: a change of `h^2 a` far below that bit
/// leaves every rounding as it was. In units `1 + 2^-20` smaller every number
/// of the run differs from the rung's in its low 32 bits, so every rounding
/// is drawn anew, and since Newton's equations, and every scheme that
/// combines states and forces linearly, are unchanged by a change of units,
/// the twin is the rung in exact arithmetic.
pub const TWIN_SCALE: f64 = 1.0 + 1.0 / (1u64 << 20) as f64;

/// How accurate, in units of `eps * scale`, an exact solution must be for a
/// scene to serve as a reference. The built-in ones are evaluated to a few
/// units: the oscillator and the circle by one `sin_cos`, Kepler's equation by
/// Newton's iteration to round-off (its condition number `1 / (1 - e cos E)`
/// is 10 at the pericentre of `e = 0.9`), the elliptic functions by the AGM
/// to a few ulps. Every rung's error carries this much besides its own
/// round-off.
pub const EXACT_SOLUTION_ULPS: f64 = 16.0;

/// The phase-space size of rounding each coordinate of `s` once, by half an
/// ulp, in the scene's [`phase_distance`](crate::scene::Scene::phase_distance):
/// the error of an exact solution computed in higher precision (double-double,
/// as the Kepler orbits' are) and rounded to doubles, the least any reference
/// in doubles carries.
pub fn rounding_distance<S: crate::scene::Scene<D>, const D: usize>(
    scene: &S,
    s: &crate::state::State<D>,
) -> f64 {
    let half_ulp = |x: f64| 0.5 * (x.abs().next_up() - x.abs());
    let w = scene.frequency();
    let q: f64 = s.q.iter().map(|&x| half_ulp(x).powi(2)).sum();
    let v: f64 = s.v.iter().map(|&x| (half_ulp(x) / w).powi(2)).sum();
    (q + v).sqrt()
}

/// The window's reference order is the median local order of this many of
/// its finest rungs: the most asymptotic ones, and a median of three is not
/// moved by one erratic rung.
pub const REFERENCE_RUNGS: usize = 3;

/// The window holds at most this many rungs, the finest asymptotic ones:
/// eight leave four degrees of freedom to the four-term fit, while keeping
/// the coarse rungs, whose corrections the fit models least well, out
/// (unless fewer would not span [`MIN_WINDOW_HALVINGS`]).
pub const WINDOW_RUNGS: usize = 8;

/// A window spans at least this many halvings of the step, whatever the
/// density of the ladder. Local orders that agree over a shorter stretch can
/// be the passing slope of a curved error rather than an order: near a
/// cancellation of two terms of the error expansion the local order sweeps
/// through every value, and an RK4 error on the anharmonic well close to its
/// separatrix holds a local order of 3.0 to within 3% over a factor 2.4 in
/// `h` before rising to its order, 4. Two halvings, a factor of four, is
/// what six rungs of a halving ladder's neighbour (`2^(-1/2)`) span already.
pub const MIN_WINDOW_HALVINGS: f64 = 2.0;

/// A rung belongs to the window while its local order is within this of the
/// reference (5% of the order, at least 0.05): the steady drift of the
/// error expansion's next terms, which the fit models, stays inside it once
/// asymptotic; a change of regime (pre-asymptotic rungs, a lower-order term
/// taking over at small steps) does not.
pub fn plateau_tolerance(median_order: f64) -> f64 {
    0.05 * median_order.abs().max(1.0)
}

/// The finest distinction between orders the harness claims to make.
///
/// On smooth exact-solution errors the fit's interval can shrink to 1e-6,
/// narrower than effects no finite ladder removes: accumulated round-off moves
/// the fitted order of the two-step Störmer-Verlet scheme on the oscillator by
/// 4e-4 long before its error visibly stops falling. An interval is therefore
/// never reported narrower than `order -+ 0.01`: a hundredth of an order is
/// far below any order a scheme can lose, and far above what round-off and the
/// expansion's remainder can fake.
pub const ORDER_RESOLUTION: f64 = 0.01;

/// The interval a verdict uses: the fit's 95% interval (Student's t on the
/// standard error, plus the window's systematic), at least
/// [`ORDER_RESOLUTION`] either side of the estimate.
pub fn order_interval(order: f64, ci95: [f64; 2]) -> [f64; 2] {
    [
        ci95[0].min(order - ORDER_RESOLUTION),
        ci95[1].max(order + ORDER_RESOLUTION),
    ]
}

/// The verdict on a measured order, as a refutation: a claim of order `p`
/// says the global error falls at least as fast as `h^p`, so only an error
/// that falls more slowly refutes it. It fails when the interval lies
/// wholly below the claim, or the estimate more than [`ORDER_TOLERANCE`]
/// below it. An order measured above the claim refutes nothing: a scheme of
/// order `p` whose `h^p` term is small shows `p + 1` over every step above
/// the one where that term takes over (Euler-Cromer's first-order lag of
/// `h a / 2` at the pericentre of an `e = 0.9` orbit takes over from its
/// second-order passage error only below `h = 1.7e-6`), and a scheme more
/// accurate than it claims is not a defect; the verdict passes and says so.
pub fn order_verdict(
    theoretical: f64,
    measured: f64,
    interval: [f64; 2],
) -> Result<Option<String>, String> {
    use crate::wording::{order, vs_lower};
    let estimate = format!(
        "measured order {} in [{}, {}]",
        order(measured),
        order(interval[0]),
        order(interval[1])
    );
    if interval[1] < theoretical {
        return Err(format!(
            "{estimate} lies below the theoretical order: {}",
            vs_lower(interval[1], "theoretical order", theoretical)
        ));
    }
    if measured < theoretical - ORDER_TOLERANCE {
        return Err(format!(
            "{estimate} is more than {ORDER_TOLERANCE} below the theoretical order \
             {theoretical}: {}",
            vs_lower(measured, "", theoretical - ORDER_TOLERANCE)
        ));
    }
    Ok(
        (interval[0] > theoretical && measured > theoretical + ORDER_TOLERANCE).then(|| {
            format!(
                "the error falls faster than the claimed order {theoretical} over these steps \
             (more accurate than claimed, or the claimed order's term shows only at finer steps)"
            )
        }),
    )
}

/// Largest symplectic residual `max |J^T Omega J - Omega| / max(1, max
/// |J_ij|^2)` (in the scaled coordinates `(q, v / w)`) that counts as
/// round-off. A step of `s` stages rounds each entry of `J` at about `s eps`
/// of the largest, and each entry of `J^T Omega J` sums `2D` products of
/// two of them, so its round-off is about `4 D s eps max|J|^2`: relative to
/// `max|J|^2` (which is 1 where the step hardly deforms phase space, and
/// hundreds through a pericentre taken in a few steps), 1e-15 to 1e-14 for
/// the catalogue; 1e-12 leaves a factor of 100, and the smallest defect of
/// a non-symplectic scheme at the default steps (RK4 at `h w = 2 pi / 100`:
/// `z^6 / 72 = 8.6e-10`) is a thousand times larger.
pub const SYMPLECTIC_TOLERANCE: f64 = 1e-12;

/// Largest return error, in units of `eps * scale`, that counts as round-off
/// after `steps` steps forward and back along a run that magnifies small
/// perturbations by `growth`. Each step rounds the state at about one unit;
/// those errors add up at most linearly in the number of steps, and are
/// magnified by the flow like any perturbation: `16 steps growth` units
/// (a factor 8 for the several roundings a step makes, 2 for the way back).
/// A scheme that is not time-symmetric misses by its local error, `h^(p+1)`
/// per step, ten orders of magnitude more at the default step.
pub fn reverse_tolerance_ulps(steps: u64, growth: f64) -> f64 {
    16.0 * steps as f64 * growth.max(1.0)
}

/// A relative energy error past this fraction of the energy is of the order
/// of the energy itself; if it is still growing after the first period (see
/// [`LOST_GROWTH`]) the orbit is lost and the energy classed as drifting.
pub const LOST_FRACTION: f64 = 0.5;

/// "Still growing": the final running maximum exceeds its value after one
/// period by this factor. A bounded error has sampled its whole oscillation
/// within a period (velocity Verlet at `h w = 1.95` swings by a factor 19,
/// all of it in the first period), so it stays put afterwards.
pub const LOST_GROWTH: f64 = 1.1;

/// The growth exponent is fitted over this many decades of time at the end
/// of the run: late enough that a bounded
/// error has reached its plateau, long enough to tell `t^(1/2)` from `t`.
pub const GROWTH_DECADES: f64 = 2.0;

/// Growth exponents below this are bounded: halfway between the laws
/// `g = 0` (bounded) and `1/2` (random walk).
pub const BOUNDED_BELOW: f64 = 0.25;

/// Growth exponents below this (and at least [`BOUNDED_BELOW`]) are a random
/// walk: halfway between `g = 1/2` and `1` (drift).
pub const RANDOM_WALK_BELOW: f64 = 0.75;

/// The largest relative energy error round-off alone can produce in `steps`
/// steps of a scheme computing with unit round-off `epsilon`
/// ([`crate::scheme::Scheme::epsilon`]): each step rounds the energy by a
/// few `eps`, which adds up as a
/// random walk (`eps sqrt(N)`) when roundings are unbiased and linearly
/// (`eps N`) at worst; 10 `eps N` bounds both. A growing error below it is
/// classed as round-off (random walk), not as a drift of the scheme: the
/// implicit midpoint rule, which conserves the oscillator's energy exactly,
/// reaches 4e-13 after 10^6 steps, against 2e-9 for this bound and 9e-4 for
/// RK4's genuine drift at the same step.
pub fn round_off_energy(steps: u64, epsilon: f64) -> f64 {
    10.0 * epsilon * steps as f64
}

/// Relative phase errors below this are too close to round-off (the angle is
/// computed to about 1e-15) to fit a leading term from.
pub const PHASE_FLOOR: f64 = 1e-8;

/// How far outside the unit circle a root of a multistep recurrence may be
/// computed before the recurrence counts as unstable. The roots are
/// eigenvalues of the companion matrix, with a backward error of a few eps
/// times its norm (about 10 for the methods here): a simple root moves by
/// about 1e-15, two roots about to collide by its square root, 1e-7. A root
/// of modulus `1 + 1e-6` needs 10^6 steps to grow e-fold, longer than the
/// runs here, so nothing resolvable is missed.
pub const RECURRENCE_ROOT_SLACK: f64 = 1e-6;

/// Largest relative difference between a measured and an analytic phase
/// coefficient. The measurement at `z` carries the next term of the series,
/// relatively `O(z^2)`, about 1e-4 at the finest resolvable `z` of a
/// second-order scheme; 1e-3 leaves room for fourth-order schemes resolved at
/// coarser `z`.
pub const PHASE_COEFFICIENT_TOLERANCE: f64 = 1e-3;

/// Largest relative residual of a scene check: an automatic derivative is
/// exact to a few ulps, and the eighth-order difference of the exact solution
/// (step 1e-3 of the local time scale) is good to about 1e-12; a wrong
/// potential or solution misses by its error, percent-level for any mistake
/// worth catching.
pub const SCENE_TOLERANCE: f64 = 1e-8;

/// Slack of the stability test, in units of `eps` per force evaluation of a
/// step: a map counts as power-bounded while its determinant is at most
/// `1 + slack` and its trace at most `1 + det + slack` in modulus (Jury's
/// conditions). An exactly area-preserving map computes its determinant to
/// `1 -+` round-off that grows with its stages: measured over the stable
/// `z` up to 20, at most 1 eps for the Verlet family, 7 for Forest-Ruth
/// (3 evaluations), 42 for PEFRL (4), 49 for Yoshida's sixth order (7) and
/// 105 for Kahan-Li's eighth order (17), so 32 a stage leaves a margin of 3
/// or more. For the determinant the slack is per unit of
/// `|m11 m22| + |m12 m21|` (at least 1): it is the difference of those
/// products, and its round-off grows with them; the trace condition then
/// takes a determinant above 1 as 1, so that a large map's round-off cannot
/// pass an unstable trace. McLachlan and Atela's fourth-order map at `z = 9.5672`
/// has entries up to 5.8e3, each product near 3.0e5, and in doubles its
/// determinant comes out `1 - 5.8e-11`, its trace `-1.62581065715642` (40
/// digits give `det = 1`, trace `-1.62581065715648`: stable), which a slack
/// in units of eps alone (2.8e-14 there) calls unstable. Past a boundary the
/// determinant or trace leaves its bound at a
/// finite rate, so the slack moves a boundary by about 1e-13, far below the
/// bisection's resolution; explicit Euler (`det = 1 + z^2`) would pass only
/// below `z = 8.4e-8`, under the scan's first point.
pub const STABILITY_SLACK_EPS_PER_EVALUATION: f64 = 32.0;

/// Width to which each stability boundary is bisected, in `z = h w0`.
pub const STABILITY_BISECTION: f64 = 1e-10;

/// How many times its round-off bound (the stability slack above, times the
/// products of the map's entries) `det M(z) - 1` must be before its value,
/// not only its sign, counts as measured: its relative error is then at most
/// `1/64`, a growth figure is good to two digits, and the slope of
/// `ln(det - 1)` against `ln z` over a factor 2 of `z` errs by at most
/// `2 / (64 ln 2) = 0.045`, a fifth of [`GROWTH_POWER_TOLERANCE`]. Below it a
/// growth is either inferred from the fitted law or reported unresolved.
pub const GROWTH_VALUE_RESOLUTION: f64 = 64.0;

/// Largest distance from an integer `k` of the slopes of `ln(det M(z) - 1)`
/// against `ln z` over each half (a factor 2 of `z`) of the window where a
/// map's growth is first measured. `det - 1` of a one-step map on the
/// oscillator is a function of `z` whose series starts `c z^k (1 + a z^2 + ..)`,
/// with slope `k + 2 a z^2 + O(z^4)`. Round-off takes at most 0.045 of the
/// quarter; the rest lets the next term move the slope by up to 0.2 at the
/// window's top (`4` times its bottom `z_F`), so `|a| z_F^2 <= 1/160`: from
/// the bottom down to `z -> 0` the leading term carries `det - 1` to within
/// 1%, which is what inferring the growth below round-off needs. A genuine
/// boundary, a simple zero of `det - 1` at `z*`, has slope `z/(z - z*)`,
/// which changes by far more than this across a factor 2 above it.
pub const GROWTH_POWER_TOLERANCE: f64 = 0.25;

// Round-off studies (`study::round_off::floor`, `study::round_off::longrun`).

/// The round-off component of a plain scheme's error is fitted against the
/// step over rungs of at least this many steps: a random walk of fewer
/// roundings is too short for its size to follow its law (its spread from
/// one realisation to the next is of the order of its mean), and the
/// coarsest rungs cost nothing to leave out.
pub const ROUND_OFF_FIT_STEPS: u64 = 1 << 10;

/// A round-off ladder stops once this many successive rungs have failed to
/// improve on the smallest error: past the floor a plain scheme's error grows
/// with every halving (at least by `2^(1/2)` for a random walk), while one
/// rung can fall below the last by chance (each rung is a new realisation of
/// the rounding, whose size varies by a factor of about two), two in a row
/// rarely do.
pub const ROUND_OFF_PAST_FLOOR: usize = 2;

/// Largest distance from 1/2 of the growth exponent fitted to a quantity
/// that performs a random walk (the root mean square over the long runs' 16
/// realisations, over two decades of time). The exponent of a true random
/// walk is itself random: simulated ensembles of unbiased walks, sampled and
/// fitted exactly like the long runs (`study::round_off::longrun`'s tests), give
/// exponents with mean 1/2 and standard deviation near 0.06, and 200 of them
/// stay within 0.19 of 1/2. A quarter is four standard deviations, and the
/// boundary of the energy study's random-walk class on either side; a bias
/// of 5% of a step's spread moves the exponent past it.
pub const RANDOM_WALK_EXPONENT_TOLERANCE: f64 = 0.25;

/// Largest distance between the fitted exponent of a plain scheme's
/// round-off against the step and the derived one (1/2 for velocity Verlet
/// and leap-frog, 3/2 for the two-step form). Each rung is one realisation of
/// the rounding, so rungs scatter by a factor of about two about the law, and
/// the fit over four decades of steps moves by up to about 0.1; a quarter is
/// halfway to the law of biased rounding (1 for the one-step forms), so it
/// still tells an unbiased random walk from a biased one.
pub const ROUND_OFF_EXPONENT_TOLERANCE: f64 = 0.25;

/// The two-step form's floor over velocity Verlet's on the oscillator is at
/// least this. Both have the same truncation error `C h^2`; the two-step
/// form's round-off is `R' h^(-3/2)` against velocity Verlet's `R h^(-1/2)`,
/// and the floors `(1 + 2/g) C h*^2` then differ by `(R/C)^(-8/35)` up to
/// factors of order one: at least 500 for `C` of one period's phase error and
/// per-step roundings anywhere from 0.1 to 10 units `u` for either scheme.
/// 100 leaves a factor five below that.
pub const TWO_STEP_FLOOR_RATIO: f64 = 100.0;

/// A compensated variant's long-run change over its plain twin's is at most
/// the reciprocal of this. The plain forms lose about `u` of the conserved
/// quantity per step (the two-step form more), the compensated ones `u h w`,
/// 16 times less at 100 steps a period; the rounding of the read-out, a few
/// `eps` that do not accumulate, is far below the plain forms' random walk
/// of `2^18` steps (hundreds of `eps`). A factor four leaves room for either
/// estimate to be off by four.
pub const COMPENSATED_LONGRUN_GAIN: f64 = 4.0;
// ---------------------------------------------------------------------------
// The hard cases: eccentric orbits, the separatrix, escape or trapped.
// ---------------------------------------------------------------------------

/// End time of an eccentric-orbit rung, in periods: `sqrt(2)`, one full
/// pericentre passage (at one period) after the half passage of the start,
/// and an irrational multiple like the main study's `2 sqrt(2)`. Half the
/// main study's length halves the cost of every rung; what a fixed step does
/// to a pericentre passage is measured by the one full passage.
pub const ECCENTRIC_PERIODS: f64 = std::f64::consts::SQRT_2;

/// Largest rung of an eccentric-orbit ladder, in steps. Every step is
/// compared with the exact solution (Kepler's equation solved to round-off,
/// about ten times the cost of a Verlet step), so a ladder of ratio `r`
/// costs up to `2^17 / (1 - r)` such evaluations: a few hundredths of a
/// second for a scheme whose ladder runs to the cap, and the study runs 40
/// ladders. The report states where this cap leaves a pericentre unresolved.
pub const ECCENTRIC_MAX_RUNG_STEPS: u64 = 1 << 17;

/// Steps per pericentre time scale `tau_p = r_p / v_p` of the energy runs on
/// eccentric orbits: the same resolution of the passage for every `e`, so
/// their energy errors can be compared (a fixed step per period would
/// resolve `e = 0.5` with 22 steps per `tau_p` and `e = 0.99` with 0.09).
pub const ENERGY_STEPS_PER_PERICENTRE: f64 = 8.0;

/// Periods of every eccentric energy run: four apocentre passages, three
/// full pericentre passages between them, enough to tell an energy that
/// returns to the same value after every passage from one that changes by
/// the same amount at each (by three times its offset at the first
/// apocentre, against round-off for a symplectic scheme). At `e = 0.99` and
/// `tau_p / 8` a period is 71 000 steps, so every further period costs
/// nearly a second over the catalogue.
pub const ECCENTRIC_ENERGY_PERIODS: f64 = 4.0;

/// An eccentric orbit's energy is drifting when its value at apocentre
/// changes over the run by more than this fraction of its offset from `E0`
/// there (plus round-off, [`round_off_energy`]). A symplectic scheme's
/// apocentre energy is the same after every passage to round-off, 1e-10 of
/// the offset or less; a scheme that loses or gains a fixed amount per
/// passage changes it by about `2 (apocentres - 1)` offsets (the start is
/// half a passage). A tenth lies far from both.
pub const ECCENTRIC_DRIFT_FRACTION: f64 = 0.1;

/// The separatrix study fits only rungs whose energy offset at the barrier
/// is below this fraction of `E_b`. The following time `T = ln(64 E_b /
/// |dE|) / (2 lambda)` is the leading term of the quarter period `K(m) /
/// Omega` near `m = 1`; its corrections are of relative order `sqrt(|dE| /
/// E_b)` (from `Omega^2 = k (1 + s) / 2` and `1 - m ~ 2 s`, `s = sqrt(|dE| /
/// E_b)`), 1% here, which bends the fitted slopes by less than that.
pub const SEPARATRIX_OFFSET_CEILING: f64 = 1e-4;

/// Relative tolerance on the slopes of the separatrix study against theory
/// (`1 / (2 lambda)` per unit of `ln(1/|dE|)`, `p / (2 lambda)` per unit of
/// `ln(1/h)`). Inside the window, the `sqrt(|dE| / E_b)` correction above
/// moves a local slope by at most 1%, and the next term of the energy
/// offset's expansion in `h` (relatively `O(h)` for first-order schemes,
/// `O(h^2)` for symmetric ones) by less at the steps that reach an offset of
/// `1e-4`; 3% is their sum with room to spare, and a slope computed with
/// the wrong rate `sqrt(k)` instead of `sqrt(2 k)` misses by 41%.
pub const SEPARATRIX_SLOPE_TOLERANCE: f64 = 0.03;

/// The separatrix runs end without an event at this many time scales
/// `1 / sqrt(k)`: round-off alone sends an exact scheme off the separatrix
/// after `ln(64 / eps) / (2 sqrt(2)) ~ 14` of them.
pub const SEPARATRIX_TIME_LIMIT: f64 = 40.0;

/// The separatrix ladder stops at this step (in units of `1 / sqrt(k)`): the
/// finest rung of a first-order scheme then takes about `10^6` steps.
pub const SEPARATRIX_MIN_STEP: f64 = 1.0 / 131072.0;

/// A numerical orbit has departed from the separatrix once its phase-space
/// distance from the exact one exceeds this fraction of `alpha`: small enough
/// that the deviation still grows like `e^(lambda t)` (the force is linear
/// near the barrier top to 1% at this distance), large enough to lie beyond
/// the closest approach `~ alpha sqrt(|dE| / E_b)` of every fitted rung.
pub const DEPARTURE_FRACTION: f64 = 0.1;

/// Length of each escape-or-trapped run, in periods of the trapped orbit
/// (its exact period `4 K(m) / Omega`): several chances to escape at either
/// barrier, so a scheme whose energy drifts is caught too.
pub const ESCAPE_PERIODS: f64 = 4.0;

/// Largest escape-or-trapped run, in steps; a scheme that classifies no
/// step correctly above the step this allows is reported as such.
pub const ESCAPE_MAX_STEPS: u64 = 1 << 21;

/// The escape scan confirms a correct step by checking every scan point down
/// to this fraction of it (a factor 2, four scan points).
pub const ESCAPE_CONFIRM_FACTOR: f64 = 0.5;

/// Bisections of the largest correct step between two scan points a factor
/// `2^(1/4)` apart: ten leave it known to 0.02%.
pub const ESCAPE_BISECTIONS: u32 = 10;

/// End of the stability study's log-spaced scan of `z = h w0`: a scheme
/// stable up to here is reported stable for every step, and a step beyond
/// it is refused (a state growing like a power of `h w` soon leaves the
/// doubles, and the scan has tested all such a step could show).
pub const SCAN_END: f64 = 1e6;
/// First point of the stability scans, and the smallest `h w` a study
/// accepts: below every stability limit worth a step, and a step that
/// changes the state by less than its rounding can show over a run.
pub const SCAN_START: f64 = 1e-6;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{KeplerCircular, Scene};

    /// The circular orbit's start, `q = (1, 0)`, `v = (0, 2 pi)`, `w = 2 pi`:
    /// half an ulp of 1 is `2^-53`, of `2 pi` (in `[4, 8)`) `2^-51`, of 0 a
    /// subnormal that adds nothing.
    #[test]
    fn rounding_is_half_an_ulp_a_coordinate_in_the_phase_distance() {
        let scene = KeplerCircular;
        let w = std::f64::consts::TAU;
        let expected = (2f64.powi(-106) + (2f64.powi(-51) / w).powi(2)).sqrt();
        let got = rounding_distance(&scene, &scene.initial());
        assert!((got / expected - 1.0).abs() < 1e-15, "{got:e} {expected:e}");
    }
}

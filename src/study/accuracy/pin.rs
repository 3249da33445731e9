//! Pins: change detectors for a scheme's error. The order guard checks the
//! exponent of `e = C h^p`; a pin fixes the error itself at one step, to as
//! many digits as the run's round-off leaves meaningful, so that a refactor
//! that changes the scheme by more than rounding fails even when the order
//! study cannot see it: a tuned method swapped for a plain one of the same
//! order, stages reordered, a coefficient retyped with eight or ten digits
//! instead of seventeen (which breaks an order condition by `1e-8` or
//! `1e-10`, far too little to lower the measured order before the ladder
//! reaches its round-off floor).
//!
//! A pin is a small text file per scheme and scene, in the crate's own
//! snapshot folder, written the first time and committed:
//!
//! ```text
//! format = 2
//! scheme = forest-ruth
//! scene = harmonic
//! order = 4
//! measured_order = 4.00
//! reference = exact
//! t_end = 17.771531752633464
//! steps = 33
//! h = 5.385312652313171e-1
//! error = 1.0562178236815366e-1
//! round_off = 5.66e-15
//! tolerance = 4.4e-14
//! ```
//!
//! `error` is the error as the order study measures a rung (see
//! [`crate::study::accuracy::order`]): the largest phase-space distance,
//! over the comparison steps of `steps` steps to `t_end`, to the exact
//! solution (`reference = exact`), or to the same scheme at half the step
//! for a scene without one (`half-step`). It is written with every digit
//! (the shortest decimal that reads back as the same double). The check
//! reruns that one step count and passes when the error is within
//! `tolerance` of the pinned one. `round_off` is the order study's 95% bound
//! on the run's round-off there, kept for the failure message.
//!
//! # The pinned step
//!
//! Truncation error falls like `h^p` while round-off grows with the steps
//! taken, so a pin is most sensitive at the coarse end of the ladder. It is
//! the rung whose error is the largest multiple of its tolerance, among the
//! order study's measured rungs that resolve the motion (error below
//! [`ERROR_CEILING`] times the scene's size, the rungs the round-off model
//! is fitted to) and whose own twin sample lies below the model's 95% bound
//! (the model describes that rung). In the catalogue that is the coarsest
//! resolved rung, 23 steps for most schemes (one to 2e5 in all), its error
//! 3e-7 to 0.6 of the orbit and its tolerance 5e-14 to 5e-8 of the error
//! (median 6e-12; the widest for high-order methods whose coarsest rung is
//! already accurate). The error there need not follow
//! `C h^p` yet: a change detector only needs it to be reproducible, and the
//! exponent is the order guard's business (the pin also keeps the measured
//! order, to two decimals, and fails when today's interval leaves it).
//!
//! # The tolerance
//!
//! The error is `E = max_t |y(t) - r(t)|`, the run `y` against the
//! reference `r`. On another machine, or after a change that only reorders
//! floating-point operations, the run and the reference are `y'` and `r'`,
//! and by the triangle inequality (twice, then over the maximum)
//! `|E - E'| <= max_t |y - y'| + max_t |r - r'|`. Each term is measured or
//! bounded:
//!
//! 1. **The run's rounding**, `max_t |y - y'|`. Reordering a scheme's
//!    operations (`(a h) v` for `a (h v)`, two half kicks for one merged
//!    kick, states summed in another order), a compiler's choices, or a
//!    platform draw the run's roundings anew. The order study's twin of
//!    every rung (the same run in units of length
//!    [`TWIN_SCALE`](crate::tolerance::TWIN_SCALE) smaller, where every
//!    number differs from the run's in its low bits) is exactly such a
//!    redraw, and the distance between the two is a sample of
//!    `max_t |y - y'|`; the law fitted to the twins' samples
//!    ([`RoundOffModel`]) bounds one sample at `N` steps by its 95%
//!    prediction bound `B(N)`, the rung's `round_off_bound`. That bound is
//!    exceeded once in forty draws, but the distance is far lighter-tailed
//!    than the bound's log-normal model: it is the norm of a sum of many
//!    independent roundings carried by the linearised flow, Gaussian in
//!    each phase-space component, so its chance to exceed `k` times its
//!    root mean square is `exp(-k^2)` in a plane (less in more dimensions,
//!    and the maximum over the run's times has a Gaussian tail too).
//!    A sample's logarithm then scatters by `pi / sqrt(24) = 0.64` about
//!    its mean, which puts `B(N)` at about `exp(1.96 * 0.64) = 3.5` times
//!    the geometric mean, itself `0.75` of the root mean square: `2 B(N)`
//!    is over five root mean squares, exceeded with a chance of `1e-11`.
//!    (A rung whose own twin lies above `B(N)` is not described by the
//!    law, and is not pinned.)
//! 2. **Another libm.** `sin`, `cos` and `exp` in a scene's force are
//!    within an ulp of the true value on every platform, so two platforms
//!    can differ by two ulps in a result where two roundings of one
//!    operation differ by at most one: a libm swap perturbs (some of) the
//!    run's operations by at most twice what the twin's redraw does, which
//!    doubles the first term again, to `4 B(N)`
//!    ([`PIN_ROUND_OFF_MULTIPLE`]).
//! 3. **The reference.** An exact solution is within
//!    [`EXACT_SOLUTION_ULPS`] `eps` of the truth, in units of the scene's
//!    size, on every platform, so two platforms' differ by at most twice
//!    that. A half-step reference is a second run, rounded independently of
//!    the first: its bound `B(2N)` joins `B(N)` in quadrature.
//!
//! Together: `tolerance = 4 B(N) + 2 EXACT_SOLUTION_ULPS eps scale` against
//! an exact solution, `4 hypot(B(N), B(2N))` against the half step, stored
//! to two digits, rounded up. The run is one sequential loop, so the thread
//! count cannot change it.
//!
//! # What it catches
//!
//! A scheme changed by a relative `d` in a coefficient changes its error by
//! about `d` times the error's sensitivity to that coefficient, which is of
//! order one for a weight of a composition (more where the change breaks an
//! order condition: a lower power of `h` enters with coefficient `~d`). A
//! coefficient retyped with ten significant digits is off by up to `5e-10`
//! of itself, far above those tolerances. Forest-Ruth with its outer weight
//! typed to ten digits (the middle one still `1 - 2 w_1`, so consistent)
//! passes the order study, and moves the pinned error by 9.5e-10 of itself
//! on the oscillator (tolerance 1.5e-13) and 1.7e-9 on the circular orbit
//! (5.8e-12); Yoshida's sixth order with its weights to ten digits, 3.0e-8
//! on the orbit (2.2e-12). Mathematically identical schemes (half kicks not
//! merged, products associated the other way, RK4's stages summed in
//! another order) move it by at most 0.03 of the tolerance, and the same run
//! in other units or with an exact solution and forces a few ulps off by at
//! most 0.12 (the tests in `tests/harness/pins.rs`).
//!
//! # Renewing
//!
//! Set `STEPLADDER_UPDATE_PINS=1` to rewrite pins after an intended change.
//! When a pin is missing it is written and the check passes, except under
//! `CI` (set by most CI services), where a missing pin fails: it should have
//! been committed. A pin of the first format (three digits and a relative
//! tolerance of 1%, without a `format` line) is refused with a message that
//! says to rewrite it: it cannot tell a change of `1e-9` of the error from
//! none, and accepting it would keep that blind spot without a word.

use crate::error::Error;
use crate::run::integrate;
use crate::run::{comparison_steps, exact_rung_error};
use crate::scene::Scene;
use crate::scheme::Scheme;
use crate::state::State;
use crate::study::accuracy::order::{
    DropReason, OrderRecord, OrderSpec, Reference, RoundOffModel, global_order,
};
use crate::study::verdict::Verdict;
use crate::tolerance::{ERROR_CEILING, EXACT_SOLUTION_ULPS};
use std::path::{Path, PathBuf};

/// The version of the pin format this crate writes and reads.
pub const PIN_FORMAT: u32 = 2;

/// The round-off part of a pin's tolerance in units of the order study's
/// 95% round-off bound at the pinned rung: twice for the tail of one
/// redraw of the run's roundings, twice again for a libm that differs by
/// two ulps where a rounding differs by one (see the module documentation).
pub const PIN_ROUND_OFF_MULTIPLE: f64 = 4.0;

/// What a pin records.
#[derive(Clone, Debug, PartialEq)]
pub struct Pin {
    /// Scheme id.
    pub scheme: String,
    /// Scene id.
    pub scene: String,
    /// The claimed order.
    pub order: u32,
    /// The measured order, to two decimals.
    pub measured_order: f64,
    /// What the error is measured against.
    pub reference: Reference,
    /// End time of the pinned run.
    pub t_end: f64,
    /// Steps of the pinned run.
    pub steps: u64,
    /// The error of the pinned run, every digit.
    pub error: f64,
    /// The order study's 95% bound on the run's round-off at `steps`.
    pub round_off: f64,
    /// Largest change of the error that passes (absolute, in the scene's
    /// length units).
    pub tolerance: f64,
}

/// How a pin check ended.
#[derive(Clone, Debug, PartialEq)]
pub enum PinOutcome {
    /// The pin existed and the error agrees with it.
    Agrees {
        /// The pin.
        pin: Pin,
        /// The error measured now.
        measured_error: f64,
    },
    /// There was no pin (or an update was asked for); it has been written.
    Written(Pin),
}

impl Pin {
    /// The pinned step.
    pub fn h(&self) -> f64 {
        self.t_end / self.steps as f64
    }

    /// The tolerance as a fraction of the error.
    pub fn relative_tolerance(&self) -> f64 {
        self.tolerance / self.error
    }

    /// The file's text.
    pub fn to_text(&self) -> String {
        let against = match self.reference {
            Reference::Exact => "the exact solution",
            Reference::HalfStep => "the run at half the step",
        };
        format!(
            "# stepladder pin: `{scheme}` on `{scene}`, the largest phase-space distance to\n\
             # {against} over {steps} steps to t_end (every digit); a rerun must agree within\n\
             # `tolerance` ({relative:.1e} of the error), from the round-off the order study's twin\n\
             # runs measured there. Rewrite with STEPLADDER_UPDATE_PINS=1 after an intended change.\n\
             format = {PIN_FORMAT}\nscheme = {scheme}\nscene = {scene}\norder = {order}\n\
             measured_order = {measured:.2}\nreference = {reference}\nt_end = {t_end:?}\n\
             steps = {steps}\nh = {h:e}\nerror = {error:e}\nround_off = {round_off:.2e}\n\
             tolerance = {tolerance:.1e}\n",
            scheme = self.scheme,
            scene = self.scene,
            relative = self.relative_tolerance(),
            steps = self.steps,
            order = self.order,
            measured = self.measured_order,
            reference = reference_name(self.reference),
            t_end = self.t_end,
            h = self.h(),
            error = self.error,
            round_off = self.round_off,
            tolerance = self.tolerance,
        )
    }

    /// Reads a pin from its text.
    pub fn parse(text: &str) -> Result<Self, String> {
        let fields: std::collections::HashMap<String, String> = pin_fields(text)?
            .into_iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        let get = |key: &str| {
            fields
                .get(key)
                .cloned()
                .ok_or_else(|| format!("missing `{key}`"))
        };
        match fields.get("format").map(String::as_str) {
            Some(f) if f == PIN_FORMAT.to_string() => {}
            None if fields.contains_key("relative_tolerance") => {
                return Err(
                    "a pin of the first format (the error to three digits, accepted \
                            within 1%), too coarse to tell a changed scheme from rounding; \
                            rewrite it with STEPLADDER_UPDATE_PINS=1 and commit the new file"
                        .into(),
                );
            }
            None => return Err("missing `format`".into()),
            Some(f) => {
                return Err(format!(
                    "`format = {f}` is not the format this version reads ({PIN_FORMAT}); \
                     rewrite it with STEPLADDER_UPDATE_PINS=1"
                ));
            }
        }
        let number = |key: &str| -> Result<f64, String> {
            let v = get(key)?;
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x >= 0.0)
                .ok_or_else(|| format!("`{key} = {v}` is not a finite number >= 0"))
        };
        let integer = |key: &str| -> Result<u64, String> {
            let v = get(key)?;
            v.parse::<u64>()
                .ok()
                .filter(|&n| n > 0)
                .ok_or_else(|| format!("`{key} = {v}` is not a positive integer"))
        };
        let reference = match get("reference")?.as_str() {
            "exact" => Reference::Exact,
            "half-step" => Reference::HalfStep,
            other => {
                return Err(format!(
                    "`reference = {other}` is neither `exact` nor `half-step`"
                ));
            }
        };
        Ok(Pin {
            scheme: get("scheme")?,
            scene: get("scene")?,
            order: u32::try_from(integer("order")?).map_err(|e| e.to_string())?,
            measured_order: number("measured_order")?,
            reference,
            t_end: number("t_end")?,
            steps: integer("steps")?,
            error: number("error")?,
            round_off: number("round_off")?,
            tolerance: number("tolerance")?,
        })
    }
}

/// `x` as a pin file prints it (`decimals` after the point, in exponent
/// form), so that a pin written and read back is equal.
pub(crate) fn printed(x: f64, decimals: usize) -> f64 {
    format!("{x:.decimals$e}")
        .parse()
        .expect("a formatted float parses")
}

/// Why a missing pin fails under CI, where nothing is written.
pub(crate) fn missing_under_ci(who: &str, path: &Path) -> String {
    format!(
        "{who}: no pin at {} under CI; run the tests locally and commit the pin it writes",
        path.display()
    )
}

/// Writes a pin file (and its folder), or says why it could not.
pub(crate) fn write_pin(who: &str, path: &Path, text: &str) -> Result<(), String> {
    path.parent()
        .map_or(Ok(()), std::fs::create_dir_all)
        .and_then(|()| std::fs::write(path, text))
        .map_err(|e| format!("{who}: cannot write {}: {e}", path.display()))
}

/// The `key = value` lines of a pin file, comments (`#`) and blank lines
/// skipped; the fixed-step and the adaptive pins share the format.
pub(crate) fn pin_fields(text: &str) -> Result<std::collections::HashMap<&str, &str>, String> {
    let mut fields = std::collections::HashMap::new();
    for line in text.lines().map(str::trim) {
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let (key, value) = line
            .split_once('=')
            .ok_or_else(|| format!("not `key = value`: {line:?}"))?;
        fields.insert(key.trim(), value.trim());
    }
    Ok(fields)
}

fn reference_name(r: Reference) -> &'static str {
    match r {
        Reference::Exact => "exact",
        Reference::HalfStep => "half-step",
    }
}

/// The pin file of `scheme_id` on `scene_id` in `dir`: a file of `dir`
/// only for plain kebab-case ids, which [`check_pin`] asks of both before
/// it makes the path ([`crate::error::is_kebab_case`]).
pub fn pin_path(dir: &Path, scheme_id: &str, scene_id: &str) -> PathBuf {
    dir.join(format!("{scheme_id}__{scene_id}.pin"))
}

/// The error of `steps` steps of `t_end / steps` as the order study
/// measures a rung: the largest phase-space distance at its comparison
/// steps to the exact solution, or, for a scene without one, to the run at
/// half the step. `None` when a run does not complete.
pub fn pinned_error<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    t_end: f64,
    steps: u64,
) -> Option<f64> {
    if scene.exact(0.0).is_some() {
        return exact_rung_error(scheme, scene, t_end, steps);
    }
    // the states at the comparison steps of `steps` steps, of a run of
    // `every` times as many
    let states = |every: u64| -> Option<Vec<State<D>>> {
        let n = every * steps;
        let mut at = comparison_steps(steps).map(|k| every * k).peekable();
        let mut kept = Vec::new();
        let outcome = integrate(
            scheme,
            scene,
            &scene.initial(),
            t_end / n as f64,
            n,
            |i, _, s| {
                if at.next_if_eq(&i).is_some() {
                    kept.push(*s);
                }
            },
        );
        outcome.completed().then_some(kept)
    };
    let (own, half) = (states(1)?, states(2)?);
    Some(
        own.iter()
            .zip(&half)
            .map(|(a, b)| scene.phase_distance(a, b))
            .fold(0.0, f64::max),
    )
}

/// The tolerance of a pin at `steps` steps (see the module documentation):
/// [`PIN_ROUND_OFF_MULTIPLE`] times the round-off bound of the run (and of
/// its half-step reference), plus twice the exact solution's own
/// inaccuracy.
pub fn pin_tolerance(model: &RoundOffModel, reference: Reference, steps: u64, scale: f64) -> f64 {
    let bound = |n: u64| model.bound(n);
    match reference {
        Reference::Exact => {
            PIN_ROUND_OFF_MULTIPLE * bound(steps) + 2.0 * EXACT_SOLUTION_ULPS * f64::EPSILON * scale
        }
        Reference::HalfStep => PIN_ROUND_OFF_MULTIPLE * bound(steps).hypot(bound(2 * steps)),
    }
}

/// Measures the order, then checks the error at the pinned step against
/// the pin in `dir` (writing it if missing, or if `STEPLADDER_UPDATE_PINS`
/// is set). `Err` carries the failure message.
pub fn check_pin<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    dir: &Path,
) -> Result<PinOutcome, String> {
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty() && v != "0");
    check_pin_with(scheme, scene, dir, set("STEPLADDER_UPDATE_PINS"), set("CI"))
}

/// [`check_pin`] with the environment made explicit: `update` rewrites the
/// pin, `ci` makes a missing pin a failure.
pub fn check_pin_with<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    dir: &Path,
    update: bool,
    ci: bool,
) -> Result<PinOutcome, String> {
    let meta = scheme.meta();
    let scene_id = scene.meta().id;
    let who = format!("stepladder: `{}` on `{scene_id}`", meta.id);
    // ids name the pin file: one that is a path would write outside `dir`
    crate::error::kebab_id("scheme", meta.id)
        .and_then(|_| crate::error::kebab_id("scene", scene_id))
        .map_err(|e| format!("{who}: {e}"))?;
    let record = global_order(scheme, scene, &OrderSpec::default())
        .map_err(|e: Error| format!("{who}: the order study could not run: {e}"))?;
    if record.verdict != Verdict::Pass {
        return Err(format!(
            "{who}: the order study did not pass ({}), so its error is not pinned: {}",
            record.verdict.name(),
            record.reason
        ));
    }
    let path = pin_path(dir, meta.id, scene_id);
    let existing = std::fs::read_to_string(&path).ok();
    match existing {
        Some(text) if !update => {
            let pin = Pin::parse(&text).map_err(|e| format!("{who}: {}: {e}", path.display()))?;
            compare(scheme, scene, &record, pin, &who)
        }
        _ if ci && !update => Err(missing_under_ci(&who, &path)),
        _ => {
            let pin = new_pin(scheme, scene, &record).map_err(|e| format!("{who}: {e}"))?;
            write_pin(&who, &path, &pin.to_text())?;
            Ok(PinOutcome::Written(pin))
        }
    }
}

/// A new pin at the rung where the error is the largest multiple of its
/// tolerance (see the module documentation).
fn new_pin<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    record: &OrderRecord,
) -> Result<Pin, String> {
    let model = record
        .round_off
        .ok_or("the order study has no round-off model to derive a tolerance from")?;
    let scale = scene.scale();
    let ceiling = ERROR_CEILING * scale;
    let (rung, tolerance) = record
        .rungs
        .iter()
        .filter(|r| r.dropped != Some(DropReason::Reference) && r.outcome.completed())
        .filter(|r| r.error.is_some_and(|e| e > 0.0 && e <= ceiling))
        .filter(|r| {
            r.round_off_sample
                .zip(r.round_off_bound)
                .is_some_and(|(s, b)| s <= b)
        })
        .map(|r| (r, pin_tolerance(&model, record.reference, r.steps, scale)))
        .filter(|(r, tol)| tol.is_finite() && *tol < r.error.unwrap_or(0.0))
        .max_by(|(a, ta), (b, tb)| {
            let ratio = |e: Option<f64>, t: f64| e.unwrap_or(0.0) / t;
            ratio(a.error, *ta).total_cmp(&ratio(b.error, *tb))
        })
        .ok_or(
            "no rung resolves the motion with an error above its round-off: nothing \
             reproducible to pin",
        )?;
    let steps = rung.steps;
    let error = pinned_error(scheme, scene, record.t_end, steps)
        .ok_or("the pinned run did not complete")?;
    let measured_order = record.measured_order.ok_or("no measured order")?;
    Ok(Pin {
        scheme: scheme.meta().id.to_string(),
        scene: scene.meta().id.to_string(),
        order: scheme.meta().order,
        measured_order: (measured_order * 100.0).round() / 100.0,
        reference: record.reference,
        t_end: record.t_end,
        steps,
        error,
        round_off: printed(rung.round_off_bound.unwrap_or(0.0), 2),
        // two significant digits, rounded up: the printed value is at
        // least the derived one
        tolerance: printed(1.05 * tolerance, 1),
    })
}

fn compare<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    record: &OrderRecord,
    pin: Pin,
    who: &str,
) -> Result<PinOutcome, String> {
    let meta = scheme.meta();
    if pin.scheme != meta.id
        || pin.scene != scene.meta().id
        || pin.order != meta.order
        || pin.reference != record.reference
    {
        return Err(format!(
            "{who}: the pin is for `{}` on `{}` at order {} against the {} reference; rewrite \
             it with STEPLADDER_UPDATE_PINS=1 if the claims or the scene changed",
            pin.scheme,
            pin.scene,
            pin.order,
            reference_name(pin.reference)
        ));
    }
    // the measured order: the pinned two-decimal value must lie in today's
    // interval, widened by its rounding
    if let Some([lo, hi]) = record.ci95
        && !(lo - 0.005..=hi + 0.005).contains(&pin.measured_order)
    {
        return Err(format!(
            "{who}: measured order {:.4} in [{lo:.4}, {hi:.4}] no longer contains the pinned \
             {:.2}",
            record.measured_order.unwrap_or(f64::NAN),
            pin.measured_order
        ));
    }
    let error = pinned_error(scheme, scene, pin.t_end, pin.steps).ok_or_else(|| {
        format!(
            "{who}: the run of {} steps to t_end = {} did not complete",
            pin.steps, pin.t_end
        )
    })?;
    let change = error - pin.error;
    // false for a NaN error too
    let within = change.abs() <= pin.tolerance;
    if !within {
        // today's round-off at the pinned step, to tell a changed scheme
        // from changed arithmetic: two fits of one round-off law put their
        // 95% bounds well within a factor of two of each other, so a
        // fourfold rise is the arithmetic, not the fit
        let today = record.round_off.map_or(f64::NAN, |m| {
            pin_tolerance(&m, record.reference, pin.steps, scene.scale())
        });
        let arithmetic = if today > 4.0 * pin.tolerance {
            format!(
                "; today's twins put the tolerance there at {}, {} times the pinned one, so \
                 the arithmetic \
                 itself rounds more than when the pin was written (a narrower float type, a \
                 worse-conditioned evaluation)",
                crate::wording::figure(today),
                crate::wording::vs_upper(today / pin.tolerance, "", 4.0),
            )
        } else {
            String::new()
        };
        return Err(format!(
            "{who}: the error after {} steps of h = {} is {error:e}, pinned {:e} (every digit, \
             to show the change): it moved by {} ({} of itself; the tolerance is four times the \
             round-off the twins measured there, all that another platform or a reordering of \
             operations can move it by){arithmetic}; the scheme computes something else than \
             when the pin was written. Rewrite the pin with STEPLADDER_UPDATE_PINS=1 if the \
             change is intended",
            pin.steps,
            crate::wording::figure(pin.h()),
            pin.error,
            crate::wording::vs_upper(change.abs(), "tolerance", pin.tolerance),
            crate::wording::figure(change / pin.error),
        ));
    }
    Ok(PinOutcome::Agrees {
        pin,
        measured_error: error,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Harmonic, Hidden, KeplerCircular};
    use crate::scheme::{FOREST_RUTH, PEFRL, Rk4, VELOCITY_VERLET};

    /// The module's derivation, in numbers: against an exact solution the
    /// tolerance is `4 B(N)` plus twice the exact solution's own accuracy,
    /// 16 `eps` of the scene's size; against the half step, `4 B(N)` and
    /// `4 B(2N)` in quadrature. At `scale = 1e3` the exact solution's term,
    /// `7.1e-12`, is the larger, so it cannot hide in the round-off.
    #[test]
    fn the_pin_tolerance_is_four_round_off_bounds_and_the_truth_s_accuracy() {
        let samples = [(100, 1e-15), (1000, 1e-14), (10_000, 1e-13)];
        let model = RoundOffModel::fit(&samples).expect("a model");
        let (n, scale) = (1000, 1e3);
        let truth = 2.0 * 16.0 * f64::EPSILON * scale;
        let exact = pin_tolerance(&model, Reference::Exact, n, scale);
        assert!(
            truth > 4.0 * model.bound(n),
            "{truth:e} {:e}",
            model.bound(n)
        );
        let expected = 4.0 * model.bound(n) + truth;
        assert!(
            (exact - expected).abs() <= 1e-12 * expected,
            "{exact:e} against {expected:e}"
        );
        let half = pin_tolerance(&model, Reference::HalfStep, n, scale);
        let expected = 4.0 * model.bound(n).hypot(model.bound(2 * n));
        assert!(
            (half - expected).abs() <= 1e-12 * expected,
            "{half:e} against {expected:e}"
        );
    }

    /// The pinned step is the span over the steps, and the tolerance is
    /// read as a fraction of the error: 10 over 400 steps is h = 1/40.
    #[test]
    fn a_pin_states_its_step_and_relative_tolerance() {
        let pin = Pin {
            scheme: "s".into(),
            scene: "harmonic".into(),
            order: 2,
            measured_order: 2.0,
            reference: Reference::Exact,
            t_end: 10.0,
            steps: 400,
            error: 4e-3,
            round_off: 1e-15,
            tolerance: 2e-14,
        };
        assert_eq!(pin.h(), 0.025);
        assert!((pin.relative_tolerance() - 5e-12).abs() < 1e-26);
    }

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("stepladder-pin-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    fn written(outcome: PinOutcome) -> Pin {
        match outcome {
            PinOutcome::Written(pin) => pin,
            other => panic!("expected a written pin, got {other:?}"),
        }
    }

    /// The pin goes to the rung whose error stands farthest above its
    /// tolerance, the sharpest check a reproducible run allows: not the
    /// rung with the largest error, nor the one with the largest tolerance.
    /// With every resolved rung's error rewritten to 1.5 times its
    /// tolerance and one middle rung's to 3 times, that middle rung is
    /// pinned, although finer rungs have larger tolerances and coarser ones
    /// no smaller errors.
    #[test]
    fn the_pin_is_the_rung_farthest_above_its_tolerance() {
        let osc = Harmonic::default();
        let mut record =
            global_order(&VELOCITY_VERLET, &osc, &OrderSpec::default()).expect("a study");
        let model = record.round_off.expect("a round-off model");
        let ceiling = ERROR_CEILING * osc.scale();
        let resolved: Vec<usize> = (0..record.rungs.len())
            .filter(|&i| record.rungs[i].error.is_some_and(|e| e <= ceiling))
            .collect();
        assert!(resolved.len() >= 5, "{resolved:?}");
        let target = resolved[resolved.len() / 2];
        for &i in &resolved {
            let rung = &mut record.rungs[i];
            let tolerance = pin_tolerance(&model, record.reference, rung.steps, osc.scale());
            let multiple = if i == target { 3.0 } else { 1.5 };
            rung.error = Some(multiple * tolerance);
        }
        let pin = new_pin(&VELOCITY_VERLET, &osc, &record).expect("a pin");
        assert_eq!(pin.steps, record.rungs[target].steps);
    }

    #[test]
    fn a_pin_round_trips_through_its_text() {
        let pin = Pin {
            scheme: "a".into(),
            scene: "b".into(),
            order: 4,
            measured_order: 4.01,
            reference: Reference::HalfStep,
            t_end: 2.0 * std::f64::consts::SQRT_2,
            steps: 1234,
            error: 1.2345678901234567e-7,
            round_off: 3.25e-15,
            tolerance: 1.4e-14,
        };
        assert_eq!(Pin::parse(&pin.to_text()).unwrap(), pin);
        let text = pin.to_text();
        assert!(
            Pin::parse("format = 2\nscheme = a\n")
                .unwrap_err()
                .contains("missing")
        );
        assert!(Pin::parse(&text.replace("steps = 1234", "steps = -3")).is_err());
        assert!(Pin::parse(&text.replace("half-step", "midpoint")).is_err());
        assert!(
            Pin::parse(&text.replace("format = 2", "format = 7"))
                .unwrap_err()
                .contains("STEPLADDER_UPDATE_PINS=1")
        );
    }

    #[test]
    fn a_pin_of_the_first_format_is_refused_with_how_to_renew_it() {
        // the three-digit format this module wrote before
        let old = "# stepladder pin\nscheme = velocity-verlet\nscene = harmonic\norder = 2\n\
                   measured_order = 2.00\nt_end = 17.771531752633464\nsteps = 33\n\
                   h = 5.39e-1\nerror = 2.39e-1\nconstant = 8.24e-1\nrelative_tolerance = 0.01\n";
        let d = dir("old");
        std::fs::create_dir_all(&d).unwrap();
        let path = pin_path(&d, "velocity-verlet", "harmonic");
        std::fs::write(&path, old).unwrap();
        let osc = Harmonic::default();
        let message = check_pin_with(&VELOCITY_VERLET, &osc, &d, false, false).unwrap_err();
        assert!(message.contains("first format"), "{message}");
        assert!(message.contains("STEPLADDER_UPDATE_PINS=1"), "{message}");
        // the renewal rewrites it in the current format, which then agrees
        written(check_pin_with(&VELOCITY_VERLET, &osc, &d, true, true).unwrap());
        assert!(
            std::fs::read_to_string(&path)
                .unwrap()
                .contains("format = 2")
        );
        assert!(matches!(
            check_pin_with(&VELOCITY_VERLET, &osc, &d, false, true).unwrap(),
            PinOutcome::Agrees { .. }
        ));
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn velocity_verlet_on_the_oscillator_pins_its_closed_form_error() {
        // velocity Verlet on x'' = -w^2 x is a linear map with cos(theta) =
        // 1 - z^2/2 (z = h w); from (x0, 0) its n-th state is x0 cos(n theta)
        // and v / w = -x0 sqrt(1 - z^2/4) sin(n theta), against the exact
        // x0 cos(w t), -x0 sin(w t). The pinned error is that distance's
        // largest value over the steps, computed here in closed form; both
        // sides' rounding is the run's (within the pin's tolerance) and the
        // closed form's, a few eps times the phase n theta.
        let osc = Harmonic::default();
        let d = dir("vv");
        // under CI a missing pin is a failure, not a silent write
        let refused = check_pin_with(&VELOCITY_VERLET, &osc, &d, false, true).unwrap_err();
        assert!(refused.contains("under CI"), "{refused}");
        let pin = written(check_pin_with(&VELOCITY_VERLET, &osc, &d, false, false).unwrap());
        let (w, x0) = (osc.frequency(), osc.scale());
        let h = pin.t_end / pin.steps as f64;
        let z = h * w;
        let theta = (1.0 - 0.5 * z * z).acos();
        let closed = (0..=pin.steps)
            .map(|n| {
                let t = if n == pin.steps {
                    pin.t_end
                } else {
                    n as f64 * h
                };
                let nt = n as f64 * theta;
                let dx = x0 * (nt.cos() - (w * t).cos());
                let dv = x0 * ((1.0 - 0.25 * z * z).sqrt() * nt.sin() - (w * t).sin());
                dx.hypot(dv)
            })
            .fold(0.0, f64::max);
        let closed_form_rounding = 8.0 * f64::EPSILON * (1.0 + w * pin.t_end) * x0;
        assert!(
            (pin.error - closed).abs() <= pin.tolerance + closed_form_rounding,
            "{pin:?} against the closed form {closed}"
        );
        // and the pinned error is what the order study measured at that rung
        let record = global_order(&VELOCITY_VERLET, &osc, &OrderSpec::default()).unwrap();
        let rung = record.rungs.iter().find(|r| r.steps == pin.steps).unwrap();
        assert_eq!(rung.error, Some(pin.error));
        assert!(matches!(
            check_pin_with(&VELOCITY_VERLET, &osc, &d, false, false).unwrap(),
            PinOutcome::Agrees { .. }
        ));
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn the_pinned_error_is_the_order_studys_rung_error_against_either_reference() {
        // with the exact solution withheld the error is the distance to the
        // run at half the step, compared at the same times as the study's
        let osc = Harmonic::default();
        for hidden in [false, true] {
            let record = if hidden {
                global_order(&Rk4, &Hidden(&osc), &OrderSpec::default())
            } else {
                global_order(&Rk4, &osc, &OrderSpec::default())
            }
            .unwrap();
            let rungs: Vec<_> = record.rungs.iter().filter(|r| r.error.is_some()).collect();
            assert!(rungs.len() > 5);
            for r in rungs {
                let pinned = if hidden {
                    pinned_error(&Rk4, &Hidden(&osc), record.t_end, r.steps)
                } else {
                    pinned_error(&Rk4, &osc, record.t_end, r.steps)
                };
                assert_eq!(pinned, r.error, "{} steps, hidden {hidden}", r.steps);
            }
        }
    }

    /// A pin names what it was made for: one made for PEFRL, put where
    /// Forest-Ruth's pin belongs (same scene, same order, same reference), is
    /// refused as a pin for another scheme before any figure is compared.
    #[test]
    fn a_pin_made_for_another_scheme_is_refused_as_such() {
        let d = dir("other-scheme");
        check_pin_with(&PEFRL, &KeplerCircular, &d, false, false).unwrap();
        let text = std::fs::read_to_string(pin_path(&d, "pefrl", "kepler-circular")).unwrap();
        std::fs::write(pin_path(&d, "forest-ruth", "kepler-circular"), text).unwrap();
        let message = check_pin_with(&FOREST_RUTH, &KeplerCircular, &d, false, false).unwrap_err();
        assert!(
            message.contains("the pin is for `pefrl` on `kepler-circular` at order 4"),
            "{message}"
        );
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_method_of_the_same_order_with_another_constant_fails_the_pin() {
        // PEFRL is a fourth-order splitting tuned for a small leading error
        // term (Omelyan, Mryglod and Folk), Forest-Ruth the plain one.
        // Swapping the plain method in for the tuned one keeps the order,
        // and the pin catches it
        let d = dir("swap");
        check_pin_with(&PEFRL, &KeplerCircular, &d, false, false).unwrap();
        let text = std::fs::read_to_string(pin_path(&d, "pefrl", "kepler-circular")).unwrap();
        std::fs::write(
            pin_path(&d, "forest-ruth", "kepler-circular"),
            text.replace("scheme = pefrl", "scheme = forest-ruth"),
        )
        .unwrap();
        let message = check_pin_with(&FOREST_RUTH, &KeplerCircular, &d, false, false).unwrap_err();
        assert!(message.contains("computes something else"), "{message}");
        // and RK4, fourth order too, against its own pin passes
        check_pin_with(&Rk4, &KeplerCircular, &d, false, false).unwrap();
        assert!(matches!(
            check_pin_with(&Rk4, &KeplerCircular, &d, false, false).unwrap(),
            PinOutcome::Agrees { .. }
        ));
        let _ = std::fs::remove_dir_all(&d);
    }
}

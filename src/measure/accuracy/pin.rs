//! Pinned error constants: the order guard checks the exponent of `e = C
//! h^p`; a pin also fixes `C`, so a refactor that keeps the order but
//! changes the error constant (a tuned fourth-order method swapped for a
//! plain one, stages reordered) fails.
//!
//! A pin is a small text file per scheme and scene, in the crate's own
//! snapshot folder, written the first time and committed:
//!
//! ```text
//! scheme = velocity-verlet
//! scene = kepler-circular
//! order = 2
//! measured_order = 2.00
//! t_end = 2.8284271247461903
//! steps = 2048
//! h = 1.38e-3
//! error = 1.23e-5
//! constant = 6.45
//! relative_tolerance = 0.01
//! ```
//!
//! `error` is the global error (phase-space distance to the exact solution,
//! or, for a scene without one, to the run at half the step) after `steps`
//! steps to `t_end`, and `constant = error / h^order`; both are rounded to
//! three significant digits so that the file does not change from machine
//! to machine. The check reruns that one step size and compares.
//!
//! **The default tolerance, 1%**, is the sum of what can move an honest
//! measurement: rounding to three digits (at most 0.5%), and the run's
//! round-off, which differs between platforms only through the last bits of
//! `sin`, `cos` and `exp` in the exact solution and of the scene's
//! functions, so by no more than the run's round-off. The reference step is
//! the coarse end of the order study's asymptotic window, and a pin is only
//! written where the round-off bound the study measured there (twin runs) is
//! at most [`PIN_ROUND_OFF_FRACTION`] = 0.1% of the error. The run is one
//! sequential loop, so the thread count cannot change it. What is left, 0.4%,
//! is margin; a changed error constant from a refactor is typically a factor,
//! not a percent.
//!
//! Set `STEPLADDER_UPDATE_PINS=1` to rewrite pins after an intended change.
//! When a pin is missing it is written and the check passes, except under
//! `CI` (set by most CI services), where a missing pin fails: it should have
//! been committed.

use crate::error::Error;
use crate::measure::Verdict;
use crate::measure::accuracy::order::{OrderRecord, OrderSpec, global_order};
use crate::run::integrate;
use crate::scene::Scene;
use crate::scheme::Scheme;
use crate::state::State;
use std::path::{Path, PathBuf};

/// The default relative tolerance on the pinned error (see the module
/// documentation for its derivation).
pub const PIN_RELATIVE_TOLERANCE: f64 = 0.01;

/// Significant digits kept in a pin.
pub const PIN_DIGITS: usize = 3;

/// What a pin records.
#[derive(Clone, Debug, PartialEq)]
pub struct Pin {
    /// Scheme id.
    pub scheme: String,
    /// Scene id.
    pub scene: String,
    /// The claimed order `p` the constant is computed with.
    pub order: u32,
    /// The measured order, to two decimals.
    pub measured_order: f64,
    /// End time of the reference run.
    pub t_end: f64,
    /// Steps of the reference run.
    pub steps: u64,
    /// The global error after `steps` steps, rounded.
    pub error: f64,
    /// `error / h^order`, rounded.
    pub constant: f64,
    /// Largest relative change of the error that passes.
    pub relative_tolerance: f64,
}

/// How a pin check ended.
#[derive(Clone, Debug, PartialEq)]
pub enum PinOutcome {
    /// The pin existed and the error agrees with it.
    Agrees {
        /// The pin.
        pin: Pin,
        /// The error measured now, unrounded.
        measured_error: f64,
    },
    /// There was no pin (or an update was asked for); it has been written.
    Written(Pin),
}

impl Pin {
    /// The reference step.
    pub fn h(&self) -> f64 {
        self.t_end / self.steps as f64
    }

    /// The file's text.
    pub fn to_text(&self) -> String {
        format!(
            "# stepladder pin: the global error of `{scheme}` on `{scene}` after {steps} steps\n\
             # to t_end, and the error constant error / h^order, rounded to {PIN_DIGITS} digits.\n\
             # Rewrite with STEPLADDER_UPDATE_PINS=1 after an intended change.\n\
             scheme = {scheme}\nscene = {scene}\norder = {order}\nmeasured_order = {measured:.2}\n\
             t_end = {t_end:?}\nsteps = {steps}\nh = {h}\nerror = {error}\nconstant = {constant}\n\
             relative_tolerance = {tol}\n",
            scheme = self.scheme,
            scene = self.scene,
            steps = self.steps,
            order = self.order,
            measured = self.measured_order,
            t_end = self.t_end,
            h = significant(self.h()),
            error = significant(self.error),
            constant = significant(self.constant),
            tol = self.relative_tolerance,
        )
    }

    /// Reads a pin from its text.
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut fields = std::collections::HashMap::new();
        for line in text.lines().map(str::trim) {
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let (key, value) = line
                .split_once('=')
                .ok_or_else(|| format!("not `key = value`: {line:?}"))?;
            fields.insert(key.trim().to_string(), value.trim().to_string());
        }
        let get = |key: &str| {
            fields
                .get(key)
                .cloned()
                .ok_or_else(|| format!("missing `{key}`"))
        };
        let number = |key: &str| -> Result<f64, String> {
            let v = get(key)?;
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("`{key} = {v}` is not a finite number"))
        };
        let integer = |key: &str| -> Result<u64, String> {
            let v = get(key)?;
            v.parse::<u64>()
                .ok()
                .filter(|&n| n > 0)
                .ok_or_else(|| format!("`{key} = {v}` is not a positive integer"))
        };
        Ok(Pin {
            scheme: get("scheme")?,
            scene: get("scene")?,
            order: u32::try_from(integer("order")?).map_err(|e| e.to_string())?,
            measured_order: number("measured_order")?,
            t_end: number("t_end")?,
            steps: integer("steps")?,
            error: number("error")?,
            constant: number("constant")?,
            relative_tolerance: number("relative_tolerance")?,
        })
    }
}

/// `x` rounded to [`PIN_DIGITS`] significant digits, printed in scientific
/// notation.
fn significant(x: f64) -> String {
    format!("{x:.prec$e}", prec = PIN_DIGITS - 1)
}

fn rounded(x: f64) -> f64 {
    significant(x).parse().expect("a formatted float parses")
}

/// The pin file of `scheme_id` on `scene_id` in `dir`.
pub fn pin_path(dir: &Path, scheme_id: &str, scene_id: &str) -> PathBuf {
    dir.join(format!("{scheme_id}__{scene_id}.pin"))
}

/// The global error after `steps` steps of `t_end / steps`: the distance to
/// the exact solution, or to the run at half the step when the scene has
/// none. `None` when a run does not complete.
pub fn global_error<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    t_end: f64,
    steps: u64,
) -> Option<f64> {
    let end = |n: u64| -> Option<State<D>> {
        let mut last = None;
        let outcome = integrate(
            scheme,
            scene,
            &scene.initial(),
            t_end / n as f64,
            n,
            |i, _, s| {
                if i == n {
                    last = Some(*s);
                }
            },
        );
        outcome.completed().then_some(last).flatten()
    };
    let here = end(steps)?;
    let reference = match scene.exact(t_end) {
        Some(exact) => exact,
        None => end(2 * steps)?,
    };
    Some(scene.phase_distance(&here, &reference))
}

/// Measures the order, then checks the error at the pinned reference step
/// against the pin in `dir` (writing it if missing, or if
/// `STEPLADDER_UPDATE_PINS` is set). `Err` carries the failure message.
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
    let record = global_order(scheme, scene, &OrderSpec::default())
        .map_err(|e: Error| format!("{who}: the order study could not run: {e}"))?;
    if record.verdict != Verdict::Pass {
        return Err(format!(
            "{who}: the order study did not pass ({}), so there is no asymptotic error \
             constant to pin: {}",
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
        _ if ci && !update => Err(format!(
            "{who}: no pin at {} under CI; run the tests locally and commit the pin it writes",
            path.display()
        )),
        _ => {
            let pin = new_pin(scheme, scene, &record).map_err(|e| format!("{who}: {e}"))?;
            std::fs::create_dir_all(dir)
                .and_then(|()| std::fs::write(&path, pin.to_text()))
                .map_err(|e| format!("{who}: cannot write {}: {e}", path.display()))?;
            Ok(PinOutcome::Written(pin))
        }
    }
}

/// Largest fraction of the reference error its measured round-off bound may
/// be: what platforms' last bits can move the pinned error by.
pub const PIN_ROUND_OFF_FRACTION: f64 = 1e-3;

/// A new pin at the coarse end of the order study's window.
fn new_pin<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    record: &OrderRecord,
) -> Result<Pin, String> {
    let rung = record
        .window
        .and_then(|[first, _]| record.rungs.get(first))
        .ok_or("the order study found no window")?;
    let steps = rung.steps;
    let error = global_error(scheme, scene, record.t_end, steps)
        .ok_or("the reference run did not complete")?;
    let round_off = rung.round_off_bound.unwrap_or(0.0);
    if round_off > PIN_ROUND_OFF_FRACTION * error {
        return Err(format!(
            "at the coarse end of the window (h = {:.3e}) round-off may be {:.1e} of the \
             error, more than {PIN_ROUND_OFF_FRACTION}: the error there is not reproducible \
             enough to pin",
            rung.h,
            round_off / error
        ));
    }
    let order = scheme.meta().order;
    let h = record.t_end / steps as f64;
    let measured_order = record.measured_order.ok_or("no measured order")?;
    Ok(Pin {
        scheme: scheme.meta().id.to_string(),
        scene: scene.meta().id.to_string(),
        order,
        measured_order: (measured_order * 100.0).round() / 100.0,
        t_end: record.t_end,
        steps,
        error: rounded(error),
        constant: rounded(error / h.powi(order as i32)),
        relative_tolerance: PIN_RELATIVE_TOLERANCE,
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
    if pin.scheme != meta.id || pin.scene != scene.meta().id || pin.order != meta.order {
        return Err(format!(
            "{who}: the pin is for `{}` on `{}` at order {}; rewrite it with \
             STEPLADDER_UPDATE_PINS=1 if the claims changed",
            pin.scheme, pin.scene, pin.order
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
    let error = global_error(scheme, scene, pin.t_end, pin.steps).ok_or_else(|| {
        format!(
            "{who}: the run of {} steps to t_end = {} did not complete",
            pin.steps, pin.t_end
        )
    })?;
    let change = error / pin.error - 1.0;
    if change.abs() > pin.relative_tolerance {
        let h = pin.h();
        return Err(format!(
            "{who}: the error after {} steps of h = {h:.3e} is {error:.4e}, pinned {:.3e} \
             ({:+.2}%, tolerance {}%): the error constant moved from {:.3e} to {:.3e} \
             (order {}); rewrite the pin with STEPLADDER_UPDATE_PINS=1 if the change is \
             intended",
            pin.steps,
            pin.error,
            100.0 * change,
            100.0 * pin.relative_tolerance,
            pin.constant,
            error / h.powi(pin.order as i32),
            pin.order
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
    use crate::scene::{Harmonic, KeplerCircular};
    use crate::scheme::{FOREST_RUTH, PEFRL, Rk4, VELOCITY_VERLET};

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("stepladder-pin-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn a_pin_round_trips_through_its_text() {
        let pin = Pin {
            scheme: "a".into(),
            scene: "b".into(),
            order: 4,
            measured_order: 4.01,
            t_end: 2.0 * std::f64::consts::SQRT_2,
            steps: 1234,
            error: 1.23e-7,
            constant: 4.56e3,
            relative_tolerance: 0.01,
        };
        assert_eq!(Pin::parse(&pin.to_text()).unwrap(), pin);
        assert!(Pin::parse("scheme = a\n").unwrap_err().contains("missing"));
        assert!(Pin::parse(&pin.to_text().replace("steps = 1234", "steps = -3")).is_err());
    }

    #[test]
    fn velocity_verlet_on_the_oscillator_pins_its_analytic_constant() {
        // velocity Verlet on x'' = -w^2 x runs slow by z^2/24 (z = h w): after
        // time t the phase lags by w t (h w)^2 / 24, a distance of x0 times that
        // (plus an O(h^2) amplitude wobble in v of the same order, bounded by
        // (h w)^2 / 8 of the amplitude); so C lies between w^3 t x0 / 24 and that
        // plus x0 w^2 / 8.
        let osc = Harmonic::default();
        let d = dir("vv");
        // under CI a missing pin is a failure, not a silent write
        let refused = check_pin_with(&VELOCITY_VERLET, &osc, &d, false, true).unwrap_err();
        assert!(refused.contains("under CI"), "{refused}");
        let PinOutcome::Written(pin) =
            check_pin_with(&VELOCITY_VERLET, &osc, &d, false, false).unwrap()
        else {
            panic!("first check writes")
        };
        let (w, x0) = (osc.frequency(), osc.scale());
        let lag = w.powi(3) * pin.t_end * x0 / 24.0;
        let wobble = x0 * w * w / 8.0;
        assert!(
            (pin.constant - lag).abs() <= 1.01 * wobble,
            "{pin:?} against {lag} +- {wobble}"
        );
        assert!(matches!(
            check_pin_with(&VELOCITY_VERLET, &osc, &d, false, false).unwrap(),
            PinOutcome::Agrees { .. }
        ));
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_method_of_the_same_order_with_another_constant_fails_the_pin() {
        // PEFRL is a fourth-order splitting tuned for a small leading error
        // term (Omelyan, Mryglod and Folk), Forest-Ruth the plain one: on the
        // orbit the error at the pinned step is 54 times larger. Swapping
        // the plain method in for the tuned one keeps the order, and the
        // pin catches it
        let d = dir("swap");
        check_pin_with(&PEFRL, &KeplerCircular, &d, false, false).unwrap();
        let text = std::fs::read_to_string(pin_path(&d, "pefrl", "kepler-circular")).unwrap();
        std::fs::write(
            pin_path(&d, "forest-ruth", "kepler-circular"),
            text.replace("scheme = pefrl", "scheme = forest-ruth"),
        )
        .unwrap();
        let message = check_pin_with(&FOREST_RUTH, &KeplerCircular, &d, false, false).unwrap_err();
        assert!(message.contains("error constant moved"), "{message}");
        // and RK4, fourth order too, against its own pin passes
        check_pin_with(&Rk4, &KeplerCircular, &d, false, false).unwrap();
        assert!(matches!(
            check_pin_with(&Rk4, &KeplerCircular, &d, false, false).unwrap(),
            PinOutcome::Agrees { .. }
        ));
        let _ = std::fs::remove_dir_all(&d);
    }
}

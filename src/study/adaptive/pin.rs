//! Pins for adaptive integrators: a change detector for refactors, as the
//! fixed-step pins are (see [`crate::study::accuracy::pin`]).
//!
//! The pin is the global error of the run at one tolerance, written with
//! every digit: the loosest tolerance of the ladder whose error is resolved
//! above round-off (the fewest steps, so the least round-off and the fewest
//! step-size decisions). A rerun must agree within a tolerance measured on
//! the same run, four times the larger of
//!
//! - the change of the error when the run is repeated in units of length
//!   `1 + 2^-20` smaller ([`TWIN_SCALE`]) and mapped back. A controller
//!   measures its estimate against `TOL (1 + max |y|)`, which the change of
//!   units moves by about `2^-20` relative, so every step size moves by
//!   about `2^-20 / m` relative and the error by as much: a perturbation a
//!   million times the last bit, and the twin's change bounds what another
//!   platform's rounding (a few ulps) or a reordering of operations can do;
//! - the round-off the run can have made, `8 eps N scale`, as the ladder
//!   bounds it.
//!
//! The factor four is the fixed-step pin's: twice for the tail of one draw
//! of a perturbation, twice again for a maths library that rounds by two
//! ulps where this one rounds by one. A step-size decision that flips
//! (an estimate within the perturbation of the tolerance) changes the error
//! by far more than rounding: where the twin sees such a flip the tolerance
//! is large and says so in the file; a flip only another platform makes
//! would be reported as a change (a chance of about `N` times `1e-16` for a
//! run of `N` steps).

use super::ladder::tolerance_point;
use super::record::ToleranceLadderRecord;
use crate::error::Error;
use crate::scene::{Scaled, Scene};
use crate::scheme::{AdaptiveIntegrator, RunEnd};
use crate::study::accuracy::pin::{missing_under_ci, pin_fields, printed, write_pin};
use crate::tolerance::TWIN_SCALE;
use crate::wording::figure;
use std::path::{Path, PathBuf};

/// The format the pin files are written in.
pub const ADAPTIVE_PIN_FORMAT: u32 = 1;

/// What an adaptive pin records.
#[derive(Clone, Debug, PartialEq)]
pub struct AdaptivePin {
    /// The integrator's name.
    pub integrator: String,
    /// Scene id.
    pub scene: String,
    /// The tolerance of the pinned run.
    pub tolerance: f64,
    /// End time of the pinned run.
    pub t_end: f64,
    /// Accepted steps of the pinned run (shown, not compared).
    pub accepted: u64,
    /// The largest phase-space distance to the exact solution over the
    /// accepted steps, every digit.
    pub error: f64,
    /// The error's change in the twin run, mapped back.
    pub twin_change: f64,
    /// The round-off bound of the run.
    pub round_off: f64,
    /// Largest change of the error that passes.
    pub allowed: f64,
}

/// How an adaptive pin check ended.
#[derive(Clone, Debug, PartialEq)]
pub enum AdaptivePinOutcome {
    /// The pin existed and the error agrees with it.
    Agrees {
        /// The pin.
        pin: AdaptivePin,
        /// The error measured now.
        measured_error: f64,
    },
    /// There was no pin (or an update was asked for); it has been written.
    Written(AdaptivePin),
}

impl AdaptivePin {
    /// The file's text.
    pub fn to_text(&self) -> String {
        format!(
            "# stepladder adaptive pin: `{integrator}` on `{scene}`, the largest phase-space distance\n\
             # to the exact solution of the run at TOL = {tolerance:e} to t_end (every digit); a rerun\n\
             # must agree within `allowed`, four times the larger of the twin run's change and the\n\
             # run's round-off. Rewrite with STEPLADDER_UPDATE_PINS=1 after an intended change.\n\
             format = {ADAPTIVE_PIN_FORMAT}\nintegrator = {integrator}\nscene = {scene}\n\
             tolerance = {tolerance:e}\nt_end = {t_end:?}\naccepted = {accepted}\n\
             error = {error:e}\ntwin_change = {twin:.2e}\nround_off = {round_off:.2e}\n\
             allowed = {allowed:.1e}\n",
            integrator = self.integrator,
            scene = self.scene,
            tolerance = self.tolerance,
            t_end = self.t_end,
            accepted = self.accepted,
            error = self.error,
            twin = self.twin_change,
            round_off = self.round_off,
            allowed = self.allowed,
        )
    }

    /// Reads a pin from its text.
    pub fn parse(text: &str) -> Result<Self, String> {
        let fields = pin_fields(text)?;
        let get = |key: &str| {
            fields
                .get(key)
                .copied()
                .ok_or_else(|| format!("missing `{key}`"))
        };
        if get("format")? != ADAPTIVE_PIN_FORMAT.to_string() {
            return Err(format!(
                "`format = {}` is not the format this version reads ({ADAPTIVE_PIN_FORMAT}); \
                 rewrite it with STEPLADDER_UPDATE_PINS=1",
                get("format")?
            ));
        }
        let number = |key: &str| -> Result<f64, String> {
            let v = get(key)?;
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x >= 0.0)
                .ok_or_else(|| format!("`{key} = {v}` is not a finite number >= 0"))
        };
        Ok(Self {
            integrator: get("integrator")?.to_string(),
            scene: get("scene")?.to_string(),
            tolerance: number("tolerance")?,
            t_end: number("t_end")?,
            accepted: get("accepted")?
                .parse()
                .map_err(|_| "`accepted` is not an integer".to_string())?,
            error: number("error")?,
            twin_change: number("twin_change")?,
            round_off: number("round_off")?,
            allowed: number("allowed")?,
        })
    }
}

/// Where the pin of `integrator` on `scene` lives in `dir`: the
/// integrator's name is a display name (`DPRKN6(4) adaptive`), so the file
/// takes its kebab-case form ([`file_stem`]); the scene id, plain
/// kebab-case, is checked by [`check_adaptive_pin`] before.
pub fn adaptive_pin_path(dir: &Path, integrator: &str, scene: &str) -> PathBuf {
    dir.join(format!("{}__{scene}.adaptive.pin", file_stem(integrator)))
}

/// `name` in plain kebab-case: its ASCII letters lower-cased and digits
/// kept, every other run of characters one hyphen, none at either end
/// (`DPRKN6(4) adaptive` is `dprkn6-4-adaptive`). Never a path.
pub fn file_stem(name: &str) -> String {
    name.split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(str::to_ascii_lowercase)
        .collect::<Vec<_>>()
        .join("-")
}

/// Refuses an integrator name with no letter or digit, or one that is a
/// path (a separator, a `..`), and a scene id that is not plain kebab-case.
fn check_names(integrator: &str, scene: &str) -> Result<(), Error> {
    let path_like = integrator.contains(['/', '\\']) || integrator.contains("..");
    if file_stem(integrator).is_empty() || path_like {
        return Err(Error::InvalidId {
            what: "integrator",
            id: integrator.to_string(),
        });
    }
    crate::error::kebab_id("scene", scene).map(|_| ())
}

/// Checks the error at the pinned tolerance against the pin in `dir`,
/// writing it if it is missing (a failure under CI, where nothing is
/// written) or if `STEPLADDER_UPDATE_PINS` is set. `record` is the
/// integrator's tolerance ladder on `scene`, which chooses the tolerance of
/// a new pin.
pub fn check_adaptive_pin<I: AdaptiveIntegrator, S: Scene<D>, const D: usize>(
    integrator: &I,
    scene: &S,
    record: &ToleranceLadderRecord,
    dir: &Path,
) -> Result<AdaptivePinOutcome, String> {
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty() && v != "0");
    check_adaptive_pin_with(
        integrator,
        scene,
        record,
        dir,
        set("STEPLADDER_UPDATE_PINS"),
        set("CI"),
    )
}

/// [`check_adaptive_pin`] with the environment made explicit.
pub fn check_adaptive_pin_with<I: AdaptiveIntegrator, S: Scene<D>, const D: usize>(
    integrator: &I,
    scene: &S,
    record: &ToleranceLadderRecord,
    dir: &Path,
    update: bool,
    ci: bool,
) -> Result<AdaptivePinOutcome, String> {
    let who = format!(
        "stepladder: adaptive `{}` on `{}`",
        integrator.name(),
        scene.meta().id
    );
    check_names(integrator.name(), scene.meta().id).map_err(|e| format!("{who}: {e}"))?;
    let path = adaptive_pin_path(dir, integrator.name(), scene.meta().id);
    match std::fs::read_to_string(&path).ok() {
        Some(text) if !update => {
            let pin =
                AdaptivePin::parse(&text).map_err(|e| format!("{who}: {}: {e}", path.display()))?;
            let measured = error_at(integrator, scene, pin.t_end, pin.tolerance)
                .map_err(|e| format!("{who}: {e}"))?;
            let change = measured - pin.error;
            // false for a NaN error too
            if change.abs() <= pin.allowed {
                Ok(AdaptivePinOutcome::Agrees {
                    pin,
                    measured_error: measured,
                })
            } else {
                Err(format!(
                    "{who}: the error at TOL = {:e} is {measured:e}, pinned {:e} (every digit): it \
                     moved by {} > allowed {} (four times the larger of the twin run's change {} \
                     and the round-off {}): the integrator computes something else than when \
                     the pin was written. Rewrite the pin with STEPLADDER_UPDATE_PINS=1 if the \
                     change is intended",
                    pin.tolerance,
                    pin.error,
                    figure(change.abs()),
                    figure(pin.allowed),
                    figure(pin.twin_change),
                    figure(pin.round_off),
                ))
            }
        }
        _ if ci && !update => Err(missing_under_ci(&who, &path)),
        _ => {
            let pin = new_pin(integrator, scene, record).map_err(|e| format!("{who}: {e}"))?;
            write_pin(&who, &path, &pin.to_text())?;
            Ok(AdaptivePinOutcome::Written(pin))
        }
    }
}

/// The error of the run at `tol` to `t_end`, or why there is none.
fn error_at<I: AdaptiveIntegrator, S: Scene<D>, const D: usize>(
    integrator: &I,
    scene: &S,
    t_end: f64,
    tol: f64,
) -> Result<f64, String> {
    let p = tolerance_point(integrator, scene, t_end, tol).map_err(|e| e.to_string())?;
    match (p.end, p.error) {
        (RunEnd::Reached, Some(e)) => Ok(e),
        _ => Err(format!(
            "the run at TOL = {tol:e} to t_end = {t_end} did not reach t_end with an error"
        )),
    }
}

/// A new pin at the loosest tolerance whose error the ladder resolved.
fn new_pin<I: AdaptiveIntegrator, S: Scene<D>, const D: usize>(
    integrator: &I,
    scene: &S,
    record: &ToleranceLadderRecord,
) -> Result<AdaptivePin, String> {
    let chosen =
        record.points.iter().find(|p| p.fitted).ok_or(
            "no tolerance's error is resolved above round-off: nothing reproducible to pin",
        )?;
    let (tol, t_end) = (chosen.tolerance, record.t_end);
    let error = error_at(integrator, scene, t_end, tol)?;
    let twin = Scaled::new(scene, TWIN_SCALE);
    let twin_error = error_at(integrator, &twin, t_end, tol)? / TWIN_SCALE;
    let twin_change = (twin_error - error).abs();
    let allowed = 4.0 * twin_change.max(chosen.round_off);
    Ok(AdaptivePin {
        integrator: integrator.name().to_string(),
        scene: scene.meta().id.to_string(),
        tolerance: tol,
        t_end,
        accepted: chosen.accepted,
        error,
        twin_change: printed(twin_change, 2),
        round_off: printed(chosen.round_off, 2),
        // two significant digits rounded up: the printed value is at least
        // the derived one
        allowed: printed(1.05 * allowed, 1),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::KeplerCircular;
    use crate::scheme::DPRKN6_ADAPTIVE;
    use crate::study::adaptive::{ToleranceLadderSpec, tolerance_ladder};

    /// A name becomes a file stem of plain kebab-case, never a path.
    #[test]
    fn file_stems_are_plain_kebab_case() {
        assert_eq!(file_stem("DPRKN6(4) adaptive"), "dprkn6-4-adaptive");
        assert_eq!(file_stem("../../escaped pin"), "escaped-pin");
        assert_eq!(file_stem("--A__b--"), "a-b");
    }

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("stepladder-apin-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn a_pin_is_written_read_back_and_holds_then_catches_a_changed_error() {
        let spec = ToleranceLadderSpec {
            energy_periods: 0.0,
            ..Default::default()
        };
        let record = tolerance_ladder(&DPRKN6_ADAPTIVE, &KeplerCircular, &spec).unwrap();
        let dir = scratch("roundtrip");
        let check = |ci: bool| {
            check_adaptive_pin_with(&DPRKN6_ADAPTIVE, &KeplerCircular, &record, &dir, false, ci)
        };
        let written = check(false).unwrap();
        let AdaptivePinOutcome::Written(pin) = written else {
            panic!("a missing pin is written: {written:?}")
        };
        // the file says what it holds
        let path = adaptive_pin_path(&dir, DPRKN6_ADAPTIVE.name(), "kepler-circular");
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(AdaptivePin::parse(&text).unwrap(), pin);
        // the tolerance is far below the error, yet above its round-off
        assert!(pin.allowed < 1e-3 * pin.error, "{pin:?}");
        assert!(pin.allowed >= 4.0 * pin.round_off, "{pin:?}");
        // a rerun agrees
        let again = check(true).unwrap();
        assert!(
            matches!(again, AdaptivePinOutcome::Agrees { .. }),
            "{again:?}"
        );
        // a pinned error moved by twice its tolerance fails, naming both
        let mut moved = pin.clone();
        moved.error += 2.0 * pin.allowed;
        std::fs::write(&path, moved.to_text()).unwrap();
        let err = check(true).unwrap_err();
        assert!(err.contains("moved by") && err.contains("allowed"), "{err}");
        // under CI a missing pin is a failure, not a write
        std::fs::remove_file(&path).unwrap();
        let err = check(true).unwrap_err();
        assert!(err.contains("under CI"), "{err}");
        assert!(!path.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

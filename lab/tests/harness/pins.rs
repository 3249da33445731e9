//! The catalogue pins its own errors, as a downstream crate does (see
//! `stepladder::internals::accuracy::pin`): one file per scheme and built-in
//! scene in `snapshots/pins/`, committed. A refactor that moves a scheme's
//! error at the pinned step by more than the round-off the order study
//! measured there fails here, whatever it does to the order.
//!
//! Both sides of that tolerance are tested below on Forest-Ruth: a weight
//! retyped with ten or eight digits (a changed scheme the order study
//! passes) fails its pin; the same scheme with its operations in another
//! order, and the same run under another platform's rounding, pass.

use std::path::{Path, PathBuf};
use stepladder::internals::accuracy::order::{OrderSpec, global_order};
use stepladder::internals::accuracy::pin::{
    Pin, PinOutcome, check_pin_with, pin_path, pinned_error,
};
use stepladder::internals::parallel::{default_threads, parallel_map};
use stepladder::internals::run::integrate;
use stepladder::internals::tolerance::TWIN_SCALE;
use stepladder::nalgebra::SVector;
use stepladder::scene::{
    AnyScene, Harmonic, KeplerCircular, KeplerEccentric, Scaled, Scene, SceneMeta,
};
use stepladder::scheme::{
    FOREST_RUTH, Flow, OneStep, Rk4, Scheme, SchemeMeta, SplittingTable, StepFailure,
    VerletComposition, YOSHIDA6,
};
use stepladder::state::{Real, State};
use stepladder_lab::case::case;

#[test]
fn the_catalogue_keeps_its_pinned_errors() {
    let dir = crate::common::root().join("snapshots").join("pins");
    let jobs: Vec<(&str, AnyScene)> = stepladder::scheme::scheme_ids()
        .into_iter()
        .flat_map(|id| AnyScene::all().into_iter().map(move |scene| (id, scene)))
        .collect();
    let outcomes = parallel_map(
        &jobs,
        default_threads(),
        |(id, scene)| case(id, scene).map_err(|e| e.to_string())?.pin(&dir),
        &|_, _| {},
    );
    let failures: Vec<&String> = outcomes.iter().filter_map(|o| o.as_ref().err()).collect();
    assert!(
        failures.is_empty(),
        "{}",
        failures
            .iter()
            .map(|f| f.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
    let checked = outcomes
        .iter()
        .filter(|o| matches!(o, Ok(PinOutcome::Agrees { .. })))
        .count();
    // a pin is written only outside CI (a first run, or an update); under
    // CI a missing pin is one of the failures above
    eprintln!("{checked} pins agree, {} written", outcomes.len() - checked);
}

/// A fresh folder for one test's pins.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("stepladder-pins-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Writes the pin of `scheme` on `scene` in `dir` (whatever the
/// environment says) and returns it.
fn write_pin<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S, dir: &Path) -> Pin {
    match check_pin_with(scheme, scene, dir, true, false).expect("the pin is written") {
        PinOutcome::Written(pin) => pin,
        other => panic!("an update writes, got {other:?}"),
    }
}

/// Forest-Ruth with its outer weight `w1` as given and the middle one
/// `1 - 2 w1`, as the published formula has it, so that the weights sum to
/// one whatever `w1` is: the scheme a refactor gets when it types `w1`
/// with fewer digits. Built by the crate's composition machinery, under
/// Forest-Ruth's own claims (so its pin file).
fn forest_ruth_with(w1: f64) -> &'static SplittingTable {
    let stages: &'static VerletComposition<3, 4> =
        Box::leak(Box::new(VerletComposition::new([w1, 1.0 - 2.0 * w1, w1])));
    Box::leak(Box::new(stages.table(FOREST_RUTH.meta)))
}

/// The published outer weight `1 / (2 - 2^(1/3))` to seventeen digits, the
/// nearest double (what `FOREST_RUTH` uses).
const FOREST_RUTH_W1: f64 = 1.3512071919596575;

/// `x` rounded to `digits` significant decimal digits: a constant retyped
/// from a table that prints that many.
fn typed(x: f64, digits: usize) -> f64 {
    format!("{x:.*e}", digits - 1)
        .parse()
        .expect("a formatted float parses")
}

/// Checks `retyped` (claiming `original`'s id) against `original`'s pin on
/// `scene`: unless the order study already refutes it, the pin must fail.
/// Returns whether the order study passed it.
fn retyped_fails<M: Scheme, N: Scheme, S: Scene<D>, const D: usize>(
    original: &M,
    retyped: &N,
    scene: &S,
    what: &str,
) -> bool {
    let dir = scratch(&format!(
        "retyped-{}-{}",
        original.meta().id,
        scene.meta().id
    ));
    let pin = write_pin(original, scene, &dir);
    let record = global_order(retyped, scene, &OrderSpec::default()).unwrap();
    let error = pinned_error(retyped, scene, pin.t_end, pin.steps).unwrap();
    let outcome = check_pin_with(retyped, scene, &dir, false, true);
    eprintln!(
        "{} on {}, {what}: order study {} ({}), pinned error moved by {:.2e} of itself, tolerance {:.2e}",
        pin.scheme,
        pin.scene,
        record.verdict.name(),
        record
            .measured_order
            .map_or("no order".into(), |p| format!("{p:.4}")),
        (error - pin.error) / pin.error,
        pin.relative_tolerance()
    );
    let message = outcome.expect_err("no guard caught the retyped scheme");
    if record.passed() {
        assert!(message.contains("computes something else"), "{message}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    record.passed()
}

#[test]
fn a_forest_ruth_weight_retyped_with_ten_or_eight_digits_fails_its_pin() {
    // With w1 off by d, the weights still sum to one but sum w^3 = 2 w1^3 +
    // (1 - 2 w1)^3, which the order conditions set to zero, moves by (6 w1^2
    // - 6 (1 - 2 w1)^2) d = -6.4 d: a term ~ 6.4 d h^2 joins the error's
    // h^4. It overtakes the h^4 term only where h^2 ~ d / 6.4 (times the
    // ratio of the two terms' constants), steps at which the error is far
    // below the round-off floor, so the order study still measures 4; but at
    // the pinned coarse step the error moves by about d times its
    // sensitivity to w1, far above the tolerance.
    for digits in [10, 8] {
        let retyped = forest_ruth_with(typed(FOREST_RUTH_W1, digits));
        let what = format!("w1 to {digits} digits");
        for passed in [
            retyped_fails(&FOREST_RUTH, retyped, &Harmonic::default(), &what),
            retyped_fails(&FOREST_RUTH, retyped, &KeplerCircular, &what),
        ] {
            assert!(
                passed,
                "{what}: the order study saw it, so this tests no pin"
            );
        }
    }
}

#[test]
fn yoshida6_weights_retyped_with_ten_digits_fail_the_pin_eight_the_order() {
    // Yoshida's solution A with w1, w2, w3 typed to a number of digits and
    // w0 = 1 - 2 (w1 + w2 + w3), as the paper gives it: consistent, but the
    // higher order conditions are off by ~10^-digits, a term of order two
    // with that coefficient. With eight digits the order study sees it
    // before its round-off floor (an order reduction); with ten it does not,
    // and the pin is what catches it.
    let build = |digits: usize| -> &'static SplittingTable {
        let w = YOSHIDA6.composition.expect("a composition");
        let [w3, w2, w1] = [w[0], w[1], w[2]].map(|x| typed(x, digits));
        let w0 = 1.0 - 2.0 * (w1 + w2 + w3);
        let stages: &'static VerletComposition<7, 8> =
            Box::leak(Box::new(VerletComposition::new([
                w3, w2, w1, w0, w1, w2, w3,
            ])));
        Box::leak(Box::new(stages.table(YOSHIDA6.meta)))
    };
    let orbit = KeplerCircular;
    assert!(retyped_fails(
        &YOSHIDA6,
        build(10),
        &orbit,
        "weights to 10 digits"
    ));
    assert!(!retyped_fails(
        &YOSHIDA6,
        build(8),
        &orbit,
        "weights to 8 digits"
    ));
}

/// A splitting table run by a hand-written step whose products associate
/// the other way, `(v h) c` and `(a h) c` where the crate's stepper forms
/// `v (h c)` and `a (h c)`, and which evaluates the force afresh at every
/// step instead of reusing the last kick's: the same scheme in exact
/// arithmetic, other roundings.
struct Reassociated(&'static SplittingTable);

impl OneStep for Reassociated {
    fn meta(&self) -> &SchemeMeta {
        &self.0.meta
    }
    fn advance<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        for (flow, c) in self.0.sequence() {
            match flow {
                Flow::Drift => s.q += (s.v * h) * R::of(c),
                Flow::Kick => s.v += (scene.acceleration(&s.q) * h) * R::of(c),
            }
        }
        Ok(())
    }
}

/// The end state of `steps` steps of `scheme` over `t_end` on `scene`.
fn end_state<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    t_end: f64,
    steps: u64,
) -> State<D> {
    let mut last = scene.initial();
    integrate(
        scheme,
        scene,
        &scene.initial(),
        t_end / steps as f64,
        steps,
        |_, _, s| last = *s,
    );
    last
}

/// Writes the pin of `original` on `scene`, then checks `changed`, the same
/// scheme with its roundings in another order, against it: the two runs
/// must differ (else the check tests nothing) and the pin must agree.
fn reordering_keeps_the_pin<M: Scheme, N: Scheme, S: Scene<D>, const D: usize>(
    original: &M,
    changed: &N,
    scene: &S,
    name: &str,
) {
    let dir = scratch(&format!("reorder-{name}-{}", scene.meta().id));
    let pin = write_pin(original, scene, &dir);
    assert_ne!(
        end_state(original, scene, pin.t_end, pin.steps),
        end_state(changed, scene, pin.t_end, pin.steps),
        "{name}: the same bits, so this tests nothing"
    );
    match check_pin_with(changed, scene, &dir, false, true)
        .unwrap_or_else(|m| panic!("{name}: {m}"))
    {
        PinOutcome::Agrees { measured_error, .. } => eprintln!(
            "{} {name} on {}: pinned error moved by {:.2e} of itself, tolerance {:.2e}",
            pin.scheme,
            pin.scene,
            (measured_error - pin.error) / pin.error,
            pin.relative_tolerance()
        ),
        other => panic!("{name}: {other:?}"),
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn forest_ruth_with_its_operations_reordered_keeps_its_pin() {
    // Two refactors that change no number of the scheme, only the order in
    // which it rounds: the composition written as its three Verlet steps,
    // each half kick applied on its own instead of merged with its
    // neighbour (K(w1/2) D(w1) K(w1/2) K(w2/2) D(w2) ...: a drift of zero
    // between two kicks moves nothing), and the crate's table stepped with
    // its products associated the other way.
    let w = FOREST_RUTH.drift;
    let (w1, w2) = (w[0], w[1]);
    let drift: &'static [f64] = Box::leak(Box::new([w1, 0.0, w2, 0.0, w1]));
    let kick: &'static [f64] = Box::leak(Box::new([
        0.5 * w1,
        0.5 * w1,
        0.5 * w2,
        0.5 * w2,
        0.5 * w1,
        0.5 * w1,
    ]));
    let unmerged = SplittingTable::new(FOREST_RUTH.meta, Flow::Kick, drift, kick);
    let reassociated = Reassociated(&FOREST_RUTH);
    let osc = Harmonic::default();
    reordering_keeps_the_pin(&FOREST_RUTH, &unmerged, &osc, "unmerged");
    reordering_keeps_the_pin(&FOREST_RUTH, &reassociated, &osc, "reassociated");
    reordering_keeps_the_pin(&FOREST_RUTH, &unmerged, &KeplerCircular, "unmerged");
    reordering_keeps_the_pin(&FOREST_RUTH, &reassociated, &KeplerCircular, "reassociated");
}

/// RK4 with its stage points and its weighted sum formed in another order:
/// `q + (k h) / 2` for `q + k (h / 2)`, and `(k1 + 2 k2 + 2 k3 + k4) h / 6`
/// summed left to right, where the crate's `Rk4` forms `k1 + (k2 + k3) 2 +
/// k4` and multiplies by `h / 6`: the same scheme, other roundings.
struct Rk4SummedOtherwise;

impl OneStep for Rk4SummedOtherwise {
    fn meta(&self) -> &SchemeMeta {
        &Rk4::META
    }
    fn advance<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), StepFailure> {
        let (two, six) = (R::of(2.0), R::of(6.0));
        let (k1q, k1v) = (s.v, scene.acceleration(&s.q));
        let (k2q, k2v) = (
            s.v + (k1v * h) / two,
            scene.acceleration(&(s.q + (k1q * h) / two)),
        );
        let (k3q, k3v) = (
            s.v + (k2v * h) / two,
            scene.acceleration(&(s.q + (k2q * h) / two)),
        );
        let (k4q, k4v) = (s.v + k3v * h, scene.acceleration(&(s.q + k3q * h)));
        s.q += (k1q + k2q * two + k3q * two + k4q) * h / six;
        s.v += (k1v + k2v * two + k3v * two + k4v) * h / six;
        Ok(())
    }
}

#[test]
fn rk4_with_its_stages_summed_in_another_order_keeps_its_pin() {
    reordering_keeps_the_pin(&Rk4, &Rk4SummedOtherwise, &KeplerCircular, "resummed");
    reordering_keeps_the_pin(
        &Rk4,
        &Rk4SummedOtherwise,
        &KeplerEccentric::new(0.6).expect("a valid eccentricity"),
        "resummed",
    );
}

/// `inner` computed in units of length [`TWIN_SCALE`] smaller (as the
/// order study's twin is), its distances and size read back in `inner`'s
/// units: the same run as `inner`'s with every rounding drawn anew, as on
/// another machine.
#[derive(Clone, Copy)]
struct OtherUnits<S> {
    inner: S,
    scaled: Scaled<S>,
}

impl<S: Copy> OtherUnits<S> {
    fn new(inner: S) -> Self {
        Self {
            inner,
            scaled: Scaled::new(inner, TWIN_SCALE),
        }
    }
}

impl<S: Scene<D> + Copy, const D: usize> Scene<D> for OtherUnits<S> {
    fn meta(&self) -> SceneMeta {
        self.inner.meta()
    }
    fn initial(&self) -> State<D> {
        self.scaled.initial()
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, D>) -> SVector<R, D> {
        self.scaled.acceleration(q)
    }
    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R {
        self.scaled.potential(q)
    }
    fn period(&self) -> f64 {
        self.inner.period()
    }
    fn exact(&self, t: f64) -> Option<State<D>> {
        self.scaled.exact(t)
    }
    fn phase_distance(&self, a: &State<D>, b: &State<D>) -> f64 {
        self.inner
            .phase_distance(&self.scaled.back(a), &self.scaled.back(b))
    }
    fn scale(&self) -> f64 {
        self.inner.scale()
    }
    fn default_t_end(&self) -> f64 {
        self.inner.default_t_end()
    }
}

/// `inner` as another platform's libm might compute it: every component of
/// the exact solution off by [`EXACT_SOLUTION_ULPS`]` / 2` ulps (signs
/// alternating), and every force an ulp high.
#[derive(Clone, Copy)]
struct OtherLibm<S>(S);

const LIBM_ULPS: f64 = stepladder::internals::tolerance::EXACT_SOLUTION_ULPS / 2.0;

impl<S: Scene<D>, const D: usize> Scene<D> for OtherLibm<S> {
    fn meta(&self) -> SceneMeta {
        self.0.meta()
    }
    fn initial(&self) -> State<D> {
        self.0.initial()
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, D>) -> SVector<R, D> {
        self.0.acceleration(q) * R::of(1.0 + f64::EPSILON)
    }
    fn potential<R: Real>(&self, q: &SVector<R, D>) -> R {
        self.0.potential(q)
    }
    fn period(&self) -> f64 {
        self.0.period()
    }
    fn exact(&self, t: f64) -> Option<State<D>> {
        self.0.exact(t).map(|s| {
            let off = |x: SVector<f64, D>, sign: f64| {
                SVector::<f64, D>::from_fn(|i, _| {
                    let s = if i % 2 == 0 { sign } else { -sign };
                    x[i] * (1.0 + s * LIBM_ULPS * f64::EPSILON)
                })
            };
            State::new(off(s.q, 1.0), off(s.v, -1.0))
        })
    }
    fn phase_distance(&self, a: &State<D>, b: &State<D>) -> f64 {
        self.0.phase_distance(a, b)
    }
    fn scale(&self) -> f64 {
        self.0.scale()
    }
    fn default_t_end(&self) -> f64 {
        self.0.default_t_end()
    }
}

#[test]
fn a_pin_survives_another_platforms_rounding() {
    // the pin written on one machine, checked against the same scheme on
    // the same scene rounded as elsewhere: in other units of length (every
    // rounding drawn anew), and with an exact solution and forces a few
    // ulps off (another libm); Forest-Ruth and Yoshida's sixth order on the
    // oscillator and the circular orbit
    fn both<M: Scheme, S: Scene<D> + Copy, const D: usize>(scheme: &M, scene: S) {
        let dir = scratch(&format!(
            "platform-{}-{}",
            scheme.meta().id,
            scene.meta().id
        ));
        let pin = write_pin(scheme, &scene, &dir);
        for (name, outcome) in [
            (
                "other units",
                check_pin_with(scheme, &OtherUnits::new(scene), &dir, false, true),
            ),
            (
                "other libm",
                check_pin_with(scheme, &OtherLibm(scene), &dir, false, true),
            ),
        ] {
            match outcome.unwrap_or_else(|m| panic!("{name}: {m}")) {
                PinOutcome::Agrees { measured_error, .. } => {
                    let change = measured_error - pin.error;
                    // the rounding did change the error: not a vacuous pass
                    assert_ne!(change, 0.0, "{name}: bit-identical");
                    eprintln!(
                        "{} on {} in {name}: moved by {:.2e} of the tolerance",
                        pin.scheme,
                        pin.scene,
                        change.abs() / pin.tolerance
                    );
                }
                other => panic!("{name}: {other:?}"),
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
    both(&FOREST_RUTH, Harmonic::default());
    both(&FOREST_RUTH, KeplerCircular);
    both(&YOSHIDA6, KeplerCircular);
}

#[test]
fn a_pin_is_written_refused_under_ci_and_rewritten_on_request() {
    let osc = Harmonic::default();
    let dir = scratch("workflow");
    // under CI a missing pin fails, and nothing is written
    let refused = check_pin_with(&FOREST_RUTH, &osc, &dir, false, true).unwrap_err();
    assert!(refused.contains("under CI"), "{refused}");
    assert!(!pin_path(&dir, "forest-ruth", "harmonic").exists());
    // the first run outside CI writes it, the next ones agree
    assert!(matches!(
        check_pin_with(&FOREST_RUTH, &osc, &dir, false, false).unwrap(),
        PinOutcome::Written(_)
    ));
    assert!(matches!(
        check_pin_with(&FOREST_RUTH, &osc, &dir, false, true).unwrap(),
        PinOutcome::Agrees { .. }
    ));
    // a pin that no longer agrees is rewritten on request, even under CI
    let retyped = forest_ruth_with(typed(FOREST_RUTH_W1, 8));
    check_pin_with(retyped, &osc, &dir, false, true).unwrap_err();
    assert!(matches!(
        check_pin_with(retyped, &osc, &dir, true, true).unwrap(),
        PinOutcome::Written(_)
    ));
    assert!(matches!(
        check_pin_with(retyped, &osc, &dir, false, true).unwrap(),
        PinOutcome::Agrees { .. }
    ));
    let _ = std::fs::remove_dir_all(&dir);
}

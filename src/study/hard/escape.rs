//! Escape or trapped: does a scheme tell an orbit just below the barrier of
//! the anharmonic well from one just above it, and from which step down?
//!
//! Two orbits start at the bottom with energies `E_b (1 - delta)` (trapped:
//! it turns at `|x| = alpha sqrt(1 - sqrt(delta)) < alpha` for ever) and
//! `E_b (1 + delta)` (escaping: it passes `x = alpha` within its first
//! quarter period and runs away). Each runs for [`ESCAPE_PERIODS`] periods
//! of the trapped orbit; the trapped one is classified correctly when `|x|`
//! stays below `alpha` throughout, the escaping one when `|x|` reaches
//! `alpha`. The orbits cross the barrier region where the flow separates
//! neighbouring orbits like `e^(sqrt(2k) t)`, so what decides is the sign and
//! size of the energy error the scheme carries there: a symplectic scheme
//! whose error at the barrier is `dE ~ c E_b h^q` misclassifies the orbit on
//! the wrong side of the barrier once `|c| h^q > delta`, that is above `h* =
//! (delta / |c|)^(1/q)`; a scheme whose energy drifts misclassifies the
//! trapped orbit once the drift over the run exceeds `delta E_b`.
//!
//! The largest correct step is found by a scan down from `4 / sqrt(k)` in
//! ratios of `2^(-1/4)` to the first step where both orbits are classified
//! correctly, confirmed on every scan point down to half of it, then bisected
//! between it and the failing scan point above.

use crate::error::Error;
use crate::run::guarded_step;
use crate::scene::{Anharmonic, Scene, WellOrbit};
use crate::scheme::Scheme;
use crate::tolerance::{
    ESCAPE_BISECTIONS, ESCAPE_CONFIRM_FACTOR, ESCAPE_MAX_STEPS, ESCAPE_PERIODS,
};
use serde::Serialize;

/// The study's well and energy gap.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EscapeSpec {
    /// Stiffness at the bottom.
    pub k: f64,
    /// Barrier position.
    pub alpha: f64,
    /// Relative gap `delta` of both energies from the barrier, in `(0, 1)`.
    pub delta: f64,
}

/// The smallest relative gap from the barrier: `1e-12`, some ten thousand
/// rounding units (`2.2e-16`) of the energy, so the orbits on both sides are
/// told apart by more than the round-off of their energies.
pub const MIN_DELTA: f64 = 1e-12;

impl EscapeSpec {
    /// The course notes' well with a gap of `delta`.
    pub fn new(delta: f64) -> Result<Self, Error> {
        // below MIN_DELTA the gap is lost in the rounding of E_b (1 - delta)
        if !(MIN_DELTA..1.0).contains(&delta) {
            return Err(Error::InvalidParameter {
                name: "delta",
                value: delta,
                expected: "a relative energy gap in [1e-12, 1) (the trapped energy E_b (1 - delta) \
                           must stay positive, and its gap from E_b resolved by ten thousand \
                           rounding units of the energy)",
            });
        }
        Ok(Self {
            k: 1.0,
            alpha: 1.0,
            delta,
        })
    }
}

/// One orbit at one step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OrbitRun {
    /// The time `|x|` first reached `alpha` (or the state stopped being
    /// finite, or a step failed): `None` when it stayed inside.
    pub crossed_at: Option<f64>,
    /// `(E - E0) / (delta E_b)` at the orbit's first arrival at the barrier
    /// region: its first turning point, or the step that crossed.
    pub first_approach_error: Option<f64>,
    /// `(E - E0) / (delta E_b)` at the step that crossed, if one did.
    pub crossing_error: Option<f64>,
    /// Steps taken.
    pub steps: u64,
}

/// Both orbits at one step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Classification {
    /// The step.
    pub h: f64,
    /// The orbit below the barrier.
    pub trapped: OrbitRun,
    /// The orbit above it.
    pub escaping: OrbitRun,
}

impl Classification {
    /// The trapped orbit stayed inside.
    pub fn trapped_ok(&self) -> bool {
        self.trapped.crossed_at.is_none()
    }
    /// The escaping orbit crossed.
    pub fn escaping_ok(&self) -> bool {
        self.escaping.crossed_at.is_some()
    }
    /// Both right.
    pub fn correct(&self) -> bool {
        self.trapped_ok() && self.escaping_ok()
    }
}

/// Which orbit a scheme gets wrong just above its largest correct step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Misclassified {
    /// The trapped orbit escapes.
    TrappedEscapes,
    /// The escaping orbit stays trapped.
    EscapingTrapped,
    /// Both.
    Both,
}

impl Misclassified {
    /// `(E - E0) / (delta E_b)` of the misclassified orbit at the barrier:
    /// where the trapped orbit crossed, or where the escaping one first
    /// turned back.
    pub fn barrier_error(self, c: &Classification) -> Option<f64> {
        match self {
            Misclassified::TrappedEscapes => c.trapped.crossing_error,
            Misclassified::EscapingTrapped => c.escaping.first_approach_error,
            Misclassified::Both => None,
        }
    }

    /// A short description.
    pub fn describe(self) -> &'static str {
        match self {
            Misclassified::TrappedEscapes => "trapped orbit escapes",
            Misclassified::EscapingTrapped => "escaping orbit stays trapped",
            Misclassified::Both => "both wrong",
        }
    }
}

/// What the study found for one scheme.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EscapeRecord {
    /// Scheme id.
    pub scheme: &'static str,
    /// Claims to be symplectic.
    pub symplectic: bool,
    /// The study.
    pub spec: EscapeSpec,
    /// The trapped orbit's exact period.
    pub trapped_period: f64,
    /// Length of every run.
    pub t_obs: f64,
    /// The largest correct step, bisected.
    pub largest_correct: Option<f64>,
    /// The scan points it was bisected between: `[correct, wrong]`.
    pub bracket: Option<[f64; 2]>,
    /// The classification at the bisected step (correct) and just above it.
    pub at_boundary: Option<[Classification; 2]>,
    /// What goes wrong just above the boundary.
    pub fails_by: Option<Misclassified>,
    /// The misclassified orbit crossed (or turned) at its first approach to
    /// the barrier, where the energy error the scheme carries there from the
    /// start decides, as on the separatrix.
    pub first_approach: Option<bool>,
    /// The finest step scanned.
    pub finest_scanned: f64,
    /// Every scan point, coarse to fine (bisection points excluded).
    pub scan: Vec<Classification>,
    /// Steps taken in all.
    pub steps: u64,
}

/// Runs the escape-or-trapped study for `scheme`.
pub fn escape_or_trapped<M: Scheme>(scheme: &M, spec: EscapeSpec) -> Result<EscapeRecord, Error> {
    let spec = EscapeSpec::new(spec.delta).map(|s| EscapeSpec {
        k: spec.k,
        alpha: spec.alpha,
        ..s
    })?;
    let setup = Setup::new(spec)?;
    let (period, t_obs) = (setup.period, setup.t_obs);
    let unit = 1.0 / spec.k.sqrt();
    let ratio = 2f64.powf(-0.25);
    let classify = |h: f64| setup.classify(scheme, h);
    let affordable = |h: f64| t_obs / h <= ESCAPE_MAX_STEPS as f64;
    let mut scan: Vec<Classification> = Vec::new();
    let mut steps = 0u64;
    // scan: the first correct point whose every finer point down to
    // ESCAPE_CONFIRM_FACTOR of it is correct too
    let mut candidate: Option<usize> = None;
    let mut j = 0;
    loop {
        let h = 4.0 * unit * ratio.powi(j);
        if !affordable(h) {
            break;
        }
        let c = classify(h);
        steps += c.trapped.steps + c.escaping.steps;
        scan.push(c);
        let i = scan.len() - 1;
        match (c.correct(), candidate) {
            (true, None) => candidate = Some(i),
            (false, Some(_)) => candidate = None,
            _ => {}
        }
        if let Some(first) = candidate
            && h <= ESCAPE_CONFIRM_FACTOR * scan[first].h * (1.0 + 1e-12)
        {
            break;
        }
        j += 1;
    }
    let finest_scanned = scan.last().map_or(f64::NAN, |c| c.h);
    let confirmed = candidate.filter(|&i| {
        scan.last()
            .is_some_and(|c| c.h <= ESCAPE_CONFIRM_FACTOR * scan[i].h * (1.0 + 1e-12))
    });
    let (mut largest_correct, mut bracket, mut at_boundary) = (None, None, None);
    if let Some(i) = confirmed {
        if i == 0 {
            // correct at the coarsest step scanned: no boundary to bisect
            largest_correct = Some(scan[0].h);
        } else {
            let (mut good, mut bad) = (scan[i], scan[i - 1]);
            bracket = Some([good.h, bad.h]);
            for _ in 0..ESCAPE_BISECTIONS {
                let c = classify((good.h * bad.h).sqrt());
                steps += c.trapped.steps + c.escaping.steps;
                if c.correct() {
                    good = c;
                } else {
                    bad = c;
                }
            }
            largest_correct = Some(good.h);
            at_boundary = Some([good, bad]);
        }
    }
    let fails_by = at_boundary.map(|[_, bad]| match (bad.trapped_ok(), bad.escaping_ok()) {
        (false, true) => Misclassified::TrappedEscapes,
        (true, false) => Misclassified::EscapingTrapped,
        _ => Misclassified::Both,
    });
    // the failure happened at the first approach when the wrong crossing
    // came within the first half period (trapped orbit escaping) or the
    // escaping orbit turned at its first approach and never crossed
    let first_approach = at_boundary.and_then(|[_, bad]| match fails_by? {
        Misclassified::TrappedEscapes => Some(bad.trapped.crossed_at? < 0.5 * period),
        Misclassified::EscapingTrapped => Some(true),
        Misclassified::Both => None,
    });
    Ok(EscapeRecord {
        scheme: scheme.meta().id,
        symplectic: scheme.meta().symplectic,
        spec,
        trapped_period: period,
        t_obs,
        largest_correct,
        bracket,
        at_boundary,
        fails_by,
        first_approach,
        finest_scanned,
        scan,
        steps,
    })
}

/// The two orbits of a study and its observation time.
struct Setup {
    spec: EscapeSpec,
    trapped: WellOrbit,
    escaping: WellOrbit,
    /// The trapped orbit's exact period.
    period: f64,
    /// [`ESCAPE_PERIODS`] of them.
    t_obs: f64,
}

impl Setup {
    fn new(spec: EscapeSpec) -> Result<Self, Error> {
        let trapped = WellOrbit::relative_to_barrier(spec.k, spec.alpha, -spec.delta)?;
        let escaping = WellOrbit::relative_to_barrier(spec.k, spec.alpha, spec.delta)?;
        let v_trapped = trapped.initial().v[0];
        let period = Anharmonic::new(spec.k, spec.alpha, 0.0, v_trapped)?.period();
        Ok(Self {
            spec,
            trapped,
            escaping,
            period,
            t_obs: ESCAPE_PERIODS * period,
        })
    }

    fn classify<M: Scheme>(&self, scheme: &M, h: f64) -> Classification {
        Classification {
            h,
            trapped: run_orbit(scheme, &self.trapped, self.spec.delta, h, self.t_obs),
            escaping: run_orbit(scheme, &self.escaping, self.spec.delta, h, self.t_obs),
        }
    }
}

/// Classifies both orbits of `spec` with `scheme` at the one step `h`, over
/// the study's observation time.
pub fn classify_at<M: Scheme>(
    scheme: &M,
    spec: EscapeSpec,
    h: f64,
) -> Result<Classification, Error> {
    let h = crate::scene::positive("h", h)?;
    let setup = Setup::new(EscapeSpec::new(spec.delta).map(|s| EscapeSpec {
        k: spec.k,
        alpha: spec.alpha,
        ..s
    })?)?;
    crate::ladder::check_cost((setup.t_obs / h).ceil() as u64)?;
    Ok(setup.classify(scheme, h))
}

/// Runs one orbit for `t_obs`, or until `|x|` reaches `alpha`.
fn run_orbit<M: Scheme>(scheme: &M, orbit: &WellOrbit, delta: f64, h: f64, t_obs: f64) -> OrbitRun {
    let alpha = orbit.alpha();
    let start = orbit.initial();
    let e0 = orbit.energy(&start);
    let gap = delta * orbit.barrier();
    let steps = (t_obs / h).ceil() as u64;
    let mut carry = scheme.start(orbit, &start, h);
    let mut last_v = start.v[0];
    let mut out = OrbitRun {
        crossed_at: None,
        first_approach_error: None,
        crossing_error: None,
        steps: 0,
    };
    for n in 1..=steps {
        out.steps = n;
        let t = n as f64 * h;
        if guarded_step(scheme, orbit, &mut carry, h).is_err() {
            out.crossed_at = Some(t);
            break;
        }
        let s = scheme.state(&carry, h);
        if !s.is_finite() {
            out.crossed_at = Some(t);
            break;
        }
        let crossed = s.q[0].abs() >= alpha;
        if out.first_approach_error.is_none() && (crossed || s.v[0] * last_v <= 0.0) {
            out.first_approach_error = Some((orbit.energy(&s) - e0) / gap);
        }
        if crossed {
            out.crossed_at = Some(t);
            out.crossing_error = Some((orbit.energy(&s) - e0) / gap);
            break;
        }
        last_v = s.v[0];
    }
    out
}

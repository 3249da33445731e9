//! The hard cases of the report: eccentric Kepler orbits, the separatrix of
//! the anharmonic well, and escape or trapped near its barrier. Each study
//! is split into independent jobs (one scheme, one parameter) so that they
//! spread over the suite's threads; results are stored by job, so they are
//! the same whatever the thread count.

use std::time::{Duration, Instant};
use stepladder::error::Error;
use stepladder::internals::hard::eccentric::{
    ECCENTRICITIES, EccentricEnergyRecord, EccentricOrderRecord, ORDER_SCHEMES, Pericentre,
    RoundOffRecord, eccentric_energy, eccentric_order, stormer_round_off,
};
use stepladder::internals::hard::escape::{EscapeRecord, EscapeSpec, escape_or_trapped};
use stepladder::internals::hard::following::{FollowingRecord, WellSpec, following};
use stepladder::internals::tolerance::{
    ECCENTRIC_ENERGY_PERIODS, ECCENTRIC_MAX_RUNG_STEPS, ENERGY_STEPS_PER_PERICENTRE,
};
use stepladder::scene::KeplerEccentric;
use stepladder::scheme::{Scheme, SchemeVisitor, scheme_ids, visit_scheme};

/// The energy gaps of the escape-or-trapped study in the report.
pub const ESCAPE_DELTAS: [f64; 2] = [1e-2, 1e-3];

/// The main energy study's step, in periods, used as the naive step on the
/// eccentric orbits.
pub const NAIVE_STEP: f64 = stepladder::internals::geometry::energy::DEFAULT_STEP;

/// One unit of work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HardJob {
    /// The order study of a scheme on an eccentric orbit, with the largest
    /// rung in steps.
    Order(&'static str, f64, u64),
    /// The energy of a scheme on an eccentric orbit at `tau_p / 8` and at
    /// the naive step.
    Energy(&'static str, f64),
    /// Störmer's and leap-frog's round-off against velocity Verlet.
    RoundOff(f64),
    /// The separatrix study of a scheme in a well.
    Following(&'static str, WellSpec),
    /// The escape-or-trapped study of a scheme at a gap.
    Escape(&'static str, f64),
}

/// What a job produced.
#[derive(Clone, Debug)]
pub enum HardOutput {
    /// See [`HardJob::Order`].
    Order(Box<EccentricOrderRecord>),
    /// See [`HardJob::Energy`]: at `tau_p / 8`, at the naive step.
    Energy(Box<[EccentricEnergyRecord; 2]>),
    /// See [`HardJob::RoundOff`].
    RoundOff(Box<RoundOffRecord>),
    /// See [`HardJob::Following`].
    Following(Box<FollowingRecord>),
    /// See [`HardJob::Escape`].
    Escape(Box<EscapeRecord>),
}

/// Every job of the report's hard cases, the expensive ones first so that
/// they start early.
pub fn hard_jobs() -> Vec<HardJob> {
    let ids = scheme_ids();
    let mut jobs = Vec::new();
    for e in ECCENTRICITIES.iter().rev() {
        jobs.extend(
            ORDER_SCHEMES
                .iter()
                .map(|id| HardJob::Order(id, *e, ECCENTRIC_MAX_RUNG_STEPS)),
        );
    }
    for e in ECCENTRICITIES.iter().rev() {
        jobs.extend(ids.iter().map(|id| HardJob::Energy(id, *e)));
        jobs.push(HardJob::RoundOff(*e));
    }
    for d in ESCAPE_DELTAS.iter().rev() {
        jobs.extend(ids.iter().map(|id| HardJob::Escape(id, *d)));
    }
    jobs.extend(
        ids.iter()
            .map(|id| HardJob::Following(id, WellSpec::default())),
    );
    jobs
}

impl HardJob {
    /// Runs the job.
    pub fn run(self) -> Result<HardOutput, Error> {
        match self {
            HardJob::Order(id, e, cap) => visit_scheme(id, OrderOf(e, cap))?
                .map(Box::new)
                .map(HardOutput::Order),
            HardJob::Energy(id, e) => visit_scheme(id, EnergyOf(e))?
                .map(Box::new)
                .map(HardOutput::Energy),
            HardJob::RoundOff(e) => {
                let tau = Pericentre::of(&KeplerEccentric::new(e)?).time_scale;
                stormer_round_off(e, tau / ENERGY_STEPS_PER_PERICENTRE)
                    .map(Box::new)
                    .map(HardOutput::RoundOff)
            }
            HardJob::Following(id, well) => visit_scheme(id, FollowingOf(well))?
                .map(Box::new)
                .map(HardOutput::Following),
            HardJob::Escape(id, delta) => {
                let spec = EscapeSpec::new(delta)?;
                visit_scheme(id, EscapeOf(spec))?
                    .map(Box::new)
                    .map(HardOutput::Escape)
            }
        }
    }
}

struct OrderOf(f64, u64);
impl SchemeVisitor for OrderOf {
    type Output = Result<EccentricOrderRecord, Error>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output {
        eccentric_order(scheme, self.0, self.1)
    }
}

struct EnergyOf(f64);
impl SchemeVisitor for EnergyOf {
    type Output = Result<[EccentricEnergyRecord; 2], Error>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output {
        let e = self.0;
        let orbit = KeplerEccentric::new(e)?;
        let tau = Pericentre::of(&orbit).time_scale;
        Ok([
            eccentric_energy(
                scheme,
                e,
                tau / ENERGY_STEPS_PER_PERICENTRE,
                ECCENTRIC_ENERGY_PERIODS,
            )?,
            eccentric_energy(scheme, e, NAIVE_STEP, ECCENTRIC_ENERGY_PERIODS)?,
        ])
    }
}

struct FollowingOf(WellSpec);
impl SchemeVisitor for FollowingOf {
    type Output = Result<FollowingRecord, Error>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output {
        following(scheme, self.0)
    }
}

struct EscapeOf(EscapeSpec);
impl SchemeVisitor for EscapeOf {
    type Output = Result<EscapeRecord, Error>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Self::Output {
        escape_or_trapped(scheme, self.0)
    }
}

/// Every record of the hard cases.
#[derive(Clone, Debug, Default)]
pub struct HardCases {
    /// Orders on eccentric orbits, scheme-major in catalogue order,
    /// eccentricity-minor.
    pub orders: Vec<EccentricOrderRecord>,
    /// Energies at `tau_p / 8`, catalogue-major, eccentricity-minor.
    pub energy: Vec<EccentricEnergyRecord>,
    /// Energies at the naive step, in the same order.
    pub naive_energy: Vec<EccentricEnergyRecord>,
    /// Störmer's round-off, one per eccentricity.
    pub round_off: Vec<RoundOffRecord>,
    /// The separatrix study, one per scheme.
    pub following: Vec<FollowingRecord>,
    /// Escape or trapped, gap-major in [`ESCAPE_DELTAS`] order.
    pub escape: Vec<EscapeRecord>,
    /// Wall time spent in the jobs, summed (machine-dependent).
    pub work: Duration,
}

impl HardCases {
    /// Sorts job outputs (in any order) into the records.
    pub fn assemble(mut outputs: Vec<(HardJob, HardOutput, Duration)>) -> Self {
        // catalogue order of schemes, increasing eccentricity, decreasing gap
        let ids = scheme_ids();
        let position = |id: &str| ids.iter().position(|x| *x == id).unwrap_or(usize::MAX) as u64;
        let key = |job: &HardJob| -> (u8, u64, u64) {
            match *job {
                HardJob::Order(id, e, _) => (0, position(id), e.to_bits()),
                HardJob::Energy(id, e) => (1, position(id), e.to_bits()),
                HardJob::RoundOff(e) => (2, e.to_bits(), 0),
                HardJob::Following(id, _) => (3, position(id), 0),
                HardJob::Escape(id, d) => (4, u64::MAX - d.to_bits(), position(id)),
            }
        };
        outputs.sort_by_key(|(job, _, _)| key(job));
        let mut out = HardCases::default();
        for (_, output, time) in outputs {
            out.work += time;
            match output {
                HardOutput::Order(r) => out.orders.push(*r),
                HardOutput::Energy(r) => {
                    let [fine, naive] = *r;
                    out.energy.push(fine);
                    out.naive_energy.push(naive);
                }
                HardOutput::RoundOff(r) => out.round_off.push(*r),
                HardOutput::Following(r) => out.following.push(*r),
                HardOutput::Escape(r) => out.escape.push(*r),
            }
        }
        out
    }

    /// Steps taken over every study (each eccentric order step also compared
    /// with the exact orbit).
    pub fn steps(&self) -> u64 {
        self.orders.iter().map(|r| r.steps).sum::<u64>()
            + self
                .energy
                .iter()
                .chain(&self.naive_energy)
                .map(|r| r.steps)
                .sum::<u64>()
            + self.round_off.iter().map(|r| 3 * r.steps).sum::<u64>()
            + self.following.iter().map(|r| r.steps).sum::<u64>()
            + self.escape.iter().map(|r| r.steps).sum::<u64>()
    }

    /// Steps of the eccentric order study, each compared with the exact orbit
    /// (Kepler's equation solved to round-off): the dearest steps of all.
    pub fn exact_steps(&self) -> u64 {
        self.orders.iter().map(|r| r.steps).sum()
    }

    /// The record of the escape study for `scheme` at gap `delta`.
    pub fn escape_of(&self, scheme: &str, delta: f64) -> Option<&EscapeRecord> {
        self.escape
            .iter()
            .find(|r| r.scheme == scheme && r.spec.delta == delta)
    }

    /// The separatrix record of `scheme`.
    pub fn following_of(&self, scheme: &str) -> Option<&FollowingRecord> {
        self.following.iter().find(|r| r.scheme == scheme)
    }
}

/// Runs `jobs` on `threads` threads (at least one).
pub fn run_hard_jobs(jobs: Vec<HardJob>, threads: usize) -> Result<HardCases, Error> {
    let results = stepladder::internals::parallel::parallel_map(
        &jobs,
        threads,
        |job| {
            let t = Instant::now();
            (job.run(), t.elapsed())
        },
        &|_, _| {},
    );
    let mut outputs = Vec::with_capacity(jobs.len());
    for (job, (result, time)) in jobs.into_iter().zip(results) {
        outputs.push((job, result?, time));
    }
    Ok(HardCases::assemble(outputs))
}

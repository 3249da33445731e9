//! Geometry against theory: modified energies of the oscillator, analytic
//! symplectic defects, metadata against measurement, and schemes or scenes
//! that lie about themselves.

use nalgebra::{SVector, Vector1};
use stepladder::internals::accuracy::scene_check::check_scene;
use stepladder::internals::geometry::energy::{EnergyClass, EnergySpec, energy_drift};
use stepladder::internals::geometry::reverse::{ReverseSpec, reversibility};
use stepladder::internals::geometry::symplectic::{SymplecticSpec, symplecticity};
use stepladder::internals::maths::tangent::step_jacobian;
use stepladder::internals::run::integrate;
use stepladder::scene::{Harmonic, KeplerCircular, Scene, SceneMeta};
use stepladder::scheme::{
    EULER_CROMER, Euler, Flow, Rk4, SchemeMeta, SplittingTable, VELOCITY_VERLET,
};
use stepladder::state::{Real, State};
use stepladder::study::Verdict;

#[test]
fn every_geometric_claim_of_the_catalogue_is_confirmed() {
    let mut failures = Vec::new();
    for r in &super::common::suite().cases {
        for (what, verdict, reason) in [
            ("energy", r.energy.verdict, &r.energy.reason),
            ("symplectic", r.symplectic.verdict, &r.symplectic.reason),
            ("reverse", r.reverse.verdict, &r.reverse.reason),
        ] {
            if verdict != Verdict::Pass {
                failures.push(format!(
                    "{} on {} {what}: {reason}",
                    r.order.scheme, r.order.scene
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn explicit_euler_drifts_on_both_scenes() {
    let a = energy_drift(&Euler, &Harmonic::default(), &EnergySpec::default()).unwrap();
    let b = energy_drift(&Euler, &KeplerCircular, &EnergySpec::default()).unwrap();
    assert_eq!(a.class, Some(EnergyClass::Drifting), "{}", a.reason);
    assert_eq!(b.class, Some(EnergyClass::Drifting), "{}", b.reason);
}

/// On `x'' = -w^2 x` any one-step map `M = [[a, b], [c, d]]` with det 1 keeps
/// `Q(u) = u^T J M u` (`J = [[0, 1], [-1, 0]]`) exactly, because
/// `M^T J M = J`; written out, `-Q = -c x^2 + (a - d) x v + b v^2`.
/// Velocity Verlet: `a = d = 1 - z^2/2`, `b = h`, `c = -h w^2 (1 - z^2/4)`,
/// so it keeps `v^2/2 + w^2 x^2 (1 - z^2/4)/2`. Euler-Cromer (kick, then
/// drift): `a = 1 - z^2`, `b = h`, `c = -h w^2`, `d = 1`, so it keeps
/// `v^2/2 + w^2 x^2/2 - h w^2 x v/2`. (`z = h w`.)
#[test]
fn verlet_and_euler_cromer_conserve_their_modified_energies_exactly() {
    let (w, h) = (1.3, 0.05);
    let osc = Harmonic::new(w, 0.7, -0.4).unwrap();
    let z = h * w;
    let vv =
        |s: &State<1>| 0.5 * s.v[0].powi(2) + 0.5 * w * w * s.q[0].powi(2) * (1.0 - z * z / 4.0);
    let ec = |s: &State<1>| {
        0.5 * s.v[0].powi(2) + 0.5 * w * w * s.q[0].powi(2) - 0.5 * h * w * w * s.q[0] * s.v[0]
    };
    for (scheme_is_vv, modified, true_swing) in [
        (true, &vv as &dyn Fn(&State<1>) -> f64, z * z / 4.0),
        (false, &ec, z),
    ] {
        let (mut m_min, mut m_max, mut e_min, mut e_max) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        let mut track = |s: &State<1>| {
            let (m, e) = (modified(s), osc.energy(s));
            m_min = m_min.min(m);
            m_max = m_max.max(m);
            e_min = e_min.min(e);
            e_max = e_max.max(e);
        };
        let s0 = osc.initial();
        if scheme_is_vv {
            integrate(&VELOCITY_VERLET, &osc, &s0, h, 100_000, |_, _, s| track(s));
        } else {
            integrate(&EULER_CROMER, &osc, &s0, h, 100_000, |_, _, s| track(s));
        }
        let e0 = osc.energy(&s0);
        assert!(
            (m_max - m_min) / e0 < 1e-12,
            "modified energy moved by {}",
            (m_max - m_min) / e0
        );
        // meanwhile the true energy swings by a fraction of order z^2/4 (Verlet) or z (Euler-Cromer)
        let swing = (e_max - e_min) / e0;
        assert!(
            swing > 0.2 * true_swing && swing < 5.0 * true_swing,
            "swing {swing} vs {true_swing}"
        );
    }
}

/// Explicit Euler on the oscillator: `M = [[1, h], [-h w^2, 1]]`,
/// `det M = 1 + (h w)^2`, whatever the state.
#[test]
fn euler_symplectic_defect_is_its_analytic_value() {
    for w in [0.5, 1.0, 7.0] {
        let osc = Harmonic::new(w, 1.0, 0.3).unwrap();
        for z in [0.01, 0.1, 0.5] {
            let j = step_jacobian(&Euler, &osc, &osc.initial(), z / w).unwrap();
            let defect = j.determinant() - 1.0;
            assert!(
                (defect - z * z).abs() <= 1e-14 * (1.0 + z * z),
                "w = {w}, z = {z}: {defect}"
            );
        }
    }
}

/// RK4 on the oscillator multiplies by `R(iz) = 1 - z^2/2 + z^4/24 + i(z - z^3/6)`
/// in the rotating basis, so `det J = |R(iz)|^2 = 1 - z^6/72 + z^8/576`
/// exactly: the `z^2` and `z^4` terms cancel (1/4 + 1/12 - 1/3 = 0).
#[test]
fn rk4_symplectic_defect_is_its_analytic_value() {
    for w in [0.5, 3.0] {
        let osc = Harmonic::new(w, 1.0, -0.2).unwrap();
        for z in [0.05, 0.3, 1.0, 2.0] {
            let j = step_jacobian(&Rk4, &osc, &osc.initial(), z / w).unwrap();
            let expected = -z.powi(6) / 72.0 + z.powi(8) / 576.0;
            let defect = j.determinant() - 1.0;
            assert!(
                (defect - expected).abs() <= 1e-14,
                "w = {w}, z = {z}: {defect} vs {expected}"
            );
        }
    }
}

/// Euler-Cromer, but its metadata claims time symmetry; explicit Euler, but
/// claiming symplecticity: both lies must be caught.
#[test]
fn metadata_that_claims_too_much_is_refuted() {
    const SYMMETRIC_EC: SplittingTable = SplittingTable::new(
        SchemeMeta {
            id: "symmetric-claiming-ec",
            symmetric: true,
            ..EULER_CROMER.meta
        },
        Flow::Kick,
        &[1.0],
        &[1.0],
    );
    let r = reversibility(&SYMMETRIC_EC, &KeplerCircular, &ReverseSpec::default()).unwrap();
    assert_eq!(r.verdict, Verdict::Fail, "{}", r.reason);
    assert!(!r.measured);

    let s = symplecticity(
        &SymplecticEuler,
        &Harmonic::default(),
        &SymplecticSpec::default(),
    )
    .unwrap();
    assert_eq!(s.verdict, Verdict::Fail, "{}", s.reason);
    let e = energy_drift(
        &SymplecticEuler,
        &Harmonic::default(),
        &EnergySpec::default(),
    )
    .unwrap();
    assert_eq!(e.verdict, Verdict::Fail, "{}", e.reason);
}

/// Explicit Euler under a false claim of symplecticity.
struct SymplecticEuler;
const LYING_META: SchemeMeta = SchemeMeta {
    id: "symplectic-claiming-euler",
    symplectic: true,
    ..Euler::META
};
impl stepladder::scheme::Scheme for SymplecticEuler {
    type Carry<R: Real, const D: usize> = State<D, R>;
    fn meta(&self) -> &SchemeMeta {
        &LYING_META
    }
    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &State<D, R>,
        h: R,
    ) -> State<D, R> {
        Euler.start(scene, s, h)
    }
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &mut State<D, R>,
        h: R,
    ) -> Result<(), stepladder::scheme::StepFailure> {
        Euler.step(scene, s, h)
    }
    fn state<R: Real, const D: usize>(&self, s: &State<D, R>, h: R) -> State<D, R> {
        Euler.state(s, h)
    }
}

/// The oscillator with one thing wrong, to show the scene check catches it.
#[derive(Clone, Copy)]
struct Flawed {
    potential_factor: f64,
    frequency_factor: f64,
}

impl Scene<1> for Flawed {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "flawed",
            ..Harmonic::default().meta()
        }
    }
    fn initial(&self) -> State<1> {
        State::new(Vector1::new(1.0), Vector1::new(0.0))
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, 1>) -> SVector<R, 1> {
        -q
    }
    fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
        R::of(0.5 * self.potential_factor) * q[0] * q[0]
    }
    fn period(&self) -> f64 {
        std::f64::consts::TAU
    }
    fn exact(&self, t: f64) -> Option<State<1>> {
        let w = self.frequency_factor;
        Some(State::new(
            Vector1::new((w * t).cos()),
            Vector1::new(-w * (w * t).sin()),
        ))
    }
}

#[test]
fn a_wrong_potential_or_exact_solution_fails_the_scene_check() {
    let good = check_scene(&Flawed {
        potential_factor: 1.0,
        frequency_factor: 1.0,
    });
    assert_eq!(good.verdict, Verdict::Pass, "{good:?}");
    let wrong_potential = check_scene(&Flawed {
        potential_factor: 1.01,
        frequency_factor: 1.0,
    });
    assert_eq!(wrong_potential.verdict, Verdict::Fail);
    assert!(wrong_potential.force_residual > 1e-3);
    let wrong_solution = check_scene(&Flawed {
        potential_factor: 1.0,
        frequency_factor: 1.01,
    });
    assert_eq!(wrong_solution.verdict, Verdict::Fail);
    assert!(wrong_solution.acceleration_residual.unwrap() > 1e-3);
}

#[test]
fn every_built_in_scene_passes_its_check() {
    for s in stepladder::scene::AnyScene::all() {
        let c = s.visit(Check);
        assert_eq!(c.verdict, Verdict::Pass, "{c:?}");
    }
}

struct Check;
impl stepladder::scene::SceneVisitor for Check {
    type Output = stepladder::internals::accuracy::scene_check::SceneCheck;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        s: &S,
    ) -> Self::Output {
        check_scene(s)
    }
}

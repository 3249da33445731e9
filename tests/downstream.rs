//! A downstream crate guarding its own integrator with stepladder, through
//! the public API alone: the scheme and one scene are defined here, as a user
//! would define them in their own test.

use nalgebra::{SVector, Vector1};
use stepladder::guard;
use stepladder::internals::accuracy::order::{OrderSpec, Reference, global_order};
use stepladder::scene::{Harmonic, KeplerCircular, Scene, SceneMeta};
use stepladder::scheme::{Scheme, SchemeMeta, StepFailure};
use stepladder::state::{Real, State};

/// The user's own velocity Verlet, written out by hand with a flag to plant
/// the classic bug of a full first kick instead of a half one.
struct MyVerlet {
    meta: SchemeMeta,
    first_kick: f64,
}

const MY_META: SchemeMeta = SchemeMeta {
    id: "my-verlet",
    name: "velocity Verlet, hand-written",
    order: 2,
    symplectic: true,
    symmetric: true,
    force_evaluations: 1,
    implicit: false,
    reference: "the user's own code",
    phase_error: None,
};

const GOOD: MyVerlet = MyVerlet {
    meta: MY_META,
    first_kick: 0.5,
};
const BUGGY: MyVerlet = MyVerlet {
    meta: MY_META,
    first_kick: 1.0,
};

/// `(q, v, a(q))`: the acceleration is reused by the next step.
#[derive(Clone, Debug)]
struct Carry<R: Real, const D: usize> {
    q: SVector<R, D>,
    v: SVector<R, D>,
    a: SVector<R, D>,
}

impl Scheme for MyVerlet {
    type Carry<R: Real, const D: usize> = Carry<R, D>;
    fn meta(&self) -> &SchemeMeta {
        &self.meta
    }
    fn start<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        s: &State<D, R>,
        _: R,
    ) -> Carry<R, D> {
        Carry {
            q: s.q,
            v: s.v,
            a: scene.acceleration(&s.q),
        }
    }
    fn step<R: Real, const D: usize, S: Scene<D>>(
        &self,
        scene: &S,
        c: &mut Carry<R, D>,
        h: R,
    ) -> Result<(), StepFailure> {
        c.v += c.a * (h * R::of(self.first_kick));
        c.q += c.v * h;
        c.a = scene.acceleration(&c.q);
        c.v += c.a * (h * R::of(1.0 - self.first_kick));
        Ok(())
    }
    fn state<R: Real, const D: usize>(&self, c: &Carry<R, D>, _: R) -> State<D, R> {
        State::new(c.q, c.v)
    }
}

/// The user's own scene: the plane pendulum `x'' = -sin x`, `V = 1 - cos x`,
/// started at 1 rad. It has no elementary exact solution, so its order is
/// measured from the differences of successive rungs.
#[derive(Clone, Copy)]
struct Pendulum;

impl Scene<1> for Pendulum {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "pendulum",
            name: "plane pendulum",
            dimension: 1,
            parameters: "x0 = 1 rad, v0 = 0".into(),
            reference: "x'' = -sin x",
        }
    }
    fn initial(&self) -> State<1> {
        State::new(Vector1::new(1.0), Vector1::new(0.0))
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, 1>) -> SVector<R, 1> {
        Vector1::new(-q[0].sin())
    }
    fn potential<R: Real>(&self, q: &SVector<R, 1>) -> R {
        R::one() - q[0].cos()
    }
    fn period(&self) -> f64 {
        // the small-oscillation period: only a time scale for the studies
        std::f64::consts::TAU
    }
    fn exact(&self, _: f64) -> Option<State<1>> {
        None
    }
}

#[test]
fn a_correct_integrator_passes_every_guard_on_the_built_in_scenes() {
    guard::assert_claims(&GOOD, &Harmonic::default());
    guard::assert_claims(&GOOD, &KeplerCircular);
}

#[test]
fn an_own_scene_without_an_exact_solution_is_measured_by_successive_rungs() {
    let record = guard::assert_order(&GOOD, &Pendulum);
    assert_eq!(record.reference, Reference::HalfStep);
    assert!(
        (record.measured_order.unwrap() - 2.0).abs() < 0.01,
        "{}",
        record.reason
    );
    guard::assert_symplectic(&GOOD, &Pendulum);
    guard::assert_reversible(&GOOD, &Pendulum);
    guard::assert_energy(&GOOD, &Pendulum);
}

#[test]
fn a_broken_integrator_fails_with_the_figures_that_decided_it() {
    let message = std::panic::catch_unwind(|| guard::assert_order(&BUGGY, &KeplerCircular))
        .expect_err("a full first kick makes velocity Verlet first order")
        .downcast::<String>()
        .expect("a formatted message");
    for figure in [
        "`my-verlet` on `kepler-circular`",
        "order 2 claimed",
        "measured 1.0",
        "over rungs",
        "ladder",
        "h = ",
    ] {
        assert!(message.contains(figure), "{message:?} lacks {figure:?}");
    }
    // the full kick also breaks the time symmetry, though not symplecticity
    assert!(
        std::panic::catch_unwind(|| guard::assert_reversible(&BUGGY, &KeplerCircular)).is_err()
    );
    guard::assert_symplectic(&BUGGY, &KeplerCircular);
}

/// The user pins the record in their own snapshot folder, rounded so it is
/// the same on any machine: a refactor of their integrator that changes the
/// measured order, the window or the verdict fails their CI.
#[test]
fn a_record_can_be_pinned_with_insta() {
    let r = global_order(&GOOD, &Pendulum, &OrderSpec::default()).unwrap();
    let pinned = format!(
        "scheme {} on {}: order {:.2}, window {:?}, verdict {:?}",
        r.scheme,
        r.scene,
        r.measured_order.unwrap(),
        r.window.unwrap(),
        r.verdict
    );
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path("../snapshots");
    settings.set_prepend_module_to_snapshot(false);
    settings.set_omit_expression(true);
    settings.set_description(
        "A downstream user's own record: its measured order (2 decimals), window and verdict.",
    );
    settings.bind(|| insta::assert_snapshot!("downstream_pendulum_order", pinned));
}

//! The catalogue against its own claims, on every built-in scene.

use stepladder::internals::compensated::{any_scheme_ids, paired_ids, variants};
use stepladder::scene::{Counted, Harmonic, KeplerCircular, Scene};
use stepladder::scheme::{
    Flow, POSITION_VERLET, Scheme, SchemeMeta, SchemeVisitor, TABLES, VELOCITY_VERLET, catalogue,
    scheme_ids, visit_scheme,
};

#[test]
fn every_scheme_has_its_claimed_order_on_every_scene() {
    let failures: Vec<String> = super::common::suite()
        .order()
        .into_iter()
        .filter(|r| !r.passed())
        .map(|r| format!("{} on {}: {}", r.scheme, r.scene, r.reason))
        .collect();
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Every id the command line accepts (the catalogue and the compensated
/// variants) names one scheme: ids and names unique, ids in kebab-case, and
/// each variant documents itself rather than inheriting its twin's text.
#[test]
fn registry_ids_are_unique_kebab_case_and_documented() {
    let metas: Vec<&SchemeMeta> = catalogue().into_iter().chain(variants()).collect();
    let ids: Vec<&str> = metas.iter().map(|m| m.id).collect();
    assert_eq!(ids, any_scheme_ids());
    for key in [|m: &SchemeMeta| m.id, |m: &SchemeMeta| m.name] {
        let mut sorted: Vec<&str> = metas.iter().map(|m| key(m)).collect();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), metas.len(), "duplicates in {sorted:?}");
    }
    for m in &metas {
        assert!(
            !m.id.is_empty()
                && m.id.split('-').all(|w| !w.is_empty()
                    && w.chars()
                        .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit())),
            "{} is not kebab-case",
            m.id
        );
        assert!(
            !m.name.is_empty() && !m.reference.is_empty(),
            "{} lacks a name or reference",
            m.id
        );
        assert!(m.order >= 1 && m.force_evaluations >= 1, "{}", m.id);
    }
    for (twin, variant) in paired_ids().into_iter().zip(variants()) {
        let twin = catalogue().into_iter().find(|m| m.id == twin).unwrap();
        assert_ne!(twin.reference, variant.reference, "{}", variant.id);
    }
}

/// Force evaluations spent by `start` alone, by `start` plus `steps` steps,
/// and the evaluations the carry reports for an implicit scheme's solves.
fn evaluations<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: S,
    h: f64,
    steps: u64,
) -> (u64, u64, Option<u64>) {
    let scene = Counted::new(scene);
    let mut carry = scheme.start(&scene, &scene.initial(), h);
    let start = scene.evaluations();
    for _ in 0..steps {
        scheme
            .step(&scene, &mut carry, h)
            .expect("a small step succeeds");
    }
    (
        start,
        scene.evaluations(),
        scheme.solver_evaluations(&carry),
    )
}

/// An explicit scheme spends exactly `force_evaluations` per step. An
/// implicit one spends what its solves need, which varies with the step and
/// the scene: the count is checked against the evaluations the carry
/// reports (never one unaccounted for), and is at least `force_evaluations`
/// per step.
struct CountForces;
impl SchemeVisitor for CountForces {
    type Output = ();
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) {
        let meta = scheme.meta();
        let steps = 1000;
        let per = meta.force_evaluations as u64;
        for (start, total, reported) in [
            evaluations(scheme, Harmonic::default(), 0.01, steps),
            evaluations(scheme, KeplerCircular, 0.01, steps),
        ] {
            assert!(
                start <= 1,
                "{} spends {start} evaluations starting",
                meta.id
            );
            match (meta.implicit, reported) {
                (false, None) => assert_eq!(
                    total - start,
                    steps * per,
                    "{} claims {per} force evaluations per step",
                    meta.id
                ),
                (true, Some(reported)) => {
                    assert_eq!(
                        total - start,
                        reported,
                        "{}: evaluations unaccounted for",
                        meta.id
                    );
                    assert!(
                        reported >= steps * per,
                        "{}: {reported} evaluations",
                        meta.id
                    );
                }
                (implicit, reported) => panic!(
                    "{}: implicit = {implicit} but reports solver evaluations {reported:?}",
                    meta.id
                ),
            }
        }
    }
}

#[test]
fn force_evaluations_per_step_match_the_metadata() {
    for id in scheme_ids() {
        visit_scheme(id, CountForces).unwrap();
    }
}

/// Starting and reading back the state must give the state started from:
/// the synchronised output of a staggered or two-step scheme included.
struct StartIsSynchronised;
impl SchemeVisitor for StartIsSynchronised {
    type Output = ();
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) {
        let scene = KeplerCircular;
        let s0 = scene.initial();
        for h in [0.1, 1e-3] {
            let back = scheme.state(&scheme.start(&scene, &s0, h), h);
            assert!(
                scene.phase_distance(&back, &s0) < 1e-13,
                "{} reads back {back:?} from {s0:?}",
                scheme.meta().id
            );
        }
    }
}

#[test]
fn state_read_back_after_start_is_the_initial_state() {
    for id in scheme_ids() {
        visit_scheme(id, StartIsSynchronised).unwrap();
    }
}

// Weights, symmetry and order conditions of the splitting tables are
// checked in tests/order_conditions.rs.

#[test]
fn velocity_verlet_reuses_its_last_acceleration() {
    assert_eq!(VELOCITY_VERLET.first, Flow::Kick);
    assert!(VELOCITY_VERLET.reuses_acceleration());
    assert!(!POSITION_VERLET.reuses_acceleration());
}

#[test]
fn every_splitting_table_is_in_the_catalogue() {
    let ids = scheme_ids();
    for t in TABLES {
        assert!(ids.contains(&t.meta.id), "{} is not registered", t.meta.id);
    }
}

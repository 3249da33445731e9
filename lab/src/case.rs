//! A case: one catalogue scheme bound to one built-in scene, chosen at run
//! time, with every study available on it. Inside, the scheme and the scene
//! are concrete types, so each study runs fully monomorphised code; the only
//! dynamic dispatch is the one call that starts a study.
//!
//! It lives in the lab, not in the published core: binding every catalogue
//! scheme to every built-in scene instantiates every study for each pair,
//! code a user's test crate would otherwise compile and never call.

use stepladder::error::Error;
use stepladder::internals::compensated::visit_any_scheme;
use stepladder::internals::cost::count::counting_step;
use stepladder::scene::{AnyScene, Hidden, Scene, SceneMeta, SceneVisitor};
use stepladder::scheme::{Scheme, SchemeMeta, SchemeVisitor};
use stepladder::study::{
    EnergyRecord, EnergySpec, EvaluationRecord, OrderRecord, OrderSpec, PinOutcome, ReverseRecord,
    ReverseSpec, SymplecticRecord, SymplecticSpec, check_pin, energy_drift, evaluations,
    global_order, reversibility, symplecticity,
};

/// The studies that can be run on a scheme bound to a scene.
pub trait Case: Send + Sync {
    /// The scheme's claims.
    fn scheme(&self) -> &SchemeMeta;
    /// The scene.
    fn scene(&self) -> SceneMeta;
    /// The global order study.
    fn order(&self, spec: &OrderSpec) -> Result<OrderRecord, Error>;
    /// The global order study with the scene's exact solution withheld
    /// ([`stepladder::scene::Hidden`]): errors against the half-step run.
    fn hidden_order(&self, spec: &OrderSpec) -> Result<OrderRecord, Error>;
    /// The long-run energy study.
    fn energy(&self, spec: &EnergySpec) -> Result<EnergyRecord, Error>;
    /// The tangent-map study.
    fn symplectic(&self, spec: &SymplecticSpec) -> Result<SymplecticRecord, Error>;
    /// The forward-and-back study.
    fn reverse(&self, spec: &ReverseSpec) -> Result<ReverseRecord, Error>;
    /// The force evaluations counted against the claim.
    fn evaluations(&self) -> EvaluationRecord;
    /// The error pin in `dir` ([`stepladder::study::check_pin`]).
    fn pin(&self, dir: &std::path::Path) -> Result<PinOutcome, String>;
}

/// A scheme and a `D`-dimensional scene of concrete types.
#[derive(Clone, Debug)]
pub struct Bound<M: 'static, S, const D: usize> {
    /// The scheme.
    pub scheme: &'static M,
    /// The scene.
    pub scene: S,
}

impl<M, S, const D: usize> Case for Bound<M, S, D>
where
    M: Scheme + Sync + 'static,
    S: Scene<D> + Send + Sync,
{
    fn scheme(&self) -> &SchemeMeta {
        self.scheme.meta()
    }
    fn scene(&self) -> SceneMeta {
        self.scene.meta()
    }
    fn order(&self, spec: &OrderSpec) -> Result<OrderRecord, Error> {
        global_order(self.scheme, &self.scene, spec)
    }
    fn hidden_order(&self, spec: &OrderSpec) -> Result<OrderRecord, Error> {
        global_order(self.scheme, &Hidden(&self.scene), spec)
    }
    fn energy(&self, spec: &EnergySpec) -> Result<EnergyRecord, Error> {
        energy_drift(self.scheme, &self.scene, spec)
    }
    fn symplectic(&self, spec: &SymplecticSpec) -> Result<SymplecticRecord, Error> {
        symplecticity(self.scheme, &self.scene, spec)
    }
    fn reverse(&self, spec: &ReverseSpec) -> Result<ReverseRecord, Error> {
        reversibility(self.scheme, &self.scene, spec)
    }
    fn evaluations(&self) -> EvaluationRecord {
        evaluations(self.scheme, &self.scene, counting_step(&self.scene))
    }
    fn pin(&self, dir: &std::path::Path) -> Result<PinOutcome, String> {
        check_pin(self.scheme, &self.scene, dir)
    }
}

/// Binds the catalogue scheme (or compensated variant) `scheme_id` to `scene`.
///
/// ```
/// use stepladder_lab::case::case;
/// use stepladder::scene::AnyScene;
/// let c = case("leapfrog", &AnyScene::parse("kepler-circular").unwrap()).unwrap();
/// assert_eq!(c.scheme().order, 2);
/// assert!(case("rk9", &AnyScene::parse("harmonic").unwrap()).is_err());
/// ```
pub fn case(scheme_id: &str, scene: &AnyScene) -> Result<Box<dyn Case>, Error> {
    visit_any_scheme(scheme_id, BindScheme(scene))
}

struct BindScheme<'a>(&'a AnyScene);

impl SchemeVisitor for BindScheme<'_> {
    type Output = Box<dyn Case>;
    fn visit<M: Scheme + Sync + 'static>(self, scheme: &'static M) -> Box<dyn Case> {
        self.0.visit(BindScene(scheme))
    }
}

struct BindScene<M: 'static>(&'static M);

impl<M: Scheme + Sync + 'static> SceneVisitor for BindScene<M> {
    type Output = Box<dyn Case>;
    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> Box<dyn Case> {
        Box::new(Bound::<M, S, D> {
            scheme: self.0,
            scene: scene.clone(),
        })
    }
}

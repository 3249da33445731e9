//! The N-body scenes against published data, and the order study's
//! error estimate against a published truth.
//!
//! The Pleiades have no exact solution, so the order study measures each
//! rung against the same scheme at half the step. Their published state at
//! `t = 3` (IVP test set, problem PLEI) is an independent truth: it tests the
//! scene (masses, units, mass-weighting, the published tables) and the
//! harness's estimate of the error it never sees.

use stepladder::internals::accuracy::order::{OrderRecord, OrderSpec, global_order};
use stepladder::internals::accuracy::scene_check::check_scene;
use stepladder::internals::run::integrate;
use stepladder::internals::tolerance::SCENE_TOLERANCE;
use stepladder::nalgebra::SVector;
use stepladder::scene::{Invariant, OuterSolarSystem, Pleiades, Scene, SceneMeta};
use stepladder::scheme::{KAHAN_LI8, Rk4, Scheme, VELOCITY_VERLET, YOSHIDA6};
use stepladder::state::{Real, State};
use stepladder::study::Verdict;
use stepladder_lab::suite::race::KAHAN_LI8_COMPENSATED;
use stepladder_lab::suite::race::{
    RACE_TARGETS, REFERENCE_SHARE, pleiades_published_accuracy, pleiades_quadruple_precision,
};

/// The unit round-off of f64.
const U: f64 = f64::EPSILON / 2.0;

/// What the tests need to know of an N-body scene besides [`Scene`].
trait Bodies<const D: usize>: Scene<D> {
    /// Coordinates per body.
    const K: usize;
    const G: f64;
    const MASSES: &'static [f64];
    fn to_physical(&self, s: &State<D>) -> State<D>;
    fn to_mass_weighted(&self, s: &State<D>) -> State<D>;
    /// Physical positions and velocities at `t = 0`, body after body.
    fn published_start(&self) -> State<D>;
}

impl Bodies<14> for Pleiades {
    const K: usize = 2;
    const G: f64 = Pleiades::G;
    const MASSES: &'static [f64] = &Pleiades::MASSES;
    fn to_physical(&self, s: &State<14>) -> State<14> {
        self.physical(s)
    }
    fn to_mass_weighted(&self, s: &State<14>) -> State<14> {
        self.mass_weighted(s)
    }
    fn published_start(&self) -> State<14> {
        flatten(&Pleiades::POSITIONS, &Pleiades::VELOCITIES)
    }
}

impl Bodies<18> for OuterSolarSystem {
    const K: usize = 3;
    const G: f64 = OuterSolarSystem::G;
    const MASSES: &'static [f64] = &OuterSolarSystem::MASSES;
    fn to_physical(&self, s: &State<18>) -> State<18> {
        self.physical(s)
    }
    fn to_mass_weighted(&self, s: &State<18>) -> State<18> {
        self.mass_weighted(s)
    }
    fn published_start(&self) -> State<18> {
        flatten(&OuterSolarSystem::POSITIONS, &OuterSolarSystem::VELOCITIES)
    }
}

/// A state from per-body tables.
fn flatten<const K: usize, const N: usize, const D: usize>(
    q: &[[f64; K]; N],
    v: &[[f64; K]; N],
) -> State<D> {
    State::new(
        SVector::from_fn(|n, _| q[n / K][n % K]),
        SVector::from_fn(|n, _| v[n / K][n % K]),
    )
}

/// Body `i`'s `K` coordinates of `x`.
fn body<const D: usize>(x: &SVector<f64, D>, k: usize, i: usize) -> Vec<f64> {
    (0..k).map(|c| x[k * i + c]).collect()
}

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|c| c * c).sum::<f64>().sqrt()
}

/// The state at `t_end` after `steps` steps.
fn last_state<M: Scheme, S: Scene<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    t_end: f64,
    steps: u64,
) -> State<D> {
    let mut last = scene.initial();
    let outcome = integrate(
        scheme,
        scene,
        &scene.initial(),
        t_end / steps as f64,
        steps,
        |_, _, s| last = *s,
    );
    assert!(outcome.completed(), "{outcome}");
    last
}

/// The quadruple-precision state at `t = 3` (see
/// [`stepladder_lab::suite::race::PLEIADES_QUADRUPLE_PRECISION`]) as a
/// mass-weighted state.
fn quadruple_precision_end(stars: &Pleiades) -> State<14> {
    pleiades_quadruple_precision(stars)
}

/// An upper bound on the published state's own error, which every true
/// error measured against it carries (see
/// [`stepladder_lab::suite::race::pleiades_published_accuracy`]).
fn published_accuracy(stars: &Pleiades) -> f64 {
    pleiades_published_accuracy(stars)
}

// ---------------------------------------------------------------------------
// The scenes are conservative only in mass-weighted coordinates.

#[test]
fn both_scenes_pass_the_scene_check() {
    let stars = check_scene(&Pleiades::default());
    assert_eq!(stars.verdict, Verdict::Pass, "{stars:?}");
    let planets = check_scene(&OuterSolarSystem::default());
    assert_eq!(planets.verdict, Verdict::Pass, "{planets:?}");
    for r in [stars, planets] {
        assert!(r.force_residual <= SCENE_TOLERANCE && r.curl_residual <= SCENE_TOLERANCE);
    }
}

/// The Pleiades written in physical coordinates, `r_i'' = sum_j m_j (r_j -
/// r_i) / r^3` with the potential `-sum m_i m_j / r`: the correct equations
/// of motion, but not a scene, since the force on body `i` is `-grad_i V /
/// m_i`.
#[derive(Clone, Copy, Debug)]
struct PhysicalPleiades;

impl Scene<14> for PhysicalPleiades {
    fn meta(&self) -> SceneMeta {
        SceneMeta {
            id: "pleiades-physical",
            name: "Pleiades in physical coordinates",
            dimension: 14,
            parameters: String::new(),
            reference: "",
        }
    }
    fn initial(&self) -> State<14> {
        Pleiades::default().published_start()
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, 14>) -> SVector<R, 14> {
        let mut a = SVector::<R, 14>::zeros();
        for i in 0..7 {
            for j in 0..7 {
                if i != j {
                    let (dx, dy) = (q[2 * j] - q[2 * i], q[2 * j + 1] - q[2 * i + 1]);
                    let r2 = dx * dx + dy * dy;
                    let pull = R::of(Pleiades::MASSES[j]) / (r2 * r2.sqrt());
                    a[2 * i] += dx * pull;
                    a[2 * i + 1] += dy * pull;
                }
            }
        }
        a
    }
    fn potential<R: Real>(&self, q: &SVector<R, 14>) -> R {
        let mut v = R::zero();
        for i in 0..7 {
            for j in i + 1..7 {
                let (dx, dy) = (q[2 * j] - q[2 * i], q[2 * j + 1] - q[2 * i + 1]);
                v -= R::of(Pleiades::MASSES[i] * Pleiades::MASSES[j]) / (dx * dx + dy * dy).sqrt();
            }
        }
        v
    }
    fn period(&self) -> f64 {
        Pleiades::default().period()
    }
    fn exact(&self, _: f64) -> Option<State<14>> {
        None
    }
}

/// In physical coordinates `a + grad V` is `(1 - m_i) a_i` on body `i`, of
/// the size of the force itself, and `da_i/dr_j = m_j (...)` against
/// `da_j/dr_i = m_i (...)` is not symmetric: the check must refuse both.
#[test]
fn the_same_stars_in_physical_coordinates_fail_the_scene_check() {
    let r = check_scene(&PhysicalPleiades);
    assert_eq!(r.verdict, Verdict::Fail, "{r:?}");
    assert!(r.force_residual > 0.1 && r.curl_residual > 0.1, "{r:?}");
}

// ---------------------------------------------------------------------------
// The conversions carry the published data, and the invariants are physical.

/// The physical energy, momentum and angular momentum of a physical state,
/// computed directly: `sum m v^2 / 2 - sum G m_i m_j / r`, `sum m v`, `sum m r
/// x v`.
fn physical_invariants<S: Bodies<D>, const D: usize>(s: &State<D>) -> (f64, Vec<f64>, Vec<f64>) {
    let (k, m) = (S::K, S::MASSES);
    let n = m.len();
    let mut energy = 0.0;
    let mut momentum = vec![0.0; k];
    let mut angular = vec![0.0; 3];
    for i in 0..n {
        let (r, v) = (body(&s.q, k, i), body(&s.v, k, i));
        energy += 0.5 * m[i] * norm(&v).powi(2);
        for c in 0..k {
            momentum[c] += m[i] * v[c];
        }
        let (r3, v3) = (pad(&r), pad(&v));
        for (c, l) in angular.iter_mut().enumerate() {
            let (a, b) = ((c + 1) % 3, (c + 2) % 3);
            *l += m[i] * (r3[a] * v3[b] - r3[b] * v3[a]);
        }
        for j in i + 1..n {
            let d: Vec<f64> = (0..k).map(|c| r[c] - s.q[k * j + c]).collect();
            energy -= S::G * m[i] * m[j] / norm(&d);
        }
    }
    (energy, momentum, angular)
}

fn pad(x: &[f64]) -> [f64; 3] {
    [x[0], x[1], x.get(2).copied().unwrap_or(0.0)]
}

/// The scene's energy, momenta and angular momenta at its start are the
/// physical ones of the published data, which the conversions carry to a
/// unit of round-off.
fn check_conversions<S: Bodies<D>, const D: usize>(scene: &S) {
    let published = scene.published_start();
    let start = scene.initial();
    let back = scene.to_physical(&start);
    // x sqrt(m) / sqrt(m): two roundings of half an ulp each
    for (a, b) in back
        .q
        .iter()
        .chain(&back.v)
        .zip(published.q.iter().chain(&published.v))
    {
        assert!((a - b).abs() <= 2.0 * U * b.abs(), "{a} against {b}");
    }
    let again = scene.to_mass_weighted(&back);
    assert!(scene.phase_distance(&again, &start) <= 4.0 * U * scene.scale());

    let (energy, momentum, angular) = physical_invariants::<S, D>(&published);
    // every quantity is a sum of at most n^2 / 2 terms of a few roundings
    // each, on inputs carried to 2 ulps: 4 n^2 u of the terms' magnitudes
    let n = S::MASSES.len() as f64;
    let slack = |terms: f64| 4.0 * n * n * U * terms;
    let kinetic = 0.5 * start.v.norm_squared();
    let potential = -scene.potential(&start.q);
    let e = scene.invariant(Invariant::Energy, &start).unwrap().value;
    assert!(
        (e - energy).abs() <= slack(kinetic + potential),
        "energy {e} against {energy}"
    );
    let weights = S::MASSES.iter().map(|m| m.sqrt());
    let momentum_terms: f64 = weights
        .enumerate()
        .map(|(i, w)| w * norm(&body(&start.v, S::K, i)))
        .sum();
    for (axis, p) in momentum.iter().enumerate() {
        let which = Invariant::Momentum { axis: axis as u8 };
        let value = scene.invariant(which, &start).unwrap().value;
        assert!(
            (value - p).abs() <= slack(momentum_terms),
            "{which:?}: {value} against {p}"
        );
    }
    let angular_terms: f64 = (0..S::MASSES.len())
        .map(|i| norm(&body(&start.q, S::K, i)) * norm(&body(&start.v, S::K, i)))
        .sum();
    for axis in 0..3u8 {
        let which = Invariant::AngularMomentum { axis };
        if let Some(l) = scene.invariant(which, &start) {
            let expected = angular[axis as usize];
            assert!(
                (l.value - expected).abs() <= slack(angular_terms),
                "{which:?}: {} against {expected}",
                l.value
            );
        }
    }
    // every declared invariant has a value, nothing else does
    for which in all_invariants() {
        let declared = scene.invariants().contains(&which);
        assert_eq!(
            scene.invariant(which, &start).is_some(),
            declared,
            "{which:?}"
        );
    }
}

fn all_invariants() -> Vec<Invariant> {
    let mut all = vec![Invariant::Energy];
    for axis in 0..4 {
        all.push(Invariant::Momentum { axis });
        all.push(Invariant::AngularMomentum { axis });
    }
    all
}

#[test]
fn published_data_enter_through_the_conversions_and_the_invariants_are_physical() {
    let stars = Pleiades::default();
    check_conversions(&stars);
    assert_eq!(
        stars.invariants(),
        &[
            Invariant::Energy,
            Invariant::Momentum { axis: 0 },
            Invariant::Momentum { axis: 1 },
            Invariant::AngularMomentum { axis: 2 }
        ]
    );
    let planets = OuterSolarSystem::default();
    check_conversions(&planets);
    assert_eq!(planets.invariants().len(), 7);
}

// ---------------------------------------------------------------------------
// Velocity Verlet conserves the momenta to round-off.

/// `F_i(Q) = sqrt(m_i) sum_(j != i) G m_j / |r_i - r_j|^2`: the sum of the
/// magnitudes of the pair terms of body `i`'s mass-weighted acceleration.
fn pair_magnitudes<S: Bodies<D>, const D: usize>(scene: &S, q: &SVector<f64, D>) -> Vec<f64> {
    let r = scene.to_physical(&State::new(*q, SVector::zeros())).q;
    let (k, m) = (S::K, S::MASSES);
    (0..m.len())
        .map(|i| {
            let sum: f64 = (0..m.len())
                .filter(|&j| j != i)
                .map(|j| {
                    let d: Vec<f64> = (0..k).map(|c| r[k * i + c] - r[k * j + c]).collect();
                    S::G * m[j] / norm(&d).powi(2)
                })
                .sum();
            m[i].sqrt() * sum
        })
        .collect()
}

/// The largest drift of any momentum and angular-momentum component over a
/// velocity-Verlet run (or another scheme's), and the round-off bound that
/// velocity Verlet's drift must stay within.
///
/// A step `V+ = V + h/2 A(Q)`, `Q' = Q + h V+`, `V' = V+ + h/2 A(Q')`
/// conserves `P = sum sqrt(m_i) V_i` and `L = sum Q_i x V_i` exactly in exact
/// arithmetic: the pair forces cancel in `sum sqrt(m_i) A_i = sum m_i a_i`
/// and are central in `sum Q_i x A_i = sum m_i r_i x a_i`, and a drift adds
/// `h V x V = 0`. In floating point (`u = eps / 2`, each operation good to
/// `u`):
/// - each kick rounds `V` to `u |V_new|`;
/// - each computed `A_i` is off by at most `gamma F_i` with `gamma = (n + 6)
///   u`: `n - 1` accumulations and the two products of each pair term, the
///   scaling by `sqrt(m_i)`, the product with `h c` (and `h c`'s own
///   rounding), and `sqrt(m_i)^2 != m_i` (two more), where `F_i` is the sum
///   of its pair terms' magnitudes (`pair_magnitudes`); for `L` the pair
///   vector's own rounding adds three more units, `gamma_L = (n + 9) u`;
/// - the drift rounds `Q` to `2 u (|Q| + |Q'|)`, which moves `L` by that
///   times `|V+|`;
/// - evaluating `P` and `L` costs `(n + 2) u` of their terms' magnitudes, at
///   the start and at the end.
///
/// Added up over every step as a worst case (every rounding in the same
/// direction), with `|V+| <= |V| + h/2 F` and the forces evaluated at the
/// observed positions (velocity Verlet evaluates them nowhere else).
fn momentum_drift<M: Scheme, S: Bodies<D>, const D: usize>(
    scheme: &M,
    scene: &S,
    t_end: f64,
    steps: u64,
) -> (f64, f64, f64, f64) {
    let (k, m) = (S::K, S::MASSES);
    let n = m.len();
    let h = t_end / steps as f64;
    let (gamma, gamma_l) = ((n as f64 + 6.0) * U, (n as f64 + 9.0) * U);
    let start = scene.initial();
    let momenta: Vec<Invariant> = scene
        .invariants()
        .iter()
        .copied()
        .filter(|i| *i != Invariant::Energy)
        .collect();
    let value = |which: Invariant, s: &State<D>| scene.invariant(which, s).unwrap().value;
    let initial: Vec<f64> = momenta.iter().map(|&i| value(i, &start)).collect();
    let evaluation = |s: &State<D>| {
        let (mut p, mut l) = (0.0, 0.0);
        for (i, mi) in m.iter().enumerate() {
            let (q, v) = (norm(&body(&s.q, k, i)), norm(&body(&s.v, k, i)));
            p += mi.sqrt() * v;
            l += 2.0 * q * v;
        }
        ((n as f64 + 2.0) * U * p, (n as f64 + 2.0) * U * l)
    };
    let (p0, l0) = evaluation(&start);
    let (mut bound_p, mut bound_l) = (p0, l0);
    let (mut drift_p, mut drift_l) = (0.0f64, 0.0f64);
    let mut previous = start;
    let mut forces = pair_magnitudes(scene, &start.q);
    let outcome = integrate(scheme, scene, &start, h, steps, |step, _, s| {
        if step == 0 {
            return;
        }
        let next_forces = pair_magnitudes(scene, &s.q);
        for i in 0..n {
            let (q0, q1) = (norm(&body(&previous.q, k, i)), norm(&body(&s.q, k, i)));
            let (v0, v1) = (norm(&body(&previous.v, k, i)), norm(&body(&s.v, k, i)));
            let (f0, f1) = (forces[i], next_forces[i]);
            let half = v0 + 0.5 * h * f0;
            bound_p += m[i].sqrt() * (U * (half + v1) + gamma * 0.5 * h * (f0 + f1));
            bound_l += U * (q0 * half + q1 * v1)
                + 2.0 * U * (q0 + q1) * half
                + gamma_l * 0.5 * h * (q0 * f0 + q1 * f1);
        }
        for (which, first) in momenta.iter().zip(&initial) {
            let change = (value(*which, s) - first).abs();
            match which {
                Invariant::Momentum { .. } => drift_p = drift_p.max(change),
                _ => drift_l = drift_l.max(change),
            }
        }
        (previous, forces) = (*s, next_forces);
    });
    assert!(outcome.completed(), "{outcome}");
    let (p1, l1) = evaluation(&previous);
    (drift_p, bound_p + p1, drift_l, bound_l + l1)
}

#[test]
fn velocity_verlet_conserves_both_momenta_to_round_off() {
    // the Pleiades over the published interval, Verlet's error there 0.05
    // of the orbit; the planets over the default end time, 400 steps a
    // Jupiter period
    let stars = Pleiades::default();
    let (dp, bp, dl, bl) = momentum_drift(&VELOCITY_VERLET, &stars, 3.0, 30_000);
    eprintln!("Pleiades: P drift {dp:e} (bound {bp:e}), L drift {dl:e} (bound {bl:e})");
    assert!(
        dp <= bp && dl <= bl,
        "Pleiades: P {dp:e} > {bp:e} or L {dl:e} > {bl:e}"
    );
    let planets = OuterSolarSystem::default();
    let t_end = planets.default_t_end();
    let steps = (400.0 * t_end / planets.period()).round() as u64;
    let (dp, bp, dl, bl) = momentum_drift(&VELOCITY_VERLET, &planets, t_end, steps);
    eprintln!("planets: P drift {dp:e} (bound {bp:e}), L drift {dl:e} (bound {bl:e})");
    assert!(
        dp <= bp && dl <= bl,
        "planets: P {dp:e} > {bp:e} or L {dl:e} > {bl:e}"
    );

    // The bound can tell conservation from its absence: RK4 keeps the
    // linear momentum (every Runge-Kutta method keeps linear invariants)
    // but not the quadratic angular momentum, which its local errors,
    // O(h^5) a step, change by O(h^4) over the run; at 6,000 steps, where
    // its global error is a few percent of the orbit, that is far above
    // what round-off could do to a conserving scheme.
    let (_, _, dl, bl) = momentum_drift(&Rk4, &stars, 3.0, 6_000);
    eprintln!("RK4, 6000 steps: L drift {dl:e}, Verlet's round-off bound {bl:e}");
    assert!(dl > bl, "RK4's angular momentum drift {dl:e} within {bl:e}");
}

// ---------------------------------------------------------------------------
// The published end state.

/// The published state is reproduced by an eighth-order composition to
/// better than the `1e-11` a component that Hairer, Nørsett and Wanner's
/// eighth-order composition reaches at 30,000 to 120,000 steps. With
/// compensated sums the round-off of 60,000 steps stays below that; the
/// truncation error there is `256^-1` of the 30,000-step run's, itself some
/// `1e-13` (the order study's final-time differences fall from `1e-10` at
/// 15,000 steps by `2^8` a halving). A wrong mass, constant or table entry
/// would miss by its own size.
#[test]
fn an_eighth_order_composition_reproduces_the_published_state() {
    let stars = Pleiades::default();
    let end = last_state(
        &KAHAN_LI8_COMPENSATED,
        &stars,
        Pleiades::PUBLISHED_TIME,
        60_000,
    );
    let (ours, published) = (stars.physical(&end), stars.physical(&stars.published_end()));
    let worst = (ours.q - published.q)
        .amax()
        .max((ours.v - published.v).amax());
    assert!(worst <= 1e-11, "largest component difference {worst:e}");
    // the agreement measures the run only if the published state is itself
    // closer to the solution: a quadruple-precision integration says it is
    let quad = stars.physical(&quadruple_precision_end(&stars));
    let off = (quad.q - published.q)
        .amax()
        .max((quad.v - published.v).amax());
    assert!(
        off < worst,
        "published against quadruple precision: {off:e}, our run {worst:e}"
    );
}

/// Why no plain f64 run reaches the smallest race target the published
/// Pleiades state resolves (1e-12): the round-off of the state updates.
/// Kahan and Li's composition at `2^15` steps is some `2^8` times more
/// accurate than at `2^14` (order eight), where its compensated run is
/// already near `1e-11`, so truncation alone is far below the target. With
/// compensated sums its distance to the published state, plus that state's
/// own error, is then below the target; without them the same steps end
/// farther than the target plus that error, and doubling the steps again
/// does not even halve the distance: the plain sums' round-off, not
/// truncation, sets it.
#[test]
fn compensated_sums_take_the_composition_below_the_smallest_judged_race_target_on_the_pleiades() {
    let stars = Pleiades::default();
    let published = stars.published_end();
    let accuracy = published_accuracy(&stars);
    let target = RACE_TARGETS
        .iter()
        .copied()
        .filter(|&t| accuracy <= REFERENCE_SHARE * t)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(target, 1e-12);
    let steps = 1 << 15;
    let distance =
        |scheme: &dyn Fn(u64) -> State<14>, n: u64| stars.phase_distance(&scheme(n), &published);
    let compensated = distance(
        &|n| last_state(&KAHAN_LI8_COMPENSATED, &stars, Pleiades::PUBLISHED_TIME, n),
        steps,
    );
    let plain = |n| {
        distance(
            &|n| last_state(&KAHAN_LI8, &stars, Pleiades::PUBLISHED_TIME, n),
            n,
        )
    };
    let (plain_n, plain_2n) = (plain(steps), plain(2 * steps));
    let shown = format!(
        "compensated {compensated:e}, plain {plain_n:e} then {plain_2n:e}, published state within {accuracy:e}"
    );
    assert!(compensated + accuracy <= target, "{shown}");
    assert!(plain_n - accuracy > target, "{shown}");
    assert!(plain_2n >= 0.5 * plain_n, "{shown}");
}

// ---------------------------------------------------------------------------
// The harness's error estimate against the truth.

/// One rung of an order study's window: the successive-rung estimate of its
/// final-time error against the true one.
#[derive(Debug)]
struct Comparison {
    h: f64,
    /// Final-time distance to the half step, `|y_h(T) - y_(h/2)(T)|`.
    difference: f64,
    /// `difference / (1 - 2^-p)`, `p` the claimed order.
    estimate: f64,
    /// Distance of `y_h(T)` from the published state.
    truth: f64,
    /// The interval `truth / estimate` must lie in.
    allowed: [f64; 2],
    /// The allowed interval is set by the order's interval rather than by
    /// round-off and the published state's accuracy.
    sharp: bool,
}

impl Comparison {
    fn ratio(&self) -> f64 {
        self.truth / self.estimate
    }
    fn holds(&self) -> bool {
        (self.allowed[0]..=self.allowed[1]).contains(&self.ratio())
    }
}

/// Runs the order study over the published interval and compares, on every
/// rung of its window, the final-time estimate with the distance to `truth`.
///
/// Why they must agree: in the window the error is `E_h = C h^p (1 + ...)`.
/// If the error falls by `r = 2^-p'` from `h` to `h/2`, the leading terms are
/// parallel and the difference is `d = |E_h - E_(h/2)| = (1 - r) |E_h|`, so
/// `|E_h| = d / (1 - 2^-p')`. The fitted interval `[lo, hi]` bounds `p'`, so
/// `d / (1 - 2^-hi) <= |E_h| <= d / (1 - 2^-lo)`; against the estimate `d /
/// (1 - 2^-p)` that is a factor within `[(1 - 2^-p) / (1 - 2^-hi), (1 -
/// 2^-p) / (1 - 2^-lo)]` (0.998 to 1.002 for a sixth-order scheme fitted to
/// within 0.17, a three-thousandth either side for second order to within
/// 0.01). Two additive terms widen it: round-off, which the rung's
/// round-off bound covers for the difference (both runs) and for the run
/// itself, and the published state's own error (`published_accuracy`).
/// The claimed `p` scales the estimate and the allowed factor alike: what is
/// tested is the recorded difference and the fitted interval; that `p` lies
/// in the interval is the verdict's part (`record.passed()`).
fn estimate_against_truth<M: Scheme, S: Scene<14>>(
    scheme: &M,
    scene: &S,
    truth: &State<14>,
    truth_accuracy: f64,
) -> (OrderRecord, Vec<Comparison>) {
    let spec = OrderSpec {
        t_end: Some(Pleiades::PUBLISHED_TIME),
        ..OrderSpec::default()
    };
    let record = global_order(scheme, scene, &spec).unwrap();
    let Some([lo, hi]) = record.ci95 else {
        return (record, Vec::new());
    };
    let shrink = |order: f64| 1.0 - 2f64.powf(-order);
    let p = f64::from(record.theoretical_order);
    let rows = record
        .rungs
        .iter()
        .filter(|r| r.used)
        .map(|r| {
            let difference = r.final_error.expect("a window rung has its difference");
            let noise = r
                .round_off_bound
                .expect("a window rung has its round-off bound");
            let end = last_state(scheme, scene, record.t_end, r.steps);
            let truth = scene.phase_distance(&end, truth);
            let estimate = difference / shrink(p);
            let lower = (difference - noise).max(0.0) / shrink(hi) - noise - truth_accuracy;
            let upper = (difference + noise) / shrink(lo) + noise + truth_accuracy;
            let theory = difference * (1.0 / shrink(lo) - 1.0 / shrink(hi));
            let slack = noise * (2.0 + 1.0 / shrink(lo) + 1.0 / shrink(hi)) + 2.0 * truth_accuracy;
            Comparison {
                h: r.h,
                difference,
                estimate,
                truth,
                allowed: [lower / estimate, upper / estimate],
                sharp: slack < theory,
            }
        })
        .collect();
    (record, rows)
}

fn table(rows: &[Comparison]) -> String {
    rows.iter()
        .map(|c| {
            format!(
                "h {:.4e}  d {:.4e}  estimate {:.4e}  true {:.4e}  ratio {:.6}  allowed [{:.6}, {:.6}]{}\n",
                c.h,
                c.difference,
                c.estimate,
                c.truth,
                c.ratio(),
                c.allowed[0],
                c.allowed[1],
                if c.sharp { "" } else { "  (not sharp)" }
            )
        })
        .collect()
}

/// At least half a minimal window's rungs must be decided by the order's
/// interval, or the comparison would pass on its slack alone.
const SHARP_RUNGS: usize = 3;

#[test]
fn the_successive_rung_estimate_is_the_true_error_on_the_pleiades() {
    let stars = Pleiades::default();
    let accuracy = published_accuracy(&stars);
    let truth = stars.published_end();
    for (name, record, rows) in [
        {
            let (r, c) = estimate_against_truth(&YOSHIDA6, &stars, &truth, accuracy);
            ("yoshida6", r, c)
        },
        {
            let (r, c) = estimate_against_truth(&VELOCITY_VERLET, &stars, &truth, accuracy);
            ("velocity-verlet", r, c)
        },
    ] {
        assert!(record.passed(), "{name}: {}", record.reason);
        let shown = table(&rows);
        eprintln!("{name}, order in {:?}:\n{shown}", record.ci95.unwrap());
        assert!(rows.iter().all(Comparison::holds), "{name}:\n{shown}");
        assert!(
            rows.iter().filter(|c| c.sharp).count() >= SHARP_RUNGS,
            "{name}: too few rungs decided by the order's interval\n{shown}"
        );
    }
}

/// The Pleiades with gravity stronger by a factor `1 + epsilon`.
#[derive(Clone, Copy, Debug)]
struct StrongerGravity(Pleiades, f64);

impl Scene<14> for StrongerGravity {
    fn meta(&self) -> SceneMeta {
        self.0.meta()
    }
    fn initial(&self) -> State<14> {
        self.0.initial()
    }
    fn acceleration<R: Real>(&self, q: &SVector<R, 14>) -> SVector<R, 14> {
        self.0.acceleration(q) * R::of(1.0 + self.1)
    }
    fn potential<R: Real>(&self, q: &SVector<R, 14>) -> R {
        self.0.potential(q) * R::of(1.0 + self.1)
    }
    fn period(&self) -> f64 {
        self.0.period()
    }
    fn exact(&self, _: f64) -> Option<State<14>> {
        None
    }
}

/// The comparison can fail: with gravity `1e-7` stronger the order study
/// still converges, and estimates its own error as well as before, but to
/// another solution, which misses the published state by the perturbation's
/// effect `D` (measured here with the compensated eighth-order composition).
/// A rung whose own error `|E_h|` lies below the allowed interval's top `a`
/// then lies at least `D - a - accuracy` from the published state, above the
/// top as soon as `D > 2 a + accuracy`: every such rung must fail, and the
/// finer rungs of the window are such rungs.
#[test]
fn the_estimate_against_truth_notices_gravity_off_by_a_part_in_ten_million() {
    let stars = Pleiades::default();
    let perturbed = StrongerGravity(stars, 1e-7);
    let effect = stars.phase_distance(
        &last_state(&KAHAN_LI8_COMPENSATED, &stars, 3.0, 60_000),
        &last_state(&KAHAN_LI8_COMPENSATED, &perturbed, 3.0, 60_000),
    );
    let accuracy = published_accuracy(&stars);
    let (record, rows) =
        estimate_against_truth(&YOSHIDA6, &perturbed, &stars.published_end(), accuracy);
    assert!(record.passed(), "{}", record.reason);
    let shown = format!("effect {effect:e}\n{}", table(&rows));
    let beyond: Vec<&Comparison> = rows
        .iter()
        .filter(|c| effect > 2.0 * c.allowed[1] * c.estimate + accuracy)
        .collect();
    assert!(!beyond.is_empty(), "no rung is sure to notice:\n{shown}");
    assert!(beyond.iter().all(|c| !c.holds()), "{shown}");
}

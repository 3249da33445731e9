//! What the guard catches, measured: every coefficient of every catalogue
//! table moved in turn, and which of the guard's claims reject the result.
//!
//! For each table ([`tables`]) and each scene the catalogue is judged on,
//! each coefficient `c` is moved to `c (1 + 10^-k)` and every claim of the
//! guard is judged on the moved table: order, symplectic, reversible,
//! energy, evaluations ([`stepladder::study::claims`]) and the pin, against
//! the pin of the unmoved table ([`stepladder::guard::assert_pinned`]). A
//! claim rejects when its verdict fails a guard (a refutation or an
//! inconclusive measurement). Per claim the map records the smallest change
//! it rejects and the largest it lets through, found by bisection on `k` in
//! `1..=15`: `k = 1` and `k = 15` are judged first, then the midpoint of the
//! bracket until the two ends are adjacent. The bisection rests on a
//! premise, that a claim rejecting a change also rejects every larger one;
//! the two figures are adjacent powers of ten where it holds. Each nonzero
//! coefficient is also flipped in sign, and each pair of unequal stages of
//! one kind (two weights, two drifts, two kicks) swapped.
//!
//! What to expect, from the numerical analysis:
//!
//! - **Order.** A coefficient moved by `delta` moves the order conditions
//!   by `O(delta)`; [`tables::Coefficients::conditions_order`] says which
//!   break. A condition of degree `r <= p` left with a defect `d` adds
//!   `d h^r` to a local error of size `C h^(p+1)`, and a ladder whose finest
//!   fitted step is `h_f` sees it once `d` exceeds about `C h_f^(p+1-r)`
//!   times the order's resolution: far above round-off. A move that keeps
//!   every condition through `p` (RK4 along its family,
//!   [`tables::rk4_family`]) is a correct method of order `p`:
//!   the order claim must let it through at every size.
//! - **Scenes.** A linear force sees less than a nonlinear one: on the
//!   oscillator a method is its stability function alone, and every
//!   explicit four-stage Runge-Kutta method of order 4 has the same one,
//!   `1 + z + z^2/2 + z^3/6 + z^4/24`, so RK4 moved along its family is the
//!   same map there and no claim can reject it. The map is made on every
//!   scene, and a scheme's figure is the one of its best scene.
//! - **Pin.** The pinned error `e` changes by `O(delta)` times itself (a
//!   moved coefficient changes the error constant), and the pin's tolerance
//!   `t` is four round-off bounds, about `1e-14` of the scene: a move that
//!   only rescales the error is caught from about `t / e` whatever the
//!   order conditions say, `1e-12` for a pinned error near `1e-2`; one that
//!   breaks a condition adds an error of its own, and is caught earlier. A
//!   high-order method is pinned at a smaller error (its coarsest resolved
//!   rung is already accurate), so its pin sees less. The page prints
//!   `t / e` beside the measured figure.
//! - **Geometry.** A splitting stays symplectic whatever its weights: every
//!   flow is. A symmetric table moved in one entry of a mirrored pair loses
//!   its symmetry by `O(delta)`, and the round trip returns from it to
//!   round-off only while that loss stays below the trip's round-off
//!   allowance. For velocity Verlet with one end kick moved, the step is
//!   `Psi_h = Phi_h K` (`Phi_h` the symmetric step, `K` a kick of `delta h
//!   a / 2`), and `Psi_-h = K Psi_h^-1 K^-1`: the trip there and back is
//!   `K Psi_h^-n K^-1 Psi_h^n`. Its defect is one such kick at the far end,
//!   carried back by the flow, and does not grow with the number of steps.
//!   So the trip lets a move through while that one kick, `delta h |a| /
//!   2`, stays below the trip's allowance (`8 eps` a step over its 2000
//!   steps, times the flow's magnification). How the compositions'
//!   interior weights' defects grow is measured here, not derived. The
//!   implicit midpoint rule stays symplectic only while `b_1 = 2 a_11`, and
//!   the symplecticity claim sees a move of either.
//! - **Evaluations.** A relative move never adds or removes a stage, and
//!   the count a table claims is derived from its coefficients: no move is
//!   rejected by it, by construction. (A move that breaks a
//!   first-same-as-last table's reuse costs one force call more per step,
//!   and the claim follows it.)

pub mod page;
pub mod tables;

use crate::sensitivity::tables::{Coefficients, TableVisitor};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use stepladder::error::Error;
use stepladder::internals::accuracy::pin::{Pin, PinOutcome, check_pin_with};
use stepladder::internals::parallel::parallel_map;
use stepladder::scene::{AnyScene, Scene, SceneVisitor};
use stepladder::study::claims;

/// The guard's claims, in the order every [`Rejected`] lists them.
pub const CLAIMS: [&str; 6] = [
    "order",
    "symplectic",
    "reversible",
    "energy",
    "evaluations",
    "pin",
];

/// What the map is made from, for its fingerprint: the core's sources (the
/// tables and every study that judges them) and the map's own.
pub const SOURCES: [&str; 2] = ["src", "lab/src/sensitivity"];

/// The exponents `k` of the relative moves `10^-k`.
pub const DIGITS: [i32; 2] = [1, 15];

/// Which claims reject one table on one scene, in [`CLAIMS`] order.
pub type Rejected = [bool; 6];

/// One claim's (or the whole guard's) reach over the moves `10^-k`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Threshold {
    /// The largest `k` rejected: the smallest change caught is `10^-k`
    /// (`None`: not even `10^-1` is).
    pub caught: Option<i32>,
    /// The smallest `k` let through: the largest change let through is
    /// `10^-k` (`None`: every move down to `10^-15` is caught).
    pub passed: Option<i32>,
}

/// One coefficient's row on one scene.
#[derive(Clone, Debug, Serialize)]
pub struct CoefficientRow {
    /// Its name in the source.
    pub name: String,
    /// Its value.
    pub value: f64,
    /// Per claim, in [`CLAIMS`] order; `None` for a zero (a relative move
    /// leaves it zero).
    pub claims: Option<[Threshold; 6]>,
    /// The guard as a whole: any claim rejects.
    pub guard: Option<Threshold>,
    /// The claims that reject the coefficient with its sign flipped.
    pub sign_flip: Option<Rejected>,
    /// The order the order conditions give the table with this coefficient
    /// moved by `10^-6` (`None` where the check cannot run).
    pub conditions_order: Option<usize>,
}

/// A move that keeps every order condition, judged like a coefficient.
#[derive(Clone, Debug, Serialize)]
pub struct FamilyRow {
    /// What moves.
    pub name: String,
    /// Per claim.
    pub claims: [Threshold; 6],
    /// The order the order conditions give the table moved by `10^-1`.
    pub conditions_order: Option<usize>,
}

/// One table on one scene.
#[derive(Clone, Debug, Serialize)]
pub struct SceneMap {
    /// The scene's id.
    pub scene: &'static str,
    /// The claims that reject the unmoved table (none, for the map to mean
    /// anything).
    pub unmoved: Rejected,
    /// One row per coefficient.
    pub coefficients: Vec<CoefficientRow>,
    /// Swaps of two stages of one kind judged, and per claim how many of
    /// them it rejects.
    pub swaps: usize,
    /// Per claim, the swaps rejected.
    pub swaps_caught: [usize; 6],
    /// Swaps no claim rejects.
    pub swaps_missed: Vec<String>,
    /// RK4 along its family of fourth-order methods.
    pub family: Option<FamilyRow>,
    /// The unmoved table's pinned error.
    pub pinned_error: f64,
    /// Its pin's tolerance: a move that changes the pinned error by more is
    /// caught, so the pin should catch relative moves down to about
    /// `pin_tolerance / pinned_error` (less where a coefficient enters the
    /// error only at higher order in `h`).
    pub pin_tolerance: f64,
    /// Moved tables whose every claim was judged on this scene.
    pub judgements: usize,
}

impl SceneMap {
    /// The guard's figure on this scene: every change of a nonzero
    /// coefficient by `10^-k` or more is caught, with this `k` (`None` when
    /// some coefficient's `10^-1` is let through).
    pub fn guard_digits(&self) -> Option<i32> {
        self.coefficients
            .iter()
            .filter_map(|r| r.guard)
            .map(|g| g.caught)
            .min()
            .flatten()
    }

    /// Per claim: how many nonzero coefficients it rejects when moved by
    /// `10^-1`, and the `k` from which it rejects every one of them (`None`
    /// when it rejects none).
    pub fn claim_reach(&self, claim: usize) -> (usize, Option<i32>) {
        let seen: Vec<Option<i32>> = self
            .coefficients
            .iter()
            .filter_map(|r| r.claims.map(|c| c[claim].caught))
            .filter(Option::is_some)
            .collect();
        (seen.len(), seen.into_iter().min().flatten())
    }

    /// Nonzero coefficients.
    pub fn moved(&self) -> usize {
        self.coefficients
            .iter()
            .filter(|r| r.claims.is_some())
            .count()
    }
}

/// One catalogue table on every scene.
#[derive(Clone, Debug, Serialize)]
pub struct SchemeMap {
    /// The scheme's id.
    pub scheme: &'static str,
    /// Its claimed order.
    pub order: u32,
    /// Per scene.
    pub scenes: Vec<SceneMap>,
}

impl SchemeMap {
    /// The scene on which the guard catches the smallest change, with its
    /// figure.
    pub fn best(&self) -> Option<(&'static str, i32)> {
        self.scenes
            .iter()
            .filter_map(|s| Some((s.scene, s.guard_digits()?)))
            .max_by_key(|&(_, k)| k)
    }

    /// The map on that scene.
    pub fn best_scene(&self) -> Option<&SceneMap> {
        let (scene, _) = self.best()?;
        self.scenes.iter().find(|s| s.scene == scene)
    }
}

/// `x` moved by the relative `10^-k`.
fn moved(x: f64, k: i32) -> f64 {
    x * (1.0 + 10f64.powi(-k))
}

/// Every claim of `table` on `scene`, the pin against the pin in `pins`
/// (the unmoved table's, written by [`pin_unmoved`]). A study that cannot
/// run fails the guard, so it rejects every claim.
pub fn rejections<T: Coefficients, S: Scene<D>, const D: usize>(
    table: &T,
    scene: &S,
    pins: &Path,
) -> Rejected {
    let mut rejected = [true; 6];
    if let Ok(record) = claims(table, scene) {
        for v in &record.verdicts {
            if let Some(i) = CLAIMS.iter().position(|&c| c == v.claim) {
                rejected[i] = v.verdict.fails_a_guard();
            }
        }
    }
    rejected[5] = !matches!(
        check_pin_with(table, scene, pins, false, true),
        Ok(PinOutcome::Agrees { .. })
    );
    rejected
}

/// Writes the unmoved table's pin on `scene` into `pins`, and returns it.
///
/// # Errors
///
/// The pin cannot be made or written.
pub fn pin_unmoved<T: Coefficients, S: Scene<D>, const D: usize>(
    table: &T,
    scene: &S,
    pins: &Path,
) -> Result<Pin, Error> {
    let io = |message: String| Error::Io {
        path: pins.to_path_buf(),
        source: std::io::Error::other(message),
    };
    match check_pin_with(table, scene, pins, true, false).map_err(io)? {
        PinOutcome::Written(pin) | PinOutcome::Agrees { pin, .. } => Ok(pin),
    }
}

/// Bisection of `judged(k)` over [`DIGITS`], each `k` judged at most once,
/// for every claim and for the guard as a whole.
pub fn bisect(judged: &mut dyn FnMut(i32) -> Rejected) -> ([Threshold; 6], Threshold) {
    let mut cache: Vec<(i32, Rejected)> = Vec::new();
    let mut at = |k: i32| -> Rejected {
        if let Some(&(_, r)) = cache.iter().find(|(j, _)| *j == k) {
            return r;
        }
        let r = judged(k);
        cache.push((k, r));
        r
    };
    let mut one = |rejects: &dyn Fn(&Rejected) -> bool| -> Threshold {
        let [first, last] = DIGITS;
        if !rejects(&at(first)) {
            return Threshold {
                caught: None,
                passed: Some(first),
            };
        }
        if rejects(&at(last)) {
            return Threshold {
                caught: Some(last),
                passed: None,
            };
        }
        let (mut caught, mut passed) = (first, last);
        while passed - caught > 1 {
            let mid = (caught + passed) / 2;
            if rejects(&at(mid)) {
                caught = mid;
            } else {
                passed = mid;
            }
        }
        Threshold {
            caught: Some(caught),
            passed: Some(passed),
        }
    };
    let claims = std::array::from_fn(|i| one(&|r: &Rejected| r[i]));
    let guard = one(&|r: &Rejected| r.iter().any(|&x| x));
    (claims, guard)
}

/// A scratch folder for one table's pins on one scene.
fn pin_folder(scheme: &str, scene: &str) -> PathBuf {
    std::env::temp_dir().join(format!(
        "stepladder-sensitivity-{}-{scheme}-{scene}",
        std::process::id()
    ))
}

struct OnScene<'a, T> {
    table: &'a T,
    threads: usize,
}

impl<T: Coefficients> SceneVisitor for OnScene<'_, T> {
    type Output = Result<SceneMap, Error>;

    fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
        self,
        scene: &S,
    ) -> Result<SceneMap, Error> {
        let (table, scheme, scene_id) = (self.table, self.table.meta().id, scene.meta().id);
        let pins = pin_folder(scheme, scene_id);
        let _ = std::fs::remove_dir_all(&pins);
        let pin = pin_unmoved(table, scene, &pins)?;
        let judgements = AtomicUsize::new(0);
        let judge = |t: &T| {
            judgements.fetch_add(1, Ordering::Relaxed);
            rejections(t, scene, &pins)
        };
        let unmoved = judge(table);
        let values: Vec<f64> = table.coefficients().iter().map(|c| c.1).collect();
        let with_one = |i: usize, x: f64| {
            let mut v = values.clone();
            v[i] = x;
            table.with(&v)
        };
        let indices: Vec<usize> = (0..values.len()).collect();
        let names = table.coefficients();
        let coefficients = parallel_map(
            &indices,
            self.threads,
            |&i| {
                let (name, value) = names[i].clone();
                if value == 0.0 {
                    return CoefficientRow {
                        name,
                        value,
                        claims: None,
                        guard: None,
                        sign_flip: None,
                        conditions_order: None,
                    };
                }
                let (claims, guard) = bisect(&mut |k| judge(&with_one(i, moved(value, k))));
                CoefficientRow {
                    name,
                    value,
                    claims: Some(claims),
                    guard: Some(guard),
                    sign_flip: Some(judge(&with_one(i, -value))),
                    conditions_order: with_one(i, moved(value, 6)).conditions_order(),
                }
            },
            &|_, _| {},
        );
        let pairs: Vec<(usize, usize)> = table
            .stage_groups()
            .into_iter()
            .flat_map(|(start, end)| {
                let g: Vec<usize> = (start..end).collect();
                let mut p = Vec::new();
                for (x, &i) in g.iter().enumerate() {
                    for &j in &g[x + 1..] {
                        if values[i] != values[j] {
                            p.push((i, j));
                        }
                    }
                }
                p
            })
            .collect();
        let swapped = parallel_map(
            &pairs,
            self.threads,
            |&(i, j)| {
                let mut v = values.clone();
                v.swap(i, j);
                judge(&table.with(&v))
            },
            &|_, _| {},
        );
        let swaps_caught = std::array::from_fn(|c| swapped.iter().filter(|r| r[c]).count());
        let swaps_missed = pairs
            .iter()
            .zip(&swapped)
            .filter(|(_, r)| !r.iter().any(|&x| x))
            .map(|(&(i, j), _)| format!("{} <-> {}", names[i].0, names[j].0))
            .collect();
        let family = table.along_its_family(0.1).map(|far| {
            let (claims, _) = bisect(&mut |k| {
                let values = table.along_its_family(10f64.powi(-k)).unwrap_or_default();
                judge(&table.with(&values))
            });
            FamilyRow {
                name: "b[3] along its family of fourth-order methods".into(),
                claims,
                conditions_order: table.with(&far).conditions_order(),
            }
        });
        let _ = std::fs::remove_dir_all(&pins);
        Ok(SceneMap {
            scene: scene_id,
            unmoved,
            coefficients,
            swaps: pairs.len(),
            swaps_caught,
            swaps_missed,
            family,
            pinned_error: pin.error,
            pin_tolerance: pin.tolerance,
            judgements: judgements.load(Ordering::Relaxed),
        })
    }
}

struct MapTable<'a> {
    scenes: &'a [AnyScene],
    threads: usize,
    only: Option<&'a str>,
    progress: &'a dyn Fn(&str),
}

impl TableVisitor for MapTable<'_> {
    type Output = Option<Result<SchemeMap, Error>>;

    fn visit<T: Coefficients>(&mut self, table: &T) -> Self::Output {
        let meta = table.meta();
        if self.only.is_some_and(|id| id != meta.id) {
            return None;
        }
        (self.progress)(meta.id);
        let scenes = self
            .scenes
            .iter()
            .map(|s| {
                s.visit(OnScene {
                    table,
                    threads: self.threads,
                })
            })
            .collect::<Result<Vec<_>, _>>();
        Some(scenes.map(|scenes| SchemeMap {
            scheme: meta.id,
            order: meta.order,
            scenes,
        }))
    }
}

/// The map of every table (or of the one with id `only`) on `scenes`, on
/// `threads` threads; `progress` hears each table's id as it starts.
///
/// # Errors
///
/// `only` names no table, or the unmoved table's pin cannot be written.
pub fn sensitivity_map(
    scenes: &[AnyScene],
    only: Option<&str>,
    threads: usize,
    progress: &dyn Fn(&str),
) -> Result<Vec<SchemeMap>, Error> {
    let ids = tables::table_ids();
    if let Some(id) = only.filter(|id| !ids.contains(id)) {
        return Err(Error::UnknownScheme {
            id: id.to_string(),
            valid: ids.join(", "),
        });
    }
    tables::visit_tables(&mut MapTable {
        scenes,
        threads,
        only,
        progress,
    })
    .into_iter()
    .flatten()
    .collect()
}

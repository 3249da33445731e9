//! The outer solar system's reference state, integrated in double-double
//! arithmetic (about 32 digits), so that neither round-off nor the method's
//! coefficients limit it.
//!
//! # The problem the doubles define
//!
//! A contender integrates the scene as its doubles state it: the double `G`,
//! the double masses `m_i`, `s_i` the double nearest `sqrt(m_i)`, and the
//! double mass-weighted initial state `Q_i`. Its force law is
//! `Q_i'' = s_i sum_j G m_j (r_j - r_i) / |r_j - r_i|^3` with `r_i = Q_i / s_i`,
//! so `r_i'' = Q_i'' / s_i` is Newton's law with those masses exactly: the
//! exact solution is Newton's bodies started at `r_i = Q_i / s_i` (divided in
//! double-double, not in doubles) and read back as `s_i r_i`.
//!
//! # The method
//!
//! Yoshida's eighth-order triple jump of the Störmer-Verlet step: from an
//! order-`p` symmetric step `S`, `S(g h) S((1 - 2 g) h) S(g h)` with
//! `g = 1 / (2 - 2^(1/(p+1)))` is of order `p + 2`; three levels from Verlet
//! give 27 force evaluations a step. Its coefficients follow from the roots
//! `2^(1/3)`, `2^(1/5)`, `2^(1/7)`, each computed here in double-double by
//! Newton's method, so the composition is consistent (its weights sum to 1)
//! and of order eight to about `1e-31`: in doubles, a composition whose
//! weights sum to `1 - 1e-16` integrates a Hamiltonian `1e-16` away from the
//! scene's, which over the reference's 2.8 Jupiter orbits moves Jupiter by
//! about `1e-16` of its phase-space size times `2 pi 2.8`.
//!
//! The method is neither a contender's nor Kahan and Li's composition, and
//! the arithmetic and the force code are this module's own.

use stepladder::internals::maths::dd::Dd;
use stepladder::prelude::*;
use stepladder::scene::OuterSolarSystem;

const BODIES: usize = 6;

/// A state in double-double: physical positions and velocities of the six
/// bodies.
#[derive(Clone, Copy, Debug)]
pub struct DdBodies {
    /// Positions `r_i`.
    pub r: [[Dd; 3]; BODIES],
    /// Velocities `r_i'`.
    pub v: [[Dd; 3]; BODIES],
}

/// `x^(1/n)` in double-double, by Newton's method from the double root:
/// each step doubles the correct digits, two take 16 to beyond 32.
fn root(x: f64, n: i32) -> Dd {
    let target = Dd::of(x);
    let mut y = Dd::of(x.powf(1.0 / f64::from(n)));
    for _ in 0..3 {
        let mut power = Dd::of(1.0); // y^(n-1)
        for _ in 0..n - 1 {
            power = power.mul(y);
        }
        let residual = power.mul(y).sub(target);
        y = y.sub(residual.div(power.mul(Dd::of(f64::from(n)))));
    }
    y
}

/// The 27 Verlet step fractions of the eighth-order triple jump, in the
/// order they are taken. Their sum is 1 to double-double rounding.
pub fn triple_jump_weights() -> Vec<Dd> {
    let mut weights = vec![Dd::of(1.0)];
    for p in [2, 4, 6] {
        let r = root(2.0, p + 1);
        let outer = Dd::of(1.0).div(Dd::of(2.0).sub(r));
        let inner = r.neg().mul(outer);
        weights = [outer, inner, outer]
            .iter()
            .flat_map(|g| weights.iter().map(move |w| g.mul(*w)))
            .collect();
    }
    weights
}

/// The double-double state at `t = 0` of the problem the doubles define.
pub fn initial(planets: &OuterSolarSystem) -> DdBodies {
    let q0 = planets.initial();
    let mut s = DdBodies {
        r: [[Dd::default(); 3]; BODIES],
        v: [[Dd::default(); 3]; BODIES],
    };
    for i in 0..BODIES {
        let w = Dd::of(OuterSolarSystem::MASSES[i].sqrt());
        for k in 0..3 {
            s.r[i][k] = Dd::of(q0.q[3 * i + k]).div(w);
            s.v[i][k] = Dd::of(q0.v[3 * i + k]).div(w);
        }
    }
    s
}

/// Newton's accelerations `r_i'' = sum_j G m_j (r_j - r_i) / |r_j - r_i|^3`.
fn acceleration(r: &[[Dd; 3]; BODIES]) -> [[Dd; 3]; BODIES] {
    let g = Dd::of(OuterSolarSystem::G);
    let m = OuterSolarSystem::MASSES.map(Dd::of);
    let mut a = [[Dd::default(); 3]; BODIES];
    for i in 0..BODIES {
        for j in i + 1..BODIES {
            let d = [0, 1, 2].map(|k| r[j][k].sub(r[i][k]));
            let r2 = d[0].mul(d[0]).add(d[1].mul(d[1])).add(d[2].mul(d[2]));
            let inv3 = g.div(r2.mul(r2.sqrt()));
            let (pull_i, pull_j) = (m[j].mul(inv3), m[i].mul(inv3));
            for k in 0..3 {
                a[i][k] = a[i][k].add(d[k].mul(pull_i));
                a[j][k] = a[j][k].sub(d[k].mul(pull_j));
            }
        }
    }
    a
}

/// `steps` steps of the triple jump over `[0, t_end]`, each Verlet
/// fraction a drift of half its length, a kick, a drift.
pub fn integrate(start: &DdBodies, t_end: f64, steps: u64) -> DdBodies {
    let h = Dd::of(t_end).div(Dd::of(steps as f64));
    let fractions: Vec<Dd> = triple_jump_weights().iter().map(|w| w.mul(h)).collect();
    let mut s = *start;
    let drift = |s: &mut DdBodies, tau: Dd| {
        for (ri, vi) in s.r.iter_mut().zip(&s.v) {
            for (x, u) in ri.iter_mut().zip(vi) {
                *x = x.add(u.mul(tau));
            }
        }
    };
    let half = Dd::of(0.5);
    for _ in 0..steps {
        for tau in &fractions {
            drift(&mut s, tau.mul(half));
            let a = acceleration(&s.r);
            for (vi, ai) in s.v.iter_mut().zip(&a) {
                for (u, x) in vi.iter_mut().zip(ai) {
                    *u = u.add(x.mul(*tau));
                }
            }
            drift(&mut s, tau.mul(half));
        }
    }
    s
}

/// The mass-weighted coordinates `s_i (r_i, r_i')`, `q` then `v`, body after
/// body, in double-double.
pub fn mass_weighted_dd(s: &DdBodies) -> [Dd; 36] {
    let w = OuterSolarSystem::MASSES.map(|m| Dd::of(m.sqrt()));
    std::array::from_fn(|n| {
        let (m, part) = (n % 18, if n < 18 { &s.r } else { &s.v });
        part[m / 3][m % 3].mul(w[m / 3])
    })
}

/// A mass-weighted state, each coordinate rounded once to a double.
pub fn rounded(x: &[Dd; 36]) -> State<18> {
    State::new(
        nalgebra::SVector::from_fn(|n, _| x[n].to_f64()),
        nalgebra::SVector::from_fn(|n, _| x[18 + n].to_f64()),
    )
}

/// [`LONG_DOUBLE_CHECK`] in double-double.
pub fn long_double_check() -> [Dd; 36] {
    LONG_DOUBLE_CHECK.map(|(hi, lo)| Dd { hi, lo })
}

/// The scene's phase-space distance between two mass-weighted states in
/// double-double, resolved far below a unit of the doubles' rounding.
pub fn distance(planets: &OuterSolarSystem, a: &[Dd; 36], b: &[Dd; 36]) -> f64 {
    let w = planets.frequency();
    let squares: f64 = (0..36)
        .map(|n| {
            let d = a[n].sub(b[n]).to_f64();
            let d = if n < 18 { d } else { d / w };
            d * d
        })
        .sum();
    squares.sqrt()
}

/// The outer solar system at its default end time from an independent
/// computation: `python3 tests/check_outer_reference.py` (numpy, x87 long
/// double with Kahan-compensated updates, the sixth-order triple jump at
/// 65536 steps, which agrees with itself at 32768 steps to 3.9e-19). The 36
/// mass-weighted coordinates, `q` then `v`, each the exact sum of two
/// doubles `(hi, lo)`.
pub const LONG_DOUBLE_CHECK: [(f64, f64); 36] = [
    (0.07688057341800549, 5.414234598849488e-18),
    (-0.03904628444489287, 2.2971533529536625e-18),
    (-0.018928576683953237, 4.607859233063394e-19),
    (-0.1642945499033182, -1.4501204056993622e-18),
    (0.016043457740235308, 1.2332799712022613e-18),
    (0.010866089528542388, 2.82061971435682e-19),
    (0.1375743122191987, 7.128629284092192e-18),
    (0.07289320750367405, 4.1470733097570545e-18),
    (0.024190851653957728, 1.446732273910345e-18),
    (0.0466655605917719, 9.24959978401696e-19),
    (0.1092510553536869, -3.144186300207963e-18),
    (0.047183400109002904, -3.3237572850258745e-18),
    (0.2142499785005892, -3.3881317890172014e-18),
    (0.02218018556686186, -1.5788694136820158e-18),
    (0.0037371718731144745, 8.427977825180288e-20),
    (0.0018829348219701124, 9.846758011831241e-20),
    (-0.002210150875601537, -7.326834993749698e-20),
    (-0.001255593294520657, 5.728060305807206e-20),
    (8.183992460126034e-06, 5.550381910230816e-22),
    (2.3751374492236816e-06, 1.0877425055072314e-22),
    (7.965002900311556e-07, 4.1152235474513127e-23),
    (-3.079535339889264e-05, -2.656904127520325e-21),
    (-0.00020311996669041424, 6.696854239229312e-21),
    (-8.63135834821429e-05, 1.8131799027162367e-21),
    (-5.146998189132964e-05, -9.992341799640574e-22),
    (7.479873529179774e-05, -3.580037691129504e-21),
    (3.3113082996000514e-05, 1.8925892415213273e-21),
    (-2.4404134731994264e-05, 7.113753267956038e-22),
    (7.3470190487234235e-06, 1.8487486690560169e-22),
    (3.5624534670921378e-06, -3.7843513024301016e-23),
    (-2.4288936066984634e-06, 1.1828682759508296e-22),
    (2.0881796690767172e-05, 1.526975410772889e-21),
    (8.606972367665134e-06, 6.791152829060357e-22),
    (2.298047041776622e-07, 1.1929495396663196e-23),
    (1.241529680636094e-07, 9.318706588292702e-24),
    (-3.037110850954151e-08, -1.5380389514657858e-24),
];

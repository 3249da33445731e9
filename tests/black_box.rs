//! Black boxes the finite-difference tangent map was not designed around:
//! a highly eccentric orbit (e = 0.9, the map's derivatives large at the
//! pericentre), a non-symmetric symplectic map, and an implicit midpoint rule
//! whose fixed-point solve stops at a loose 1e-10, so its output carries
//! solver noise far above the round-off the error bound models. Correct
//! claims must pass, a false symplecticity claim must fail.

use stepladder::measure::Verdict;
use stepladder::measure::geometry::reverse::{ReverseSpec, reversibility};
use stepladder::measure::geometry::symplectic::{SymplecticSpec, symplecticity};
use stepladder::scene::{Anharmonic, KeplerCircular, KeplerEccentric, Scene};
use stepladder::scheme::{BlackBox, Force, Scheme, SchemeMeta};

const fn claims(
    id: &'static str,
    order: u32,
    symplectic: bool,
    symmetric: bool,
    evaluations: u32,
) -> SchemeMeta {
    SchemeMeta {
        id,
        name: id,
        order,
        symplectic,
        symmetric,
        force_evaluations: evaluations,
        implicit: false,
        reference: "adversarial black box",
        phase_error: None,
    }
}

fn velocity_verlet(q: &mut [f64], v: &mut [f64], h: f64, force: &mut Force<f64>) {
    let n = q.len();
    let mut a = [0.0; 2];
    force(q, &mut a[..n]);
    for i in 0..n {
        v[i] += 0.5 * h * a[i];
        q[i] += h * v[i];
    }
    force(q, &mut a[..n]);
    for i in 0..n {
        v[i] += 0.5 * h * a[i];
    }
}

fn euler_cromer(q: &mut [f64], v: &mut [f64], h: f64, force: &mut Force<f64>) {
    let n = q.len();
    let mut a = [0.0; 2];
    force(q, &mut a[..n]);
    for i in 0..n {
        v[i] += h * a[i];
        q[i] += h * v[i];
    }
}

/// The implicit midpoint rule, its midpoint velocity found by fixed-point
/// iteration stopped once a sweep changes it by less than 1e-10.
fn loose_midpoint(q: &mut [f64], v: &mut [f64], h: f64, force: &mut Force<f64>) {
    let n = q.len();
    let (mut q0, mut v0, mut mid, mut a, mut x) =
        ([0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2]);
    q0[..n].copy_from_slice(q);
    v0[..n].copy_from_slice(v);
    mid[..n].copy_from_slice(v);
    for _ in 0..200 {
        for i in 0..n {
            x[i] = q0[i] + 0.5 * h * mid[i];
        }
        force(&x[..n], &mut a[..n]);
        let mut change: f64 = 0.0;
        for i in 0..n {
            let next = v0[i] + 0.5 * h * a[i];
            change = change.max((next - mid[i]).abs());
            mid[i] = next;
        }
        if change < 1e-10 {
            break;
        }
    }
    for i in 0..n {
        q[i] = q0[i] + h * mid[i];
        v[i] = 2.0 * mid[i] - v0[i];
    }
}

fn rk4(q: &mut [f64], v: &mut [f64], h: f64, force: &mut Force<f64>) {
    let n = q.len();
    let (mut kq, mut kv) = ([[0.0; 2]; 4], [[0.0; 2]; 4]);
    let (mut x, mut u) = ([0.0; 2], [0.0; 2]);
    x[..n].copy_from_slice(q);
    u[..n].copy_from_slice(v);
    for (stage, c) in [0.5, 0.5, 1.0, 1.0].into_iter().enumerate() {
        let mut a = [0.0; 2];
        force(&x[..n], &mut a[..n]);
        kq[stage] = u;
        kv[stage] = a;
        for i in 0..n {
            x[i] = q[i] + c * h * kq[stage][i];
            u[i] = v[i] + c * h * kv[stage][i];
        }
    }
    for i in 0..n {
        q[i] += h / 6.0 * (kq[0][i] + 2.0 * kq[1][i] + 2.0 * kq[2][i] + kq[3][i]);
        v[i] += h / 6.0 * (kv[0][i] + 2.0 * kv[1][i] + 2.0 * kv[2][i] + kv[3][i]);
    }
}

fn geometry<M: Scheme, S: Scene<D>, const D: usize>(scheme: &M, scene: &S) -> (Verdict, Verdict) {
    let s = symplecticity(scheme, scene, &SymplecticSpec::default()).unwrap();
    let r = reversibility(scheme, scene, &ReverseSpec::default()).unwrap();
    (s.verdict, r.verdict)
}

#[test]
fn correct_claims_pass_on_scenes_the_bound_was_not_designed_around() {
    let e9 = KeplerEccentric::new(0.9).unwrap();
    let well = Anharmonic::default();
    let pass = (Verdict::Pass, Verdict::Pass);
    let verlet = BlackBox::new(claims("bb-verlet", 2, true, true, 2), velocity_verlet);
    assert_eq!(geometry(&verlet, &e9), pass);
    let cromer = BlackBox::new(claims("bb-euler-cromer", 1, true, false, 1), euler_cromer);
    assert_eq!(geometry(&cromer, &e9), pass);
    assert_eq!(geometry(&cromer, &well), pass);
    let midpoint = BlackBox::new(
        claims("bb-loose-midpoint", 2, true, true, 2),
        loose_midpoint,
    );
    for verdicts in [
        geometry(&midpoint, &KeplerCircular),
        geometry(&midpoint, &well),
        geometry(&midpoint, &e9),
    ] {
        assert_eq!(verdicts, pass);
    }
}

#[test]
fn a_false_symplecticity_claim_fails_on_the_eccentric_orbit() {
    let e9 = KeplerEccentric::new(0.9).unwrap();
    let liar = BlackBox::new(claims("bb-rk4-liar", 4, true, false, 4), rk4);
    let record = symplecticity(&liar, &e9, &SymplecticSpec::default()).unwrap();
    assert_eq!(record.verdict, Verdict::Fail, "{}", record.reason);
    // the defect stands far above the finite differences' bound
    assert!(
        record.symplectic_residual > 1e3 * record.tolerance,
        "{}",
        record.reason
    );
}

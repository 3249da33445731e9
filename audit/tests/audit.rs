//! One test per audited method: every claim's verdict on every scene must
//! equal the expectation written beside the method in src/methods.rs. The
//! checks that call the crates without stepladder are in independent.rs.

macro_rules! audit_tests {
    ($($name:ident),* $(,)?) => {$(
        #[test]
        fn $name() {
            stepladder_audit::assert_as_expected(&stepladder_audit::methods::$name());
        }
    )*};
}

audit_tests!(
    utsuroi_stormer_verlet,
    utsuroi_yoshida4,
    utsuroi_yoshida6,
    utsuroi_yoshida8,
    utsuroi_rk4,
    utsuroi_dormand_prince,
    de_velocity_verlet,
    de_ruth_forest,
    de_rk4,
    de_dopri5,
    os_rk4,
    os_dopri5,
    os_dop853,
    peroxide_rk4,
    peroxide_rals3,
    peroxide_rals4,
    peroxide_rk5,
    peroxide_gl4_fixed_point,
    peroxide_gl4_broyden,
    peroxide_dp45,
    peroxide_tsit45,
    russell_rk4,
    russell_dopri5,
    brahe_rkn1210_fixed,
    brahe_rkn1210,
);

/// The weights and nodes recovered from the step of each published tableau
/// the audit refutes are that tableau's, computed here from its public
/// consts without stepladder: the nodes the row sums of A (what an
/// autonomous problem sees: RALS4's third stage sits at its row sum, 1.8e-4
/// from the published c3), the weights BU summed over the stages that
/// share a node, a node of weight zero left out (RK5's second).
#[test]
fn the_recovered_rules_are_the_published_tableaux() {
    use peroxide::fuga::{ButcherTableau, RALS4, RK5};
    use stepladder::scheme::{BlackBox, Force, SchemeMeta};
    use stepladder::study::recover_quadrature;

    fn rule(a: &[&[f64]], b: &[f64]) -> Vec<(f64, f64)> {
        let mut rule: Vec<(f64, f64)> = Vec::new();
        for (row, w) in a.iter().zip(b) {
            let c: f64 = row.iter().sum();
            match rule.iter_mut().find(|(x, _)| (x - c).abs() < 1e-12) {
                Some((_, sum)) => *sum += w,
                None => rule.push((c, *w)),
            }
        }
        rule.retain(|(_, w)| *w != 0.0);
        rule.sort_by(|x, y| x.0.total_cmp(&y.0));
        rule
    }
    fn check<I: peroxide::fuga::ODEIntegrator>(
        name: &'static str,
        method: I,
        want: Vec<(f64, f64)>,
    ) -> stepladder::study::RecoveredQuadrature {
        let stages = want.len() as u32;
        let scheme = BlackBox::new(
            SchemeMeta::new(name, name, 4).force_evaluations(stages),
            move |q: &mut [f64], v: &mut [f64], h: f64, f: &Force<f64>| {
                stepladder_audit::glue::px_step(&method, q, v, h, f)
            },
        );
        let got = recover_quadrature::<_, 1>(&scheme).unwrap();
        assert_eq!(got.resolved, want.len(), "{name}: {}", got.describe());
        for (i, (c, b)) in want.iter().enumerate() {
            assert!(
                (got.nodes[i] - c).abs() <= got.node_bounds[i]
                    && (got.weights[i] - b).abs() <= got.weight_bounds[i],
                "{name}: {}: want ({c}, {b})",
                got.describe()
            );
        }
        got
    }
    let rals4 = rule(RALS4::A, RALS4::BU);
    // the third node is the row sum, resolved away from the published c3
    let published = RALS4::C[2];
    assert!((rals4[2].0 - published).abs() > 1e-4);
    let got = check("rals4", RALS4, rals4);
    assert!(
        (got.nodes[2] - published).abs() > got.node_bounds[2],
        "{}",
        got.describe()
    );
    check("rk5", RK5, rule(RK5::A, RK5::BU));
}

/// brahe's RKN12(10) step is the map of stepladder's DPRKN12 table (the
/// published tableau, its Nystrom conditions checked in double-double by
/// the core's tests): from states all round the eccentric orbit, one step
/// of each at `h = T/20` agrees to within the rounding of its sums. Both
/// form `q + h v + h^2 sum b_i k_i` and `v + h sum b'_i k_i` over 17
/// stages, in different orders; each sum's rounding is at most `17 u` of
/// the sum of its terms' sizes, which are at most those of the state and
/// its change (`u = 2^-53`): `2 x 19 u |state|`, `4.2e-15 |state|`. A
/// weight wrong in its eighth digit would move the step by `1e-8 h |k|`,
/// `~ 3e-9` here.
#[test]
fn brahe_steps_with_the_published_rkn12_tableau() {
    use stepladder::internals::run::integrate;
    use stepladder::scene::{KeplerEccentric, Scene};
    use stepladder::scheme::{BlackBox, DPRKN12, SchemeMeta};
    use stepladder::state::State;
    let scene = KeplerEccentric::default();
    let brahe = BlackBox::new(
        SchemeMeta::new("brahe-rkn1210", "brahe-rkn1210", 12).force_evaluations(17),
        stepladder_audit::glue::brahe_rkn1210_step,
    );
    let h = scene.period() / 20.0;
    let one_step = |scheme: &dyn Fn(&State<2>, &mut Option<State<2>>), from: &State<2>| {
        let mut last = None;
        scheme(from, &mut last);
        last.expect("one step")
    };
    let mut worst: f64 = 0.0;
    for k in 0..20 {
        let from = scene.exact(k as f64 * h).expect("the exact orbit");
        let theirs = one_step(
            &|s, last| {
                integrate(&brahe, &scene, s, h, 1, |_, _, x| *last = Some(*x));
            },
            &from,
        );
        let ours = one_step(
            &|s, last| {
                integrate(&DPRKN12, &scene, s, h, 1, |_, _, x| *last = Some(*x));
            },
            &from,
        );
        let size = theirs.q.norm().hypot(theirs.v.norm());
        worst = worst.max(scene.phase_distance(&theirs, &ours) / size);
    }
    let bound = 2.0 * 19.0 * f64::EPSILON / 2.0;
    println!(
        "brahe against DPRKN12, one step of T/20 from 20 states: {worst:.2e} of the state (bound {bound:.2e})"
    );
    assert!(worst <= bound, "{worst:e}");
}

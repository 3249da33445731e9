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

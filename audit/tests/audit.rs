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

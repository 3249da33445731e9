//! Change detectors: the order table, rounded so it is identical on any
//! machine, pinned with insta in the top-level `snapshots/` folder. A diff
//! here means a refactor changed a result: review it with `cargo insta review`.

use stepladder::report::order_table;
use stepladder::suite::run_suite;

fn settings(description: &str) -> insta::Settings {
    let mut s = insta::Settings::clone_current();
    s.set_snapshot_path("../snapshots");
    s.set_prepend_module_to_snapshot(false);
    s.set_description(description);
    s.set_omit_expression(true);
    s
}

#[test]
fn order_table_is_unchanged() {
    let records = run_suite(2, &|_, _, _| {}).unwrap();
    settings(
        "Measured global order of every scheme on every scene (3 decimals), its interval, the \
         fitted window with its step sizes, the straight-line slope and the verdict.",
    )
    .bind(|| insta::assert_snapshot!("order_table", order_table(&records.order)));
}

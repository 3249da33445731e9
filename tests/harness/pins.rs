//! The catalogue pins its own error constants, as a downstream crate does
//! (see `stepladder::measure::accuracy::pin`): one file per scheme and built-in scene in
//! `snapshots/pins/`, committed. A refactor that keeps a scheme's order but
//! moves its error at the pinned step by more than 1% fails here.

use std::path::Path;
use stepladder::measure::accuracy::pin::PinOutcome;
use stepladder::measure::case::case;
use stepladder::parallel::{default_threads, parallel_map};
use stepladder::scene::AnyScene;
use stepladder::scheme::scheme_ids;

#[test]
fn the_catalogue_keeps_its_pinned_error_constants() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("snapshots")
        .join("pins");
    let jobs: Vec<(&str, AnyScene)> = scheme_ids()
        .into_iter()
        .flat_map(|id| AnyScene::all().into_iter().map(move |scene| (id, scene)))
        .collect();
    let outcomes = parallel_map(
        &jobs,
        default_threads(),
        |(id, scene)| case(id, scene).map_err(|e| e.to_string())?.pin(&dir),
        &|_, _| {},
    );
    let failures: Vec<&String> = outcomes.iter().filter_map(|o| o.as_ref().err()).collect();
    assert!(
        failures.is_empty(),
        "{}",
        failures
            .iter()
            .map(|f| f.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
    let checked = outcomes
        .iter()
        .filter(|o| matches!(o, Ok(PinOutcome::Agrees { .. })))
        .count();
    // a pin is written only outside CI (a first run, or an update); under
    // CI a missing pin is one of the failures above
    eprintln!("{checked} pins agree, {} written", outcomes.len() - checked);
}

//! The full suite: every study on every catalogue scheme and built-in scene.
//! Cases run in parallel on scoped threads, but results are stored by case,
//! so the records are the same whatever the thread count.

use crate::case::{Case, case};
use crate::error::Error;
use crate::measure::order::{OrderRecord, OrderSpec};
use crate::scene::AnyScene;
use crate::scheme::scheme_ids;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Every record of a suite run, in catalogue-major, scene-minor order.
#[derive(Clone, Debug)]
pub struct SuiteRecords {
    /// One order record per scheme and scene.
    pub order: Vec<OrderRecord>,
    /// Wall time of each case's studies (machine-dependent), same order.
    pub timings: Vec<Duration>,
    /// Wall time of the whole suite.
    pub total: Duration,
    /// Threads used.
    pub threads: usize,
}

/// Where a worker leaves one case's result.
type Slot = Mutex<Option<Result<(OrderRecord, Duration), Error>>>;

/// Every catalogue scheme bound to every built-in scene.
pub fn all_cases() -> Vec<Box<dyn Case>> {
    let scenes = AnyScene::all();
    scheme_ids()
        .into_iter()
        .flat_map(|id| {
            scenes
                .iter()
                .map(move |s| case(id, s).expect("catalogue ids are valid"))
        })
        .collect()
}

/// Runs the suite on `threads` threads (at least one), calling
/// `progress(done, total, case)` as each case finishes.
pub fn run_suite(
    threads: usize,
    progress: &(dyn Fn(usize, usize, &dyn Case) + Sync),
) -> Result<SuiteRecords, Error> {
    let cases = all_cases();
    let start = Instant::now();
    let slots: Vec<Slot> = cases.iter().map(|_| Mutex::new(None)).collect();
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let threads = threads.clamp(1, cases.len().max(1));
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(c) = cases.get(i) else { break };
                    let t = Instant::now();
                    let result = c.order(&OrderSpec::default()).map(|r| (r, t.elapsed()));
                    *slots[i].lock().expect("no panics while holding the lock") = Some(result);
                    progress(
                        done.fetch_add(1, Ordering::Relaxed) + 1,
                        cases.len(),
                        c.as_ref(),
                    );
                }
            });
        }
    });
    let mut order = Vec::with_capacity(cases.len());
    let mut timings = Vec::with_capacity(cases.len());
    for slot in slots {
        let (record, time) = slot
            .into_inner()
            .expect("no poisoned lock")
            .expect("every case ran")?;
        order.push(record);
        timings.push(time);
    }
    Ok(SuiteRecords {
        order,
        timings,
        total: start.elapsed(),
        threads,
    })
}

/// Threads to use by default: what the machine offers.
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

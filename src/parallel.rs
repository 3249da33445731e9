//! The one runner of parallel work: items on scoped threads, results in
//! item order, so that every record is the same whatever the thread count.

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// `f` on every item on `threads` scoped threads (at least one), results in
/// item order whatever the thread count or the order of completion;
/// `finished(done)` is called as each item completes.
pub fn parallel_map<T: Sync, U: Send>(
    items: &[T],
    threads: usize,
    f: impl Fn(&T) -> U + Sync,
    finished: &(dyn Fn(usize, &T) + Sync),
) -> Vec<U> {
    let slots: Vec<Mutex<Option<U>>> = items.iter().map(|_| Mutex::new(None)).collect();
    let (next, done) = (AtomicUsize::new(0), AtomicUsize::new(0));
    std::thread::scope(|scope| {
        for _ in 0..threads.clamp(1, items.len().max(1)) {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(item) = items.get(i) else { break };
                    let result = f(item);
                    *slots[i].lock().expect("no panics while holding the lock") = Some(result);
                    finished(done.fetch_add(1, Ordering::Relaxed) + 1, item);
                }
            });
        }
    });
    slots
        .into_iter()
        .map(|slot| {
            slot.into_inner()
                .expect("no poisoned lock")
                .expect("every item ran")
        })
        .collect()
}

/// Threads to use by default: what the machine offers.
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

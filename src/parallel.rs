//! Independent jobs on this machine's cores (one worker pool for all), with results in
//! a fixed order, so that what is printed (and the first error reported) does not
//! depend on scheduling.

/// The stack of every thread that evaluates a file's expressions: definitions chained
/// up to the loader's bound (400) and the kernel's (1,000) recurse once per level, a few
/// kilobytes each, far beyond the 2 MiB Rust gives a spawned thread. Only the pages
/// touched are ever committed.
pub const STACK: usize = 256 << 20;

/// A scoped thread with a [`STACK`]-sized stack.
pub fn spawn_scoped<'s, 'e, T: Send + 's>(
    scope: &'s std::thread::Scope<'s, 'e>,
    f: impl FnOnce() -> T + Send + 's,
) -> std::thread::ScopedJoinHandle<'s, T> {
    std::thread::Builder::new()
        .stack_size(STACK)
        .spawn_scoped(scope, f)
        .expect("the operating system refused a worker thread")
}

/// How many workers `jobs` independent jobs get: one per core of this machine, never
/// more than there are jobs.
pub fn workers(jobs: usize) -> usize {
    std::thread::available_parallelism()
        .map_or(1, usize::from)
        .min(jobs)
        .max(1)
}

/// The one worker pool: `work(k, w)` for every job `k` of `order`, taken in that order
/// by [`workers`] threads (`w` is the worker's number, below `workers(order.len())`).
/// Each result reaches `tick` on the calling thread as `Some((k, result))` when it is
/// done, and `tick(None)` comes every `every` while jobs run (for progress). A job
/// that panics ends its worker (the others go on) and reports nothing; the first such
/// panic is returned.
pub fn pool<T: Send>(
    order: &[usize],
    every: std::time::Duration,
    work: impl Fn(usize, usize) -> T + Sync,
    mut tick: impl FnMut(Option<(usize, T)>),
) -> Option<Box<dyn std::any::Any + Send>> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::mpsc::RecvTimeoutError;
    let next = AtomicUsize::new(0);
    std::thread::scope(|scope| {
        let (tx, rx) = std::sync::mpsc::channel();
        let handles: Vec<_> = (0..workers(order.len()))
            .map(|w| {
                let (tx, next, work) = (tx.clone(), &next, &work);
                spawn_scoped(scope, move || loop {
                    let Some(&k) = order.get(next.fetch_add(1, Ordering::Relaxed)) else {
                        return;
                    };
                    if tx.send((k, work(k, w))).is_err() {
                        return;
                    }
                })
            })
            .collect();
        drop(tx);
        loop {
            match rx.recv_timeout(every) {
                Ok(done) => tick(Some(done)),
                Err(RecvTimeoutError::Timeout) => tick(None),
                Err(RecvTimeoutError::Disconnected) => break,
            }
        }
        handles.into_iter().find_map(|h| h.join().err())
    })
}

/// `work(0), …, work(n − 1)` on the [`pool`], the results in index order: for
/// independent jobs (files read, failures attributed) whose first error in index order
/// must be the one reported, as when they run one after another.
pub fn in_index_order<T: Send>(n: usize, work: impl Fn(usize) -> T + Sync) -> Vec<T> {
    if workers(n) <= 1 {
        return (0..n).map(work).collect();
    }
    let order: Vec<usize> = (0..n).collect();
    let mut slots: Vec<Option<T>> = (0..n).map(|_| None).collect();
    let panicked = pool(
        &order,
        std::time::Duration::from_secs(3600),
        |k, _| work(k),
        |done| {
            if let Some((k, value)) = done {
                slots[k] = Some(value);
            }
        },
    );
    if let Some(payload) = panicked {
        std::panic::resume_unwind(payload);
    }
    slots
        .into_iter()
        .map(|v| v.expect("every job of the pool reports"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn every_job_reports_once_and_results_come_back_in_index_order() {
        let squares = in_index_order(50, |k| k * k);
        assert_eq!(squares, (0..50).map(|k| k * k).collect::<Vec<_>>());
        let order = [3, 1, 2, 0];
        let mut seen = Vec::new();
        let mut ticks = 0;
        let panicked = pool(
            &order,
            Duration::from_millis(5),
            |k, w| {
                assert!(w < workers(order.len()));
                if k == 0 {
                    std::thread::sleep(Duration::from_millis(60));
                }
                10 * k
            },
            |done| match done {
                Some(r) => seen.push(r),
                None => ticks += 1,
            },
        );
        assert!(panicked.is_none());
        seen.sort_unstable();
        assert_eq!(seen, [(0, 0), (1, 10), (2, 20), (3, 30)]);
        assert!(ticks > 0, "progress ticks while a job runs");
    }

    #[test]
    fn a_panicking_job_is_returned_and_the_others_are_done() {
        let mut seen = Vec::new();
        let panicked = pool(
            &[0, 1, 2, 3, 4, 5],
            Duration::from_secs(60),
            |k, _| {
                assert_ne!(k, 2, "job 2 fails");
                k
            },
            |done| seen.extend(done),
        );
        let payload = panicked.expect("the panic is returned");
        let message = payload
            .downcast_ref::<String>()
            .cloned()
            .unwrap_or_default();
        assert!(message.contains("job 2 fails"), "{message}");
        // With more than one worker every other job is done, whichever worker the
        // panic stopped; alone, the worker stops at the panic.
        seen.sort_unstable();
        let expected = if workers(6) > 1 { 5 } else { 2 };
        assert_eq!(seen.len(), expected, "{seen:?}");
        assert!(!seen.iter().any(|&(k, _)| k == 2));
        let caught = std::panic::catch_unwind(|| in_index_order(4, |k| assert_ne!(k, 1)));
        assert!(caught.is_err(), "in_index_order passes the panic on");
    }
}

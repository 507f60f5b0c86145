//! Independent jobs on this machine's two cores, with results in a fixed order, so
//! that what is printed (and the first error reported) does not depend on scheduling.

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

/// `work(0), …, work(n − 1)` on up to two threads (this machine's cores), the results
/// in index order: for independent jobs (files read, failures attributed) whose first
/// error in index order must be the one reported, as when they run one after another.
pub fn in_index_order<T: Send>(n: usize, work: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let workers = std::thread::available_parallelism()
        .map_or(1, usize::from)
        .clamp(1, 2)
        .min(n);
    if workers <= 1 {
        return (0..n).map(work).collect();
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut done: Vec<(usize, T)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                spawn_scoped(scope, || {
                    let mut mine = Vec::new();
                    loop {
                        let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        if k >= n {
                            return mine;
                        }
                        mine.push((k, work(k)));
                    }
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    done.sort_unstable_by_key(|&(k, _)| k);
    done.into_iter().map(|(_, value)| value).collect()
}

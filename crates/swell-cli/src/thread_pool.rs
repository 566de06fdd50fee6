//! The worker threads a command runs on: below both the commands (`cmd/`) and the benchmarks
//! (`bench/`), so neither imports the other for it.

use swell::scene::MAX_THREADS;
use swell::{Error, Result};

/// A rayon pool with `threads` workers (0 = one per core), at most [`MAX_THREADS`], named
/// `--threads` in errors.
pub fn thread_pool(threads: u32) -> Result<rayon::ThreadPool> {
    if threads > MAX_THREADS {
        return Err(Error::out_of_range("--threads", threads, format!("[0, {MAX_THREADS}]")));
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads as usize)
        .build()
        .map_err(|e| Error::invalid("--threads", format!("cannot start {threads} threads: {e}")))
}

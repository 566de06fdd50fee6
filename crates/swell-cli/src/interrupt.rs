//! SIGINT / SIGTERM during long jobs (`bake`, `render --frames`, `export --frames`).
//!
//! The signal handler only raises a flag (the one thing a handler may safely do); the job checks it
//! between frames and stops there, so every file under its final name stays complete (each is
//! written through `swell::export::write_atomically`) and the unfinished temporary files are
//! removed as their writers unwind. The command then ends with a message naming the signal and
//! what is left to do, and exit code 1. A second SIGINT or SIGTERM while stopping ends the process
//! at once (exit code 1), for a user who does not want to wait for the frames in flight.
//!
//! This lives in the CLI, not the library: a signal handler is process-wide state.

use std::any::Any;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;

use signal_hook::consts::{SIGINT, SIGTERM};
use swell::{Error, Result};

/// The flag raised by SIGINT / SIGTERM.
pub struct Interrupt {
    raised: Arc<AtomicBool>,
    signal: Arc<AtomicUsize>,
}

/// The unwinding payload that carries a stop out of the library's parallel frame loop.
struct Stop;

impl Interrupt {
    /// Installs the handlers for SIGINT and SIGTERM.
    pub fn install() -> Result<Self> {
        let (raised, signal) = (Arc::new(AtomicBool::new(false)), Arc::new(AtomicUsize::new(0)));
        for sig in [SIGINT, SIGTERM] {
            // Registered first so that it sees the flag as it was before this signal: a second
            // signal exits at once, the first only raises the flag.
            signal_hook::flag::register_conditional_shutdown(sig, 1, raised.clone())
                .and_then(|_| signal_hook::flag::register_usize(sig, signal.clone(), sig as usize))
                .and_then(|_| signal_hook::flag::register(sig, raised.clone()))
                .map_err(|e| Error::invalid("signal", format!("cannot install the handler for signal {sig}: {e}")))?;
        }
        Ok(Self { raised, signal })
    }

    /// Whether a signal has arrived.
    pub fn raised(&self) -> bool {
        self.raised.load(Ordering::SeqCst)
    }

    /// `SIGINT` or `SIGTERM`: the signal that arrived.
    pub fn name(&self) -> &'static str {
        if self.signal.load(Ordering::SeqCst) == SIGTERM as usize {
            "SIGTERM"
        } else {
            "SIGINT"
        }
    }

    /// An error saying the job stopped on the signal, then `what` (what is complete, what to do).
    pub fn error(&self, what: impl std::fmt::Display) -> Error {
        Error::invalid("interrupted", format!("stopped by {}: {what}", self.name()))
    }

    /// `Err` once a signal has arrived: for loops the CLI drives itself, between frames.
    pub fn check(&self, what: impl std::fmt::Display) -> Result<()> {
        if self.raised() {
            Err(self.error(what))
        } else {
            Ok(())
        }
    }

    /// Called from a library callback (after a frame is complete): once a signal has arrived,
    /// unwinds out of the library's loop. The loop's other workers finish or abandon their frames
    /// as the unwinding passes (rayon joins them), and abandoned temporary files delete themselves.
    /// Must run inside [`Interrupt::catch`].
    pub fn stop_here(&self) {
        if self.raised() {
            // resume_unwind, not panic!: no panic hook, no "panicked at" message.
            resume_unwind(Box::new(Stop));
        }
    }

    /// Runs `job`, turning a stop from [`Interrupt::stop_here`] into `Err(on_stop())`; real panics
    /// go on unwinding.
    pub fn catch<T>(&self, job: impl FnOnce() -> Result<T>, on_stop: impl FnOnce() -> Error) -> Result<T> {
        match catch_unwind(AssertUnwindSafe(job)) {
            Ok(r) => r,
            Err(payload) if is_stop(&*payload) => Err(on_stop()),
            Err(payload) => resume_unwind(payload),
        }
    }
}

fn is_stop(payload: &(dyn Any + Send)) -> bool {
    payload.is::<Stop>()
}

//! Solver calls on a worker thread, so that the caller's deadline and cancel requests are
//! honoured even while a solver is busy in C code that cannot be interrupted.

use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

use super::PatternError;
use crate::control::Control;

/// How often the calling thread asks its [`Control`] whether to go on while a solver works.
const POLL: Duration = Duration::from_millis(50);
/// After a cancel, how long to wait for the solver to finish its current call (most take
/// milliseconds), so that nothing is left running in the common case.
const CANCEL_GRACE: Duration = Duration::from_secs(1);

/// Runs `work` on a worker thread and waits for it at most `time_limit`, asking `control`
/// (with `progress()`) every [`POLL`] whether to go on; progress callbacks so stay on the
/// calling thread. Returns `None` when the time limit passes first: a worker that outlives
/// it is left to finish on its own (the solvers are given their own, shorter limits), and
/// its result is dropped.
///
/// # Errors
/// [`PatternError::Cancelled`] when `control` asks to stop; [`PatternError::Solver`] when no
/// thread can be started or the worker panics.
pub(super) fn run<T: Send + 'static>(
    work: impl FnOnce() -> T + Send + 'static,
    time_limit: Duration,
    control: &mut Control<'_>,
    progress: impl Fn() -> f64,
) -> Result<Option<T>, PatternError> {
    let (sender, receiver) = mpsc::channel();
    let handle = std::thread::Builder::new()
        .name("tilepattern-solver".into())
        .spawn(move || {
            let _ = sender.send(work());
        })
        .map_err(|e| PatternError::Solver(format!("cannot start the solver thread: {e}")))?;
    // A worker that has sent its result is finished: join it so its resources go at once.
    let finished = |handle: std::thread::JoinHandle<()>| {
        let _ = handle.join();
    };
    let deadline = Instant::now() + time_limit;
    loop {
        let wait = deadline.saturating_duration_since(Instant::now()).min(POLL);
        match receiver.recv_timeout(wait) {
            Ok(result) => {
                finished(handle);
                return Ok(Some(result));
            }
            Err(RecvTimeoutError::Timeout) if Instant::now() < deadline => {
                if !control.keep_going(progress()) {
                    if receiver.recv_timeout(CANCEL_GRACE).is_ok() {
                        finished(handle);
                    }
                    return Err(PatternError::Cancelled);
                }
            }
            Err(RecvTimeoutError::Timeout) => return Ok(None),
            Err(RecvTimeoutError::Disconnected) => {
                return Err(PatternError::Solver(
                    "the solver thread stopped unexpectedly".into(),
                ));
            }
        }
    }
}

//! Solver calls on a worker thread, so that the caller's progress callbacks stay on its own
//! thread while a solver is busy in C code, and its deadline and cancel requests reach the
//! solver: they raise the solver's [`Stop`], which CBC and Clp ask at every node and every
//! iteration, and the worker ends within milliseconds (releasing CBC's lock).

use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

use super::PatternError;
use crate::control::Control;
use crate::solver::Stop;

/// How often the calling thread asks its [`Control`] whether to go on while a solver works.
const POLL: Duration = Duration::from_millis(20);
/// After a stop request, how long to wait at most for the solver to end (it ends at its
/// next node or iteration, in milliseconds), so that nothing is left running and CBC is free
/// for the next solve. A solver that takes longer is left to end on its own.
const STOP_GRACE: Duration = Duration::from_secs(1);

/// Runs `work` on a worker thread and waits for it at most `time_limit`, asking `control`
/// (with `progress()`) every [`POLL`] whether to go on; progress callbacks so stay on the
/// calling thread. `work` is given the [`Stop`] that is requested when the caller cancels or
/// the time limit passes, and should hand it to its solver. Returns `None` when the time
/// limit passes first (what the stopped worker returns is dropped).
///
/// # Errors
/// [`PatternError::Cancelled`] when `control` asks to stop; [`PatternError::Solver`] when no
/// thread can be started or the worker panics.
pub(super) fn run<T: Send + 'static>(
    work: impl FnOnce(Stop) -> T + Send + 'static,
    time_limit: Duration,
    control: &mut Control<'_>,
    progress: impl Fn() -> f64,
) -> Result<Option<T>, PatternError> {
    let stop = Stop::new();
    let (sender, receiver) = mpsc::channel();
    let handle = {
        let stop = stop.clone();
        std::thread::Builder::new()
            .name("tilepattern-solver".into())
            .spawn(move || {
                let _ = sender.send(work(stop));
            })
            .map_err(|e| PatternError::Solver(format!("cannot start the solver thread: {e}")))?
    };
    // A worker that has sent its result is finished: join it so its resources go at once.
    let finished = |handle: std::thread::JoinHandle<()>| {
        let _ = handle.join();
    };
    // Stops the worker and waits for it to end.
    let stopped = |handle: std::thread::JoinHandle<()>| {
        stop.request();
        if receiver.recv_timeout(STOP_GRACE).is_ok() {
            finished(handle);
        }
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
                    stopped(handle);
                    return Err(PatternError::Cancelled);
                }
            }
            Err(RecvTimeoutError::Timeout) => {
                stopped(handle);
                return Ok(None);
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(PatternError::Solver(
                    "the solver thread stopped unexpectedly".into(),
                ));
            }
        }
    }
}

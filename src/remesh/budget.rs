//! The remesher's side of [`Control`]: progress in stages, cancellation and the time limit,
//! polled between iterations of every loop that can run long.
//!
//! Polling never changes a result: it only decides whether to go on. Callbacks are throttled
//! (at most one every [`REPORT_EVERY`], plus one at the start of every stage), the clock is
//! read on every poll.

use std::time::{Duration, Instant};

use super::RemeshError;
use crate::control::Control;

/// Least time between two progress callbacks within a stage.
const REPORT_EVERY: Duration = Duration::from_millis(10);

/// Why the remesher stopped early.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Stop {
    /// The caller's callback asked to stop.
    Cancelled,
    /// The time limit passed.
    TimeLimit,
}

/// Progress, cancellation and time limit of one remesh run.
pub(crate) struct Budget<'c, 'a> {
    control: &'c mut Control<'a>,
    start: Instant,
    deadline: Option<Instant>,
    from: f64,
    to: f64,
    last_report: Option<Instant>,
    /// Highest fraction reported, so reports never go backwards.
    reported: f64,
    stop: Option<Stop>,
}

impl<'c, 'a> Budget<'c, 'a> {
    /// A budget of `limit` from `start`, reporting to `control`.
    pub fn new(control: &'c mut Control<'a>, start: Instant, limit: Duration) -> Self {
        Self {
            control,
            start,
            deadline: start.checked_add(limit),
            from: 0.0,
            to: 0.0,
            last_report: None,
            reported: 0.0,
            stop: None,
        }
    }

    /// Enters the stage spanning fractions `from..to` of the run; reports its start.
    pub fn stage(&mut self, from: f64, to: f64) -> bool {
        self.from = from;
        self.to = to;
        self.last_report = None;
        self.poll(0.0)
    }

    /// `within` of the current stage is done; `false` once the run must stop (and from then on).
    pub fn poll(&mut self, within: f64) -> bool {
        if self.stop.is_some() {
            return false;
        }
        let now = Instant::now();
        if self.deadline.is_some_and(|d| now >= d) {
            self.stop = Some(Stop::TimeLimit);
            return false;
        }
        if self
            .last_report
            .is_none_or(|last| now.duration_since(last) >= REPORT_EVERY)
        {
            self.last_report = Some(now);
            let fraction =
                (self.from + (self.to - self.from) * within.clamp(0.0, 1.0)).max(self.reported);
            self.reported = fraction;
            if !self.control.keep_going(fraction) {
                self.stop = Some(Stop::Cancelled);
                return false;
            }
        }
        true
    }

    /// Why the run stopped, if it did.
    pub fn stopped(&self) -> Option<Stop> {
        self.stop
    }

    /// `Err` with the reason once the run must stop.
    pub fn check(&self) -> Result<(), RemeshError> {
        match self.stop {
            None => Ok(()),
            Some(Stop::Cancelled) => Err(RemeshError::Cancelled),
            Some(Stop::TimeLimit) => Err(RemeshError::TimeLimit {
                seconds: self.start.elapsed().as_secs_f64(),
            }),
        }
    }

    /// Reports the end of the run.
    pub fn finish(&mut self) {
        if self.stop != Some(Stop::Cancelled) {
            self.control.keep_going(1.0);
        }
    }
}

//! Progress reports and cancellation for long stages.
//!
//! A stage calls [`Control::keep_going`] at safe points with the fraction of its work (or
//! time budget) done; the caller's callback answers whether to continue. Callbacks run on
//! the thread that called the stage, never on a solver's worker thread, so a host
//! application (Rhino, a Python script) can safely check its own UI state from them.

/// Watches a stage on behalf of its caller.
#[derive(Default)]
pub struct Control<'a> {
    progress: Option<&'a mut dyn FnMut(f64) -> bool>,
    cancelled: bool,
}

impl<'a> Control<'a> {
    /// A control that never cancels.
    pub fn none() -> Self {
        Self::default()
    }

    /// A control that reports progress in `[0, 1]` to `progress`; returning `false` cancels.
    pub fn with_progress(progress: &'a mut dyn FnMut(f64) -> bool) -> Self {
        Self {
            progress: Some(progress),
            cancelled: false,
        }
    }

    /// Reports `fraction` done and returns `false` once the caller has asked to stop (and
    /// from then on, without calling back again).
    pub fn keep_going(&mut self, fraction: f64) -> bool {
        if !self.cancelled {
            if let Some(progress) = self.progress.as_mut() {
                self.cancelled = !progress(fraction.clamp(0.0, 1.0));
            }
        }
        !self.cancelled
    }
}

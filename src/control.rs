//! Progress reports and cancellation for long stages.
//!
//! A stage calls [`Control::keep_going`] at safe points with the fraction of its work (or
//! time budget) done; the caller's callback answers whether to continue. Callbacks run on
//! the thread that called the stage, never on a solver's worker thread, so a host
//! application (Rhino, a Python script) can safely check its own UI state from them.
//!
//! The pattern stage also [`notes`](Control::note) its [`Figures`] (best objective found and
//! proven bound) as they improve; a caller that asked for them ([`Control::with_figures`],
//! e.g. the command line's progress line) gets the latest with every report.

/// What the pattern stage knows so far: the objective of the best pattern found and the
/// proven upper bound on it (section 3.3 of the paper: the objectives of eqs. 1-3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Figures {
    /// Objective of the best pattern found so far.
    pub best: f64,
    /// Proven upper bound on the objective.
    pub bound: f64,
}

impl Figures {
    /// The relative gap ([`relative_gap`]), zero once the best meets the bound.
    pub fn gap(&self) -> f64 {
        relative_gap(self.best, self.bound).max(0.0)
    }
}

/// `(bound - objective) / max(|bound|, 1)`: the pattern's gap (`Pattern::gap`), what its
/// `PatternOptions::gap` is compared with, and the progress line's.
pub fn relative_gap(objective: f64, bound: f64) -> f64 {
    (bound - objective) / bound.abs().max(1.0)
}

/// Watches a stage on behalf of its caller.
#[derive(Default)]
pub struct Control<'a> {
    progress: Option<&'a mut dyn FnMut(f64) -> bool>,
    watch: Option<&'a mut dyn FnMut(f64, Option<Figures>) -> bool>,
    figures: Option<Figures>,
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
            ..Self::default()
        }
    }

    /// A control that reports progress in `[0, 1]` and the latest [`Figures`] noted by the
    /// stage (none before the first) to `watch`; returning `false` cancels.
    pub fn with_figures(watch: &'a mut dyn FnMut(f64, Option<Figures>) -> bool) -> Self {
        Self {
            watch: Some(watch),
            ..Self::default()
        }
    }

    /// Records the stage's latest figures; the next report carries them.
    pub fn note(&mut self, figures: Figures) {
        self.figures = Some(figures);
    }

    /// Replaces the figures noted so far, forgetting them with `None` (a pipeline starting
    /// another try, whose pattern stage has noted nothing yet).
    pub fn set_figures(&mut self, figures: Option<Figures>) {
        self.figures = figures;
    }

    /// The figures noted last, if any.
    pub fn figures(&self) -> Option<Figures> {
        self.figures
    }

    /// Reports `fraction` done and returns `false` once the caller has asked to stop (and
    /// from then on, without calling back again).
    pub fn keep_going(&mut self, fraction: f64) -> bool {
        if !self.cancelled {
            let fraction = fraction.clamp(0.0, 1.0);
            if let Some(progress) = self.progress.as_mut() {
                self.cancelled = !progress(fraction);
            } else if let Some(watch) = self.watch.as_mut() {
                self.cancelled = !watch(fraction, self.figures);
            }
        }
        !self.cancelled
    }
}

/// For tests of cancel: a progress callback that lets a stage go on for `delay` from now,
/// then asks it to stop, and when it first asked.
#[cfg(test)]
pub(crate) fn cancel_after(
    delay: std::time::Duration,
) -> (
    impl FnMut(f64) -> bool,
    std::rc::Rc<std::cell::Cell<Option<std::time::Instant>>>,
) {
    let started = std::time::Instant::now();
    let asked = std::rc::Rc::new(std::cell::Cell::new(None));
    let seen = std::rc::Rc::clone(&asked);
    let callback = move |_| {
        if started.elapsed() < delay {
            return true;
        }
        if seen.get().is_none() {
            seen.set(Some(std::time::Instant::now()));
        }
        false
    };
    (callback, asked)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_reach_the_watcher_with_the_next_report_and_cancel_sticks() {
        let figures = Figures {
            best: 40.0,
            bound: 50.0,
        };
        let mut seen = Vec::new();
        let mut watch = |fraction: f64, figures: Option<Figures>| {
            seen.push((fraction, figures));
            fraction < 0.75
        };
        {
            let mut control = Control::with_figures(&mut watch);
            assert!(control.keep_going(0.25));
            control.note(figures);
            assert!(control.keep_going(1.5 * 0.25));
            assert!(!control.keep_going(0.8));
            assert!(!control.keep_going(0.9), "cancelled stays cancelled");
        }
        assert_eq!(
            seen,
            vec![(0.25, None), (0.375, Some(figures)), (0.8, Some(figures))]
        );
        assert!((figures.gap() - 0.2).abs() < 1e-12);
        let small = Figures {
            best: 0.25,
            bound: 0.5,
        };
        assert!(
            (small.gap() - 0.25).abs() < 1e-12,
            "divided by max(|bound|, 1)"
        );
    }
}

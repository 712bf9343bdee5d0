//! The command line's progress: while a long stage runs, one line on the terminal, redrawn
//! in place at most five times a second, with the stage, the time since the command started,
//! the share of the stage's work (or time budget) done and, for the pattern stage, the best
//! objective found, the proven bound and their gap (the [`Figures`] the engine notes through
//! its [`Control`]; the C library's callback hears the same stage and fraction). Silent when
//! standard error is not a terminal (a pipe, a file, CI), so logs and scripts see only the
//! final summary. The line is erased when the stage ends.
//!
//! With `--log` the same lines are written one under the other instead, terminal or not, as
//! a MIP solver's log is: a line when a stage starts, whenever the best or the bound
//! changes, and every [`HEARTBEAT`] in between, so that a run in a script or CI shows how
//! the search went.

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

use tilepattern::control::Figures;

/// Least time between two redraws.
const REDRAW: Duration = Duration::from_millis(200);
/// Longest time between two lines of the log when nothing changes.
const HEARTBEAT: Duration = Duration::from_secs(5);

/// The line, drawn on `out` when enabled.
pub struct ProgressLine<W: Write> {
    out: W,
    enabled: bool,
    started: Instant,
    last: Option<Instant>,
    drawn: bool,
    /// Lines one under the other ([`ProgressLine::log`]), with what the last one showed.
    log: Option<Logged>,
    /// Runs [`ProgressLine::update_run`] hears as equal shares of `0..1` (the pipeline's
    /// tries).
    tries: usize,
}

/// What the log's last line showed.
#[derive(Default)]
struct Logged {
    stage: String,
    figures: Option<Figures>,
}

impl ProgressLine<std::io::Stderr> {
    /// On standard error: the log when `log`, else the line, enabled only when standard
    /// error is a terminal.
    pub fn on_stderr(log: bool) -> Self {
        let err = std::io::stderr();
        if log {
            return ProgressLine::log(err);
        }
        let enabled = err.is_terminal();
        Self::new(err, enabled)
    }
}

impl<W: Write> ProgressLine<W> {
    /// A line on `out`; with `enabled` false nothing is ever written.
    pub fn new(out: W, enabled: bool) -> Self {
        Self {
            out,
            enabled,
            started: Instant::now(),
            last: None,
            drawn: false,
            log: None,
            tries: 1,
        }
    }

    /// For a pipeline of `tries` runs ([`tilepattern::pipeline::tile_surface_tries`], each
    /// an equal share of the fraction): the stages are labelled with their try.
    pub fn with_tries(self, tries: usize) -> Self {
        Self {
            tries: tries.max(1),
            ..self
        }
    }

    /// The log on `out`: a line when a stage starts, when the figures change, and every
    /// [`HEARTBEAT`] otherwise; nothing redrawn or erased.
    pub fn log(out: W) -> Self {
        Self {
            log: Some(Logged::default()),
            ..Self::new(out, true)
        }
    }

    /// Shows `stage` at `fraction` with the pattern's `figures`, if the last redraw is old
    /// enough. Always lets the stage go on (the command line cancels with Ctrl-C).
    pub fn update(&mut self, stage: &str, fraction: f64, figures: Option<Figures>) -> bool {
        if !self.enabled {
            return true;
        }
        let now = Instant::now();
        if let Some(logged) = self.log.as_mut() {
            let news = logged.stage != stage
                || logged.figures != figures
                || self
                    .last
                    .is_none_or(|last| now.duration_since(last) >= HEARTBEAT);
            if news {
                logged.stage = stage.to_string();
                logged.figures = figures;
                self.last = Some(now);
                let line = format_line(stage, now.duration_since(self.started), fraction, figures);
                let _ = writeln!(self.out, "{line}");
                let _ = self.out.flush();
            }
            return true;
        }
        if self
            .last
            .is_some_and(|last| now.duration_since(last) < REDRAW)
        {
            return true;
        }
        self.last = Some(now);
        let line = format_line(stage, now.duration_since(self.started), fraction, figures);
        // A failed write to the terminal is no reason to stop the work.
        let _ = write!(self.out, "\r{line}\x1b[K");
        let _ = self.out.flush();
        self.drawn = true;
        true
    }

    /// For [`tilepattern::pipeline::tile_surface`], which reports the remesh stage as
    /// fractions `0..0.5` and the pattern stage as `0.5..1` (then the tiles at 1), and for
    /// its tries ([`ProgressLine::with_tries`]), each an equal share of `0..1` reported so:
    /// with more than one, the stage is named with its try (`pattern 2/3`).
    pub fn update_run(&mut self, fraction: f64, figures: Option<Figures>) -> bool {
        let tries = self.tries as f64;
        let scaled = fraction.clamp(0.0, 1.0) * tries;
        let mut k = (scaled.floor() as usize).min(self.tries - 1);
        let mut within = scaled - k as f64;
        // k / tries is both the end of try k - 1 (its tiles report all of its share, with
        // its figures) and the start of try k (whose figures the pipeline forgets).
        if within == 0.0 && k > 0 && figures.is_some() {
            k -= 1;
            within = 1.0;
        }
        let name = |stage: &str| {
            if self.tries > 1 {
                format!("{stage} {}/{}", k + 1, self.tries)
            } else {
                stage.to_string()
            }
        };
        if within < 0.5 {
            let stage = name("remesh");
            self.update(&stage, 2.0 * within, None)
        } else {
            let stage = name("pattern");
            self.update(&stage, 2.0 * within - 1.0, figures)
        }
    }

    /// Erases the line (if one was drawn; the log stays).
    pub fn finish(&mut self) {
        if self.drawn && self.log.is_none() {
            let _ = write!(self.out, "\r\x1b[K");
            let _ = self.out.flush();
            self.drawn = false;
        }
    }
}

/// `pattern  12.3 s  45 %  best 688.5  bound 691.5  gap 0.43 %` (figures only when known).
pub fn format_line(
    stage: &str,
    elapsed: Duration,
    fraction: f64,
    figures: Option<Figures>,
) -> String {
    let mut line = format!(
        "{stage:<7} {:>6.1} s {:>4.0} %",
        elapsed.as_secs_f64(),
        100.0 * fraction.clamp(0.0, 1.0)
    );
    if let Some(f) = figures {
        line.push_str(&format!(
            "  best {}  bound {}  gap {:.2} %",
            f.best,
            f.bound,
            100.0 * f.gap()
        ));
    }
    line
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_names_stage_time_share_and_figures() {
        let figures = Figures {
            best: 688.5,
            bound: 691.5,
        };
        let line = format_line(
            "pattern",
            Duration::from_millis(12_340),
            0.45,
            Some(figures),
        );
        assert_eq!(
            line,
            "pattern   12.3 s   45 %  best 688.5  bound 691.5  gap 0.43 %"
        );
        assert_eq!(
            format_line("remesh", Duration::from_secs(2), 0.5, None),
            "remesh     2.0 s   50 %"
        );
    }

    #[test]
    fn silent_when_not_a_terminal_and_erased_at_the_end() {
        let mut quiet = ProgressLine::new(Vec::new(), false);
        assert!(quiet.update("pattern", 0.5, None));
        quiet.finish();
        assert!(quiet.out.is_empty());

        let mut shown = ProgressLine::new(Vec::new(), true);
        assert!(shown.update_run(0.75, None));
        // Within the redraw interval nothing more is drawn.
        assert!(shown.update_run(0.8, None));
        shown.finish();
        let text = String::from_utf8(shown.out).unwrap();
        assert!(text.starts_with("\rpattern "), "{text:?}");
        assert!(text.contains("   50 %"), "{text:?}");
        assert_eq!(
            text.matches('\r').count(),
            2,
            "one draw, one erase: {text:?}"
        );
        assert!(text.ends_with("\r\x1b[K"));
    }

    #[test]
    fn tries_are_told_apart() {
        let mut log = ProgressLine::log(Vec::new()).with_tries(3);
        let figures = Some(Figures {
            best: 10.0,
            bound: 12.0,
        });
        assert!(log.update_run(0.0, None));
        assert!(log.update_run(0.1, None));
        assert!(log.update_run(0.3, figures));
        // The end of the first try, with its last figures.
        let proven = Some(Figures {
            best: 11.0,
            bound: 11.0,
        });
        assert!(log.update_run(1.0 / 3.0, proven));
        // The start of the second: no figures yet.
        assert!(log.update_run(1.0 / 3.0, None));
        assert!(log.update_run(0.4, None));
        assert!(log.update_run(0.9, figures));
        assert!(log.update_run(1.0, figures));
        let text = String::from_utf8(log.out).unwrap();
        let stages: Vec<&str> = text
            .lines()
            .map(|l| l.split("   ").next().unwrap().trim())
            .collect();
        assert_eq!(
            stages,
            [
                "remesh 1/3",
                "pattern 1/3",
                "pattern 1/3",
                "remesh 2/3",
                "pattern 3/3"
            ],
            "{text:?}"
        );
    }

    #[test]
    fn the_log_writes_a_line_per_stage_and_per_change_and_keeps_it() {
        let mut log = ProgressLine::log(Vec::new());
        let figures = |best, bound| Some(Figures { best, bound });
        assert!(log.update_run(0.1, None));
        // Within the heartbeat, the same stage and figures write nothing.
        assert!(log.update_run(0.2, None));
        assert!(log.update_run(0.6, figures(10.0, 12.0)));
        assert!(log.update_run(0.7, figures(10.0, 12.0)));
        assert!(log.update_run(0.8, figures(11.0, 12.0)));
        log.finish();
        let text = String::from_utf8(log.out).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3, "{text:?}");
        assert!(lines[0].starts_with("remesh "), "{text:?}");
        assert!(
            lines[1].contains("best 10  bound 12  gap 16.67 %"),
            "{text:?}"
        );
        assert!(
            lines[2].contains("best 11  bound 12  gap 8.33 %"),
            "{text:?}"
        );
        assert!(!text.contains('\r'), "nothing redrawn or erased: {text:?}");
    }
}

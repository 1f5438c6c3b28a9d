//! Progress of a run while it solves: a spinner line when stdout is a terminal, plain lines
//! on stderr every few seconds when it is not (logs, pipes), nothing with `--quiet`.

use crate::say::quiet;
use crate::say_err;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use piezocontact::algorithm::Progress;
use std::cell::Cell;
use std::io::IsTerminal;
use std::time::{Duration, Instant};

/// Shows the progress events of one run.
pub struct Reporter {
    /// The spinner on a terminal; `None` for plain lines or silence.
    bar: Option<ProgressBar>,
    /// Plain lines (not a terminal, not quiet).
    plain: bool,
    /// The inner method's name.
    method: &'static str,
    /// The current outer step and its cap.
    outer: Cell<(usize, usize)>,
    /// When the last plain line was written.
    last: Cell<Instant>,
    /// Time between two plain lines.
    interval: Duration,
}

impl Reporter {
    /// A reporter for a run of `method` ("uzawa" or "newton"), with plain lines at least
    /// `interval` apart (the first after `interval`).
    pub fn new(method: &'static str, interval: Duration) -> Self {
        let terminal = std::io::stdout().is_terminal();
        // Process 0 alone reports a run under mpirun.
        let shown = !quiet() && crate::processes::is_root();
        let bar = (terminal && shown).then(|| {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stdout());
            bar.set_style(
                ProgressStyle::with_template("{spinner} {elapsed} {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_spinner()),
            );
            bar.enable_steady_tick(Duration::from_millis(200));
            bar
        });
        Self {
            bar,
            plain: !terminal && shown,
            method,
            outer: Cell::new((0, 0)),
            last: Cell::new(Instant::now()),
            interval,
        }
    }

    /// Takes one event.
    pub fn event(&self, event: Progress) {
        if self.bar.is_none() && !self.plain {
            return;
        }
        let message = match event {
            Progress::Outer { step, max } => {
                self.outer.set((step, max));
                format!("outer step {step} (of at most {max})")
            }
            Progress::Inner { iteration, criterion, tolerance } => {
                let (step, max) = self.outer.get();
                let what = if self.method == "newton" { "Newton step" } else { "Uzawa iteration" };
                format!(
                    "outer step {step} (of at most {max}), {what} {iteration}: criterion {criterion:.2e} (stops below {tolerance:.1e})"
                )
            }
        };
        match &self.bar {
            Some(bar) => bar.set_message(message),
            None if self.last.get().elapsed() >= self.interval => {
                self.last.set(Instant::now());
                say_err!("progress: {message}");
            }
            None => {}
        }
    }
}

impl Drop for Reporter {
    fn drop(&mut self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

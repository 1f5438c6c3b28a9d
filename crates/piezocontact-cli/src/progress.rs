//! Progress of a run while it solves: a spinner line when stdout is a terminal, plain lines
//! on stderr every few seconds when it is not (logs, pipes), nothing with `--quiet`. A
//! factorisation, which sends no event while it runs, is shown with its elapsed time: the
//! spinner's line says how long it has run, and a ticker writes a plain line every interval
//! until the next event.

use crate::say::quiet;
use crate::say_err;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use piezocontact::algorithm::Progress;
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

/// What a factorisation in progress shows: its message and when it started; `done` ends the
/// ticker.
#[derive(Default)]
struct Factorising {
    current: Option<(String, Instant)>,
    done: bool,
}

/// The thread that shows a factorisation's elapsed time while no event comes.
struct Ticker {
    state: Arc<(Mutex<Factorising>, Condvar)>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Ticker {
    /// Every `interval`, shows the factorisation in progress on `bar` or as a plain line.
    fn new(bar: Option<ProgressBar>, interval: Duration) -> Self {
        let state = Arc::new((Mutex::new(Factorising::default()), Condvar::new()));
        let shared = Arc::clone(&state);
        let thread = std::thread::spawn(move || {
            let (lock, wake) = &*shared;
            let mut guard = lock.lock().unwrap_or_else(|e| e.into_inner());
            while !guard.done {
                guard = wake.wait_timeout(guard, interval).unwrap_or_else(|e| e.into_inner()).0;
                let Some((message, since)) = guard.current.as_ref().filter(|_| !guard.done) else {
                    continue;
                };
                let line = format!("{message}: {:.1} s so far", since.elapsed().as_secs_f64());
                match &bar {
                    Some(bar) => bar.set_message(line),
                    None => say_err!("progress: {line}"),
                }
            }
        });
        Self { state, thread: Some(thread) }
    }

    /// A factorisation starts (`Some`) or the one in progress ended (`None`).
    fn set(&self, current: Option<String>) {
        let mut guard = self.state.0.lock().unwrap_or_else(|e| e.into_inner());
        guard.current = current.map(|m| (m, Instant::now()));
    }
}

impl Drop for Ticker {
    fn drop(&mut self) {
        self.state.0.lock().unwrap_or_else(|e| e.into_inner()).done = true;
        self.state.1.notify_all();
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// Shows the progress events of one run.
pub struct Reporter {
    /// The spinner on a terminal; `None` for plain lines or silence.
    bar: Option<ProgressBar>,
    /// Plain lines (not a terminal, not quiet).
    plain: bool,
    /// The inner method's name.
    method: &'static str,
    /// The current outer step and its cap.
    outer: Mutex<(usize, usize)>,
    /// When the last plain line was written.
    last: Mutex<Instant>,
    /// Time between two plain lines.
    interval: Duration,
    /// Shows a factorisation in progress (on a terminal every second, else every interval).
    ticker: Option<Ticker>,
}

impl Reporter {
    /// A reporter for a run of `method` ("uzawa" or "newton"), with plain lines at least
    /// `interval` apart (the first after `interval`).
    pub fn new(method: &'static str, interval: Duration) -> Self {
        let terminal = crate::processes::watched(&std::io::stdout());
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
        let ticker = match (&bar, !terminal && shown) {
            (Some(bar), _) => Some(Ticker::new(Some(bar.clone()), Duration::from_secs(1))),
            (None, true) => Some(Ticker::new(None, interval.max(Duration::from_millis(50)))),
            (None, false) => None,
        };
        Self {
            bar,
            plain: !terminal && shown,
            method,
            outer: Mutex::new((0, 0)),
            last: Mutex::new(Instant::now()),
            interval,
            ticker,
        }
    }

    /// Takes one event.
    pub fn event(&self, event: Progress) {
        if self.bar.is_none() && !self.plain {
            return;
        }
        let factorising = match event {
            Progress::Factorising { unknowns } => {
                let (step, _) = read(&self.outer);
                Some(format!("outer step {step}: factorising B̌ ({unknowns} unknowns)"))
            }
            _ => None,
        };
        if let Some(ticker) = &self.ticker {
            ticker.set(factorising.clone());
        }
        let message = match event {
            Progress::Factorising { .. } => factorising.unwrap_or_default(),
            Progress::Outer { step, max } => {
                write(&self.outer, (step, max));
                format!("outer step {step} (of at most {max})")
            }
            Progress::Inner { iteration, criterion, tolerance } => {
                let (step, max) = read(&self.outer);
                let what = if self.method == "newton" { "Newton step" } else { "Uzawa iteration" };
                format!(
                    "outer step {step} (of at most {max}), {what} {iteration}: criterion {criterion:.2e} (stops below {tolerance:.1e})"
                )
            }
        };
        match &self.bar {
            Some(bar) => bar.set_message(message),
            None if read(&self.last).elapsed() >= self.interval => {
                write(&self.last, Instant::now());
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

/// The value in `cell` (a reporter is shared by the threads of a run; a poisoned lock
/// still holds a usable value).
fn read<T: Copy>(cell: &Mutex<T>) -> T {
    *cell.lock().unwrap_or_else(|e| e.into_inner())
}

/// Puts `value` in `cell`.
fn write<T>(cell: &Mutex<T>, value: T) {
    *cell.lock().unwrap_or_else(|e| e.into_inner()) = value;
}

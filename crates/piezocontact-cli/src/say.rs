//! Lines for the terminal that a reader who stops reading cannot turn into a panic.
//!
//! `println!` panics when stdout is a pipe whose reader has closed (`piezocontact mesh-info
//! FILE | head -n 1`). [`say!`](crate::say!) and [`say_err!`](crate::say_err!) write through
//! [`line()`] instead: the first failed write marks the stream closed and the rest of the
//! command's output to it is dropped, while the command carries on to its own exit code.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

/// Which stream a line goes to.
#[derive(Clone, Copy, Debug)]
pub enum Stream {
    /// Standard output: reports and tables.
    Out,
    /// Standard error: errors, warnings and progress.
    Err,
}

static CLOSED: [AtomicBool; 2] = [AtomicBool::new(false), AtomicBool::new(false)];
static QUIET: AtomicBool = AtomicBool::new(false);
static SILENT: AtomicBool = AtomicBool::new(false);

/// Drops every line from now on, to both streams (the processes but the first of a run
/// under mpirun, which report nothing; their errors go through [`crate::processes::fail`]).
pub fn set_silent() {
    SILENT.store(true, Ordering::Relaxed);
}

/// Drops the reports on stdout from now on (`--quiet`); errors still reach stderr.
pub fn set_quiet() {
    QUIET.store(true, Ordering::Relaxed);
}

/// Whether `--quiet` was given.
pub fn quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// Writes `args` and a newline to `stream`, unless it is closed (or stdout is quiet).
pub fn line(stream: Stream, args: std::fmt::Arguments) {
    let closed = &CLOSED[stream as usize];
    let dropped = SILENT.load(Ordering::Relaxed) || (matches!(stream, Stream::Out) && quiet());
    if closed.load(Ordering::Relaxed) || dropped {
        return;
    }
    let written = match stream {
        Stream::Out => {
            let mut out = std::io::stdout().lock();
            out.write_fmt(args).and_then(|()| out.write_all(b"\n")).and_then(|()| out.flush())
        }
        Stream::Err => {
            let mut err = std::io::stderr().lock();
            err.write_fmt(args).and_then(|()| err.write_all(b"\n"))
        }
    };
    if written.is_err() {
        closed.store(true, Ordering::Relaxed);
    }
}

/// `println!` that a closed stdout cannot make panic.
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => { $crate::say::line($crate::say::Stream::Out, format_args!($($arg)*)) };
}

/// `eprintln!` that a closed stderr cannot make panic.
#[macro_export]
macro_rules! say_err {
    ($($arg:tt)*) => { $crate::say::line($crate::say::Stream::Err, format_args!($($arg)*)) };
}

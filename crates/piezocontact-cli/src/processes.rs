//! The processes of a run under `mpirun` (the PETSc backend): every process runs the same
//! command on the same case; process 0 alone prints and writes; an error on any process ends
//! them all with one message.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

/// This process's rank and the number of processes, once [`start`] has run.
static RANK: AtomicUsize = AtomicUsize::new(0);
static SIZE: AtomicUsize = AtomicUsize::new(1);

/// The number of processes `mpirun` started, from Open MPI's environment (1 outside it).
fn launched() -> usize {
    std::env::var("OMPI_COMM_WORLD_SIZE").ok().and_then(|v| v.parse().ok()).unwrap_or(1)
}

/// Whether `stream` is a terminal someone watches, where a spinner or a bar may be drawn:
/// never under mpirun, whose processes each get a pseudo-terminal from Open MPI whether
/// mpirun's own output goes to a terminal or to a file (a log would get the spinner's
/// control sequences instead of plain progress lines).
pub fn watched(stream: &impl std::io::IsTerminal) -> bool {
    launched() == 1 && stream.is_terminal()
}

/// Starts PETSc (and MPI) when the command runs under mpirun or `petsc_options` are given,
/// so that every process knows its rank before it prints; silences the processes but the
/// first. Refuses mpirun and PETSc options in a build without the PETSc backend.
pub fn start(petsc_options: Option<&str>) -> anyhow::Result<()> {
    if launched() == 1 && petsc_options.is_none() {
        return Ok(());
    }
    let (rank, size) = initialize(petsc_options.unwrap_or(""))?;
    RANK.store(rank, Ordering::Relaxed);
    SIZE.store(size, Ordering::Relaxed);
    if rank != 0 {
        crate::say::set_silent();
    }
    if size > 1 {
        // A panic on one process ends the others too (they would wait for it).
        let report = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            report(info);
            abort(101);
        }));
    }
    Ok(())
}

#[cfg(feature = "petsc")]
fn initialize(options: &str) -> anyhow::Result<(usize, usize)> {
    use piezocontact::linalg::petsc;
    petsc::initialize(options)?;
    Ok(petsc::rank_and_size())
}

#[cfg(not(feature = "petsc"))]
fn initialize(_options: &str) -> anyhow::Result<(usize, usize)> {
    anyhow::bail!(
        "this piezocontact is built without the PETSc backend, which runs under mpirun and reads --petsc-options (each process would repeat the whole run): build it with cargo build --release --features petsc (Debian packages petsc-dev and openmpi-bin), or run without mpirun"
    )
}

/// Catches SIGINT and SIGTERM: the first asks the runs to stop at their next safe point
/// ([`piezocontact::interrupt`]), which write what they have and exit 128 + the signal
/// (130, 143); a second signal ends the process at once with that code.
pub fn catch_signals() -> anyhow::Result<()> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    for signal in [SIGINT, SIGTERM] {
        let action = move || {
            if !piezocontact::interrupt::request(signal) {
                signal_hook::low_level::exit(128 + signal);
            }
        };
        // SAFETY: the action is async-signal-safe: one atomic operation, then `_exit`.
        unsafe { signal_hook::low_level::register(signal, action) }?;
    }
    Ok(())
}

/// Whether this process prints and writes (process 0, or the only one).
pub fn is_root() -> bool {
    RANK.load(Ordering::Relaxed) == 0
}

/// The number of processes of the run.
pub fn size() -> usize {
    SIZE.load(Ordering::Relaxed)
}

/// Ends the command after an error: alone, with `code`; under mpirun, every process (the
/// others may wait for this one). Process 0 prints `message`; another process waits a
/// moment first, so that when every process fails alike, process 0's message is the one.
pub fn fail(message: &str, code: u8) -> std::process::ExitCode {
    if size() == 1 {
        crate::say_err!("{message}");
        return std::process::ExitCode::from(code);
    }
    let rank = RANK.load(Ordering::Relaxed);
    if rank != 0 {
        std::thread::sleep(Duration::from_secs(2));
    }
    eprintln!("{message} (process {rank} of {})", size());
    abort(i32::from(code))
}

#[cfg(feature = "petsc")]
fn abort(code: i32) -> ! {
    piezocontact::linalg::petsc::abort(code)
}

#[cfg(not(feature = "petsc"))]
fn abort(code: i32) -> ! {
    std::process::exit(code)
}

//! The `piezocontact` command: parses arguments, reads cases, reports, writes files. All
//! numerics live in the `piezocontact` library.

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use piezocontact::algorithm::ContactSolver;
use piezocontact::case::{Built, Case};
use piezocontact::dofs::DofMap;
use piezocontact::mesh::gmsh;
use piezocontact::output::files as output;
use piezocontact::output::vtu::Encoding;
use piezocontact::report::summary::refusal_summary;
use piezocontact::run::{Run, StepFiles};
use piezocontact_cli::progress::Reporter;
use piezocontact_cli::{bench, print, processes, reproduce, sweep};
use piezocontact_cli::{say, say_err};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

/// Static contact of a piezoelectric body with a foundation: P1 finite elements.
#[derive(Parser)]
#[command(name = "piezocontact", version, about)]
struct Cli {
    /// More log output (-v info, -vv debug); RUST_LOG overrides.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    verbose: u8,
    /// No progress and no report on stdout; errors and warnings still go to stderr.
    #[arg(short, long, global = true)]
    quiet: bool,
    /// The most threads the command uses (assembly, factorisation, solves, parallel runs);
    /// default: the environment's PIEZOCONTACT_THREADS, else every core.
    #[arg(long, global = true, value_name = "N")]
    threads: Option<std::num::NonZeroUsize>,
    /// Options for PETSc's options database (solver.backend = "petsc"), in PETSc's syntax,
    /// e.g. "-mat_mumps_icntl_14 60 -mat_mumps_icntl_4 2".
    #[arg(long, global = true, value_name = "OPTIONS", allow_hyphen_values = true)]
    petsc_options: Option<String>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a case and write DIR/summary.json and DIR/solution.vtu.
    Run {
        /// The case file (TOML).
        case: PathBuf,
        /// Output directory (created if needed).
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Override a case key, e.g. --set mesh.nx=192 (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Write into an output directory that holds files piezocontact did not write.
        #[arg(long)]
        force: bool,
        /// Seconds between two plain progress lines when stdout is not a terminal (or under
        /// mpirun).
        #[arg(long, default_value = "5", value_name = "SECONDS", value_parser = parse_seconds)]
        progress_interval: Duration,
        /// How solution.vtu and a path's series hold their numbers: ParaView's binary
        /// encoding (appended raw data), or ascii text (readable, several times larger).
        #[arg(long, value_enum, default_value = "binary")]
        vtu: VtuEncoding,
    },
    /// Run a case once per value of swept keys, in parallel; write DIR/sweep.csv.
    Sweep {
        /// The case file (TOML).
        case: PathBuf,
        /// Keys and values: KEY[=KEY...]=V1,V2,... (every key takes each value), e.g.
        /// friction.mu=conductivity.ke=0.6,0.2,6.8e-2; a value may be an array or a table,
        /// loads.f0=[0.0,0.0],[0.0,-1.0].
        #[arg(long = "set-list", value_name = "KEYS=VALUES")]
        set_list: String,
        /// Override a case key in every run (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Overrides that turn the case into the reference run for ‖x − x_ref‖_X, e.g.
        /// --reference contact.problem=PV1 (repeatable).
        #[arg(long, value_name = "KEY=VALUE")]
        reference: Vec<String>,
        /// Runs in parallel (default: the number of cores).
        #[arg(long)]
        jobs: Option<std::num::NonZeroUsize>,
        /// Output directory.
        #[arg(long, default_value = "out/sweep")]
        out: PathBuf,
        /// Write into an output directory that holds files piezocontact did not write.
        #[arg(long)]
        force: bool,
    },
    /// Regenerate the paper's Section 7: Examples 7.1–7.2, Table 2, Figures 1–4, with a
    /// Theorem 4.1 study, a mesh study, a stopping-rule study and DIR/REPORT.md.
    Reproduce {
        /// Output directory.
        #[arg(long, default_value = "out/reproduce")]
        out: PathBuf,
        /// Base mesh NX,NY (the studies also use 2× and 4×).
        #[arg(long, default_value = "96,16", value_parser = parse_mesh)]
        mesh: (usize, usize),
        /// Runs in parallel (default: the number of cores).
        #[arg(long)]
        jobs: Option<std::num::NonZeroUsize>,
        /// Write into an output directory that holds files piezocontact did not write.
        #[arg(long)]
        force: bool,
    },
    /// Validate a case and print its mesh and DOF summary.
    Check {
        /// The case file (TOML).
        case: PathBuf,
        /// Override a case key (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
    },
    /// List the material library: each preset's constants in its source's form, in SI, with
    /// the source; a case names one with `preset = "NAME"` in its material table.
    Materials,
    /// Print what a Gmsh MSH 4.1 file holds, or why it cannot be read; exits 1 when the file
    /// cannot be used as a mesh.
    MeshInfo {
        /// The .msh file.
        file: PathBuf,
    },
    /// Time assembly, symbolic analysis, numeric factorisation and solve on the paper's
    /// rectangle at several mesh sizes, or on a Gmsh mesh, beside faer's bare LDLᵀ.
    Bench(BenchArgs),
}

/// The options of `bench`.
#[derive(clap::Args)]
struct BenchArgs {
    /// Mesh sizes NXxNY, comma separated (default 96x16,384x64,1536x256; with
    /// --contact 96x16,192x32,384x64,768x128).
    #[arg(long, value_delimiter = ',')]
    sizes: Option<Vec<String>>,
    /// A Gmsh MSH 4.1 mesh (2D or 3D) instead of the rectangle: every boundary part is
    /// clamped and grounded; with --contact, a mesh with the parts of
    /// meshes/indent-3d.geo, run as cases/indentation-3d.toml.
    #[arg(long, conflicts_with = "sizes")]
    mesh: Option<PathBuf>,
    /// Also time faer's sparse LU on the same matrices, for comparison.
    #[arg(long)]
    lu: bool,
    /// The fill-reducing orderings to measure, comma separated: amd, nd (METIS's nested
    /// dissection), auto (nested dissection in 3D; in 2D AMD, or nested dissection from 100k
    /// unknowns on a numbering without locality). Each runs on 1 thread and on all.
    #[arg(long, value_delimiter = ',', default_value = "amd,nd", value_parser = bench::factorisation::parse_ordering, conflicts_with = "contact")]
    ordering: Vec<piezocontact::linalg::Ordering>,
    /// Time the exact contact solver (newton) on PV1 and PV2 (µ = k_e = 0.2, 0.6) of the
    /// paper's bar against one plain factorisation of the same mesh, each in a process of
    /// its own to measure its peak memory.
    #[arg(long, conflicts_with = "lu")]
    contact: bool,
    /// With --contact: a contact case (a .toml file) instead, run as PV1 and as PV2 with
    /// µ = 0.3, e.g. cases/block-3d.toml (a block whose whole bottom face touches) or
    /// cases/bar-3d.toml (a bar bent onto a plane along part of its bottom face); with
    /// --path: the case whose loading path is timed.
    #[arg(long, conflicts_with = "sizes")]
    case: Option<PathBuf>,
    /// Time a loading path (each step from the last, the factorisation kept) against the
    /// same steps solved cold, in the same run: the path of --case (default
    /// cases/indentation-curve.toml), --mesh replacing its mesh.
    #[arg(long, conflicts_with_all = ["contact", "lu", "sizes"])]
    path: bool,
    /// The linear-solver backend to time on --mesh: "faer" (default) or "petsc" (PETSc +
    /// MUMPS on the processes of mpirun, beside faer's in the same run; a build with the
    /// feature `petsc`).
    /// With --contact: the exact solver on the 3D indentation of --mesh by each route of
    /// --linear.
    #[arg(long, default_value = "faer", value_parser = ["faer", "petsc"], requires = "mesh", conflicts_with_all = ["path", "lu"])]
    backend: String,
    /// With --backend petsc: the routes to time, comma separated: "direct" (MUMPS's LDLᵀ)
    /// and "iterative" (GMRES with a field split and GAMG, as solver.linear = "iterative";
    /// on a mesh with the parts of meshes/indent-3d.geo, whose contact patch is pressed
    /// down). faer's row goes with "direct".
    #[arg(long, value_delimiter = ',', default_value = "direct", value_parser = ["direct", "iterative"])]
    linear: Vec<String>,
    /// Time the assembly of B̌ on --mesh (default meshes/block-100k.msh) with one material
    /// and with four by region (the quadrants of its bounding box), the median of 5
    /// interleaved runs of each.
    #[arg(long, conflicts_with_all = ["contact", "path", "lu", "sizes", "case"])]
    materials: bool,
    /// Time the quarter model (cases/indentation-quarter.toml) on --mesh (default
    /// meshes/indent-quarter-h0.015.msh) against the whole block on its mirror (the same name
    /// with "full"), and on the quarter the numeric factorisation held by a clamp at the bottom
    /// against the same held by rollers: factor entries and time per entry, the median of 5
    /// interleaved runs of each.
    #[arg(long, conflicts_with_all = ["contact", "path", "lu", "sizes", "case", "materials"])]
    quarter: bool,
    /// Time the ball indentation of PZT-5A in 3D (meshes/indent-halfspace-fine.msh) and as a
    /// body of revolution (meshes/indent-axisym-h0.01.msh): forces against Hertz with C*, and
    /// the wall times, the median of 3 interleaved runs of each.
    #[arg(long, conflicts_with_all = ["contact", "path", "lu", "sizes", "case", "materials", "quarter", "mesh"])]
    axisym: bool,
    /// Time the 3D indentation (cases/indentation-3d.toml, on --mesh if given) with its top
    /// face an electrode at 0 V against the same face floating: factor entries, numeric
    /// factorisation and the exact solver's wall time, the median of 5 interleaved runs.
    #[arg(long, conflicts_with_all = ["contact", "path", "lu", "sizes", "case", "materials", "quarter", "axisym"])]
    floating: bool,
    /// One measurement of --contact (internal).
    #[arg(long, hide = true)]
    one: Option<String>,
}

/// Parses a number of seconds ≥ 0.
fn parse_seconds(s: &str) -> Result<Duration, String> {
    let bad = || format!("'{s}' is not a number of seconds ≥ 0, e.g. 5 or 0.5");
    s.trim().parse::<f64>().ok().and_then(|v| Duration::try_from_secs_f64(v).ok()).ok_or_else(bad)
}

/// Parses `NX,NY`.
fn parse_mesh(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("'{s}' is not NX,NY with NX, NY ≥ 1, e.g. 96,16");
    let (a, b) = s.split_once(',').ok_or_else(bad)?;
    let (nx, ny) = (
        a.trim().parse::<usize>().map_err(|_| bad())?,
        b.trim().parse::<usize>().map_err(|_| bad())?,
    );
    if nx == 0 || ny == 0 {
        return Err(bad());
    }
    Ok((nx, ny))
}

fn main() -> ExitCode {
    // summary.json's total counts from here: the process's wall time.
    let began = Instant::now();
    let cli = Cli::parse();
    let level = ["warn", "info", "debug"][usize::from(cli.verbose.min(2))];
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or(level)).init();
    if cli.quiet {
        piezocontact_cli::say::set_quiet();
    }
    if let Err(e) = set_threads(cli.threads) {
        return processes::fail(&format!("error: {e:#}"), 1);
    }
    // The command runs on a thread of the pool: faer's and the assembly's parallel calls then
    // run in place instead of each being handed to the pool from outside and waited for (a
    // wake-up and a sleep per call, a quarter of a 3D factorisation's time on one thread).
    // PETSc and MPI start on that thread, which makes every call to them.
    rayon::scope(|_| {
        let started = processes::start(cli.petsc_options.as_deref()).and_then(|_| {
            // Under mpirun, mpirun forwards signals to every process, which stop alike.
            processes::catch_signals()
        });
        if let Err(e) = started {
            return processes::fail(&format!("error: {e:#}"), 1);
        }
        match run(cli.command, began) {
            Ok(Outcome::Done) => ExitCode::SUCCESS,
            Ok(Outcome::NotConverged) => ExitCode::from(3),
            Ok(Outcome::Failed) => ExitCode::from(4),
            Ok(Outcome::Interrupted(signal)) => ExitCode::from((128 + signal) as u8),
            Err(e) => processes::fail(&format!("error: {e:#}"), 1),
        }
    })
}

fn run(command: Command, started: Instant) -> Result<Outcome> {
    match command {
        Command::Run { case, out, set, force, progress_interval, vtu } => {
            let _claim = processes::is_root().then(|| claim(&out, force)).transpose()?;
            run_case((&case, started), (&out, vtu.into()), &set, progress_interval)
        }
        Command::Sweep { case, set_list, set, reference, jobs, out, force } => {
            one_process("sweep")?;
            let _claim = claim(&out, force)?;
            let request = sweep::SweepRequest {
                case: &case,
                set_list: &set_list,
                set: &set,
                reference: &reference,
                jobs,
                out: &out,
            };
            let converged = sweep::sweep(&request)?;
            Ok(interrupted().unwrap_or(if converged {
                Outcome::Done
            } else {
                Outcome::NotConverged
            }))
        }
        Command::Reproduce { out, mesh, jobs, force } => {
            one_process("reproduce")?;
            let _claim = claim(&out, force)?;
            let converged =
                reproduce::reproduce(&reproduce::Request { out: out.clone(), mesh, jobs })?;
            say!("wrote {} with its figures and tables", out.join("REPORT.md").display());
            Ok(interrupted().unwrap_or(if converged {
                Outcome::Done
            } else {
                Outcome::NotConverged
            }))
        }
        Command::Check { case, set } => check(&case, &set).map(|_| Outcome::Done),
        Command::MeshInfo { file } => mesh_info(&file).map(|_| Outcome::Done),
        Command::Materials => {
            print::presets();
            Ok(Outcome::Done)
        }
        Command::Bench(args) => bench_command(args),
    }
}

/// `bench`: the measurement its options choose.
fn bench_command(args: BenchArgs) -> Result<Outcome> {
    let BenchArgs {
        sizes,
        mesh,
        lu,
        contact,
        case,
        path,
        materials,
        quarter,
        axisym,
        floating,
        one,
        ordering,
        backend,
        linear,
    } = args;
    if let Some(spec) = one {
        return bench::one::measure_one(&spec).map(|_| Outcome::Done);
    }
    if materials {
        let mesh = mesh.unwrap_or_else(|| PathBuf::from("meshes/block-100k.msh"));
        return bench::materials::run(&mesh).map(|_| Outcome::Done);
    }
    if axisym {
        return bench::axisym::run().map(|_| Outcome::Done);
    }
    if floating {
        return bench::electrodes::run(mesh.as_deref()).map(|_| Outcome::Done);
    }
    if quarter {
        let mesh = mesh.unwrap_or_else(|| PathBuf::from("meshes/indent-quarter-h0.015.msh"));
        return bench::quarter::run(&mesh).map(|_| Outcome::Done);
    }
    if backend == "petsc" {
        return bench_backend(mesh.as_deref(), &linear, contact).map(|_| Outcome::Done);
    }
    if linear != ["direct"] {
        anyhow::bail!("--linear goes with --backend petsc (the routes of the PETSc backend)");
    }
    if path {
        let case = case.unwrap_or_else(|| PathBuf::from("cases/indentation-curve.toml"));
        return bench::path::path(&case, mesh.as_deref()).map(|_| Outcome::Done);
    }
    if case.is_some() && !contact {
        anyhow::bail!("--case goes with --contact (a case's mesh) or --path (with --mesh)");
    }
    if case.is_some() && mesh.is_some() {
        anyhow::bail!(
            "bench --contact takes its mesh from --case or from --mesh, not both: drop one"
        );
    }
    if contact {
        return bench_contact(case.as_deref(), mesh.as_deref(), sizes).map(|_| Outcome::Done);
    }
    let sizes = sizes.unwrap_or_else(|| bench::factorisation::SIZES.map(String::from).to_vec());
    let target = match &mesh {
        Some(path) => bench::factorisation::Target::Mesh(path),
        None => bench::factorisation::Target::Sizes(&sizes),
    };
    let all = rayon::current_num_threads();
    let threads = if all > 1 { vec![1, all] } else { vec![1] };
    let variants = bench::factorisation::Variants { orderings: ordering, threads };
    bench::factorisation::run(&target, &variants, lu).map(|_| Outcome::Done)
}

/// `bench --contact`: on the case's mesh, on one mesh file, or on a list of sizes.
fn bench_contact(
    case: Option<&Path>,
    mesh: Option<&Path>,
    sizes: Option<Vec<String>>,
) -> Result<()> {
    let targets = match (mesh, sizes) {
        _ if case.is_some() => case.map(bench::contact::case_target).into_iter().collect(),
        (Some(path), _) => vec![path.display().to_string()],
        (None, Some(sizes)) => sizes,
        (None, None) => bench::contact::CONTACT_SIZES.map(String::from).to_vec(),
    };
    bench::contact::contact(&targets)
}

/// `bench [--contact] --mesh FILE --backend petsc [--linear ROUTES]`.
#[cfg(feature = "petsc")]
fn bench_backend(mesh: Option<&Path>, linear: &[String], contact: bool) -> Result<()> {
    let mesh = mesh.ok_or_else(|| anyhow::anyhow!("--backend petsc needs --mesh FILE"))?;
    match contact {
        true => bench::petsc_contact::run(mesh, linear),
        false => bench::petsc::run(mesh, linear),
    }
}

#[cfg(not(feature = "petsc"))]
fn bench_backend(_mesh: Option<&Path>, _linear: &[String], _contact: bool) -> Result<()> {
    anyhow::bail!(
        "--backend petsc needs piezocontact built with the PETSc backend: cargo build --release --features petsc (Debian packages petsc-dev and openmpi-bin)"
    )
}

/// Refuses a command that runs its cases in parallel on one machine under mpirun.
fn one_process(command: &str) -> Result<()> {
    if processes::size() > 1 {
        anyhow::bail!(
            "{command} runs its cases in parallel on this machine: run it without mpirun (mpirun goes with run, check and bench)"
        );
    }
    Ok(())
}

/// Claims the output directory; a foreign directory's error names the command's options.
fn claim(out: &Path, force: bool) -> Result<output::Claimed> {
    output::Claimed::new(out, force).map_err(|e| match e {
        piezocontact::Error::ForeignOutput { .. } => {
            anyhow::anyhow!("{e}: choose another --out, or pass --force to write there anyway")
        }
        e => e.into(),
    })
}

/// How a command ended, when it did not fail outright.
enum Outcome {
    /// Everything converged.
    Done,
    /// A loop hit its cap: results were written, marked unconverged.
    NotConverged,
    /// A loop diverged or failed numerically: the last finite iterate was written.
    Failed,
    /// A signal asked the run to stop: what it had was written; exit 128 + the signal.
    Interrupted(i32),
}

/// The environment variable that bounds the threads when --threads is not given.
const THREADS_VAR: &str = "PIEZOCONTACT_THREADS";

/// The stack of each thread of the pool the command runs on: that of a main thread.
const STACK_BYTES: usize = 8 << 20;

/// Starts rayon's global pool, which the command and faer's parallel factorisation and solves
/// run on, with `--threads` or PIEZOCONTACT_THREADS threads (every core without either).
fn set_threads(threads: Option<std::num::NonZeroUsize>) -> Result<()> {
    let threads = match (threads, std::env::var(THREADS_VAR)) {
        (Some(n), _) => n.get(),
        (None, Ok(value)) => value.trim().parse::<std::num::NonZeroUsize>().map_err(|_| {
            anyhow::anyhow!("{THREADS_VAR}={value:?} is not a number of threads ≥ 1: set it to e.g. 2, or unset it")
        })?.get(),
        (None, Err(_)) => 0,
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .stack_size(STACK_BYTES)
        .build_global()
        .map_err(|e| anyhow::anyhow!("cannot start {threads} threads: {e}"))
}

/// A signal's outcome when one asked the runs to stop (their results written, unconverged).
fn interrupted() -> Option<Outcome> {
    piezocontact::interrupt::requested().map(Outcome::Interrupted)
}

/// The outcome of a run that stopped with `failure`.
fn failed(failure: &piezocontact::Error) -> Outcome {
    match failure {
        piezocontact::Error::NotConverged { .. } => Outcome::NotConverged,
        piezocontact::Error::Interrupted { signal } => Outcome::Interrupted(*signal),
        _ => Outcome::Failed,
    }
}

/// The encodings of `run --vtu`.
#[derive(Clone, Copy, clap::ValueEnum)]
enum VtuEncoding {
    Binary,
    Ascii,
}

impl From<VtuEncoding> for Encoding {
    fn from(encoding: VtuEncoding) -> Self {
        match encoding {
            VtuEncoding::Binary => Encoding::Binary,
            VtuEncoding::Ascii => Encoding::Ascii,
        }
    }
}

fn run_case(
    (path, started): (&Path, Instant),
    (out, vtu): (&Path, Encoding),
    set: &[String],
    interval: Duration,
) -> Result<Outcome> {
    let case = Case::load(path, set)?;
    // The keys nothing reads, segment ends between nodes; the paper's hypotheses are check's
    // and summary.json's.
    for warning in case.setting_warnings() {
        say_err!("warning: {warning}");
    }
    let built = Built { started, ..case.build()? };
    let reporter = Reporter::new(built.method_name(), interval);
    let progress = |event| reporter.event(event);
    // A path's steps are written while the next one solves, by the process that writes.
    let files = processes::is_root().then_some(StepFiles { dir: out, vtu });
    let solved = built
        .linear_solver()
        .and_then(|solver| Run::solve_writing(&built, (solver, &progress), files));
    drop(reporter);
    let run = solved.map_err(|e| refused(&built, out, e))?;
    let summary = processes::is_root().then(|| run.write(&built, out, vtu)).transpose()?;
    print::run(&run, &built, out);
    if let Some(summary) = summary.filter(|_| log::log_enabled!(log::Level::Info)) {
        print::timings(&summary);
    }
    let Some(failure) = run.failure() else { return Ok(Outcome::Done) };
    say_err!(
        "error: {}: {failure}; {} in {} (marked \"converged\": false)",
        built.origin.path.display(),
        run.kept(),
        out.display()
    );
    Ok(run.error().map_or(Outcome::Failed, failed))
}

/// The error of a contact case that the solver refused after validation (memory, a
/// capability), with summary.json written to say so.
fn refused(built: &Built, out: &Path, e: piezocontact::Error) -> anyhow::Error {
    if built.model.is_none() || !processes::is_root() {
        return e.into();
    }
    match output::write_summary(out, &refusal_summary(built, &e)) {
        Ok(()) => e.into(),
        Err(written) => written.into(),
    }
}

fn check(path: &Path, set: &[String]) -> Result<()> {
    let case = Case::load(path, set)?;
    let built = case.build()?;
    say!("{}: valid", path.display());
    print::mesh(&built);
    print::material(&built)?;
    // The model a run sets up with: its first step's on a loading path.
    let first = built.model.as_ref().map(|m| match &built.loading {
        Some(l) => l.at_first(m),
        None => m.clone(),
    });
    print_memory_prediction(&built, first.as_ref())?;
    if let Some(model) = &built.model {
        say!("problem: {:?}, foundation: {:?}", case.problem_kind(), model.foundation);
    }
    if let Some(loading) = &built.loading {
        print::loading(loading, built.problem.mesh.dim(), &built.units);
    }
    piezocontact_cli::sheet::data_sheets(&case, &built)?;
    for warning in &built.warnings {
        say!("warning: {warning}");
    }
    if let Some(note) = case.uniqueness_note() {
        say!("note: {note}");
    }
    let settings = case.contact_settings()?;
    if built.model.is_none() {
        say!(
            "solver: no contact, so one direct solve per load factor (with secant steps while Hencky's law is not met); the contact methods' settings are not used"
        );
        return Ok(());
    }
    say!("contact and solver settings (in the case's units):");
    for (key, value) in settings {
        say!("  {key:<22} = {value}");
    }
    Ok(())
}

/// The symbolic analysis a run makes first (with a contact model, the exact solver's
/// condensed Γ3 unknowns ordered last) and what it predicts: the factor's entries and the
/// bytes of a numeric factorisation, the exact solver's dense matrices, against the memory
/// available (a run that does not fit is refused here, as by `run`, with both numbers).
fn print_memory_prediction(
    built: &Built,
    model: Option<&piezocontact::contact::ContactModel>,
) -> Result<()> {
    use piezocontact::limits::{available_memory, bytes_text};
    let (problem, solver) = (&built.problem, built.linear_solver()?);
    let (stats, dense_bytes, nodes) = match model {
        Some(model) => {
            ContactSolver::new(problem, model, &built.settings, solver)?.predicted_memory()
        }
        None => {
            let dofs = DofMap::new(problem)?;
            let system = piezocontact::system::CoupledSystem::new(problem, dofs, &[], solver)?;
            (system.solver_stats(), 0.0, 0)
        }
    };
    if stats.factor_bytes > 0.0 {
        say!(
            "factor: {} entries ({} ordering), about {} and {:.1} Gflop for the factorisation; {} available",
            stats.factor_len,
            stats.ordering,
            bytes_text(stats.factor_bytes),
            stats.factor_flops * 1e-9,
            bytes_text(available_memory())
        );
    } else {
        say!("factor: predicted by the backend's analysis at the first factorisation");
    }
    if nodes > 0 {
        say!(
            "dense: {} for the exact solver's condensed problem ({nodes} Γ3 nodes at first; more if the contact zone grows)",
            bytes_text(dense_bytes)
        );
    }
    Ok(())
}

fn mesh_info(path: &Path) -> Result<()> {
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    let info = gmsh::inspect(&bytes).map_err(|e| {
        let case = path.extension().is_some_and(|x| x == "toml");
        let hint = if case { " (a case file: `piezocontact check` prints its mesh)" } else { "" };
        anyhow::anyhow!("{}: {e}{hint}", path.display())
    })?;
    say!("{}: MSH 4.1 {}", path.display(), if info.binary { "binary" } else { "ASCII" });
    say!("nodes: {}", info.nodes);
    say!("elements:");
    for (name, dim, count) in &info.elements {
        say!("  dim {dim}  {name:<6} {count:>8}");
    }
    say!("physical groups:");
    if info.groups.is_empty() {
        say!("  (none: piezocontact needs named boundary parts)");
    }
    for g in &info.groups {
        say!(
            "  dim {}  tag {:<4} {:<20} {:>8} elements",
            g.dim,
            g.tag,
            format!("\"{}\"", g.name),
            g.elements
        );
    }
    match gmsh::read(&bytes) {
        Ok(mesh) => say!(
            "usable: yes ({}D, {} nodes, {} cells)",
            mesh.dim(),
            mesh.n_nodes(),
            mesh.n_cells()
        ),
        Err(e) => {
            say!("usable: no: {e}");
            anyhow::bail!("{} cannot be used as a mesh: {e}", path.display());
        }
    }
    Ok(())
}

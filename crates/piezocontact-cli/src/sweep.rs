//! `piezocontact sweep`: one run per value of a swept key, in parallel, with a progress bar
//! on a terminal and plain lines otherwise; DIR/sweep.csv holds one row per run.

use crate::{say, say_err};
use anyhow::{Context, Result, anyhow, bail};
use indicatif::{ProgressBar, ProgressStyle};
use piezocontact::case::{Built, Case};
use piezocontact::output::files::write_atomic;
use piezocontact::output::vtu::Encoding;
use piezocontact::report::csv_number;
use piezocontact::run::{ContactRun, Run};
use rayon::prelude::*;
use std::fmt::Write;
use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};

/// A run to do: a label for messages, the case, and where to write its files.
pub struct Job {
    pub label: String,
    pub case: Case,
    pub out: Option<PathBuf>,
}

/// A job's contact run with the case it solved, built.
pub struct Solved {
    /// The case, built.
    pub built: Built,
    /// Its contact run.
    pub run: ContactRun,
}

/// Runs the jobs on `threads` threads and returns the runs in the jobs' order; the first
/// job that fails fails them all, and the jobs not started by then are not run.
pub fn run_jobs(jobs: Vec<Job>, threads: usize) -> Result<Vec<Solved>> {
    let (mut runs, mut first_error, mut skipped) = (Vec::new(), None, false);
    for result in run_until(jobs, threads, true) {
        match result {
            Ok(run) => runs.push(run),
            Err(Some(error)) => first_error = first_error.or(Some(error)),
            Err(None) => skipped = true,
        }
    }
    match first_error {
        Some(error) => Err(error),
        None if skipped => Err(anyhow!("a job was not run")),
        None => Ok(runs),
    }
}

/// Runs the jobs on `threads` threads and returns each one's run or error, in the jobs'
/// order.
pub fn run_each(jobs: Vec<Job>, threads: usize) -> Vec<Result<Solved>> {
    let results = run_until(jobs, threads, false);
    results.into_iter().map(|r| r.map_err(|e| e.unwrap_or_else(|| anyhow!("not run")))).collect()
}

/// Runs the jobs on `threads` threads and returns each one's run, or its error, or `None`
/// for a job not run because another had failed (with `stop_at_failure`), in the jobs' order.
fn run_until(
    jobs: Vec<Job>,
    threads: usize,
    stop_at_failure: bool,
) -> Vec<std::result::Result<Solved, Option<anyhow::Error>>> {
    let pool = match rayon::ThreadPoolBuilder::new().num_threads(threads.max(1)).build() {
        Ok(pool) => pool,
        Err(e) => return jobs.iter().map(|_| Err(Some(anyhow!("thread pool: {e}")))).collect(),
    };
    let total = jobs.len();
    // Progress: a bar on a terminal, else a line per run; nothing with --quiet.
    let shown = !crate::say::quiet();
    let bar = (shown && crate::processes::watched(&std::io::stderr())).then(|| {
        let bar = ProgressBar::new(total as u64);
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} runs, {elapsed} {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        bar
    });
    let done = std::sync::atomic::AtomicUsize::new(0);
    let failed = std::sync::atomic::AtomicBool::new(false);
    let results = pool.install(|| {
        jobs.par_iter()
            .map(|job| {
                if stop_at_failure && failed.load(std::sync::atomic::Ordering::SeqCst) {
                    return Err(None);
                }
                let run = solve_job(job);
                let k = done.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
                let line = match &run {
                    Ok(Solved { run, .. }) => format!(
                        "{}: {} outer iterations, {}, {:.2} s",
                        job.label,
                        run.solution.outer_iterations(),
                        if run.solution.converged() { "converged" } else { "NOT converged" },
                        run.seconds
                    ),
                    Err(_) => {
                        failed.store(true, std::sync::atomic::Ordering::SeqCst);
                        let stop = if stop_at_failure { "; no further runs start" } else { "" };
                        format!("{}: failed{stop}", job.label)
                    }
                };
                match &bar {
                    Some(bar) => {
                        bar.inc(1);
                        bar.set_message(line);
                    }
                    None if shown => say_err!("[{k}/{total}] {line}"),
                    None => {}
                }
                run.map_err(Some)
            })
            .collect()
    });
    if let Some(bar) = bar {
        bar.finish();
    }
    results
}

/// Solves a job and writes its files.
fn solve_job(job: &Job) -> Result<Solved> {
    let solved = solve_contact(&job.case).with_context(|| format!("run {}", job.label))?;
    if let Some(out) = &job.out {
        solved.run.write(&solved.built, out, Encoding::default())?;
    }
    Ok(solved)
}

/// Builds and solves a case with contact and without a loading path, on the case's own linear
/// solver.
pub fn solve_contact(case: &Case) -> piezocontact::Result<Solved> {
    case.one_position()?;
    let built = case.build()?;
    match Run::solve(&built, built.linear_solver()?, &|_| {})? {
        Run::Contact(run) => Ok(Solved { built, run }),
        _ => Err(piezocontact::Error::Input(format!(
            "{}: the case has no [contact] table",
            case.path().display()
        ))),
    }
}

/// The number of threads: `--jobs`, or the machine's cores.
pub fn threads(jobs: Option<NonZeroUsize>) -> usize {
    jobs.or_else(|| std::thread::available_parallelism().ok()).map_or(1, NonZeroUsize::get)
}

/// Parses `key1=key2=...=v1,v2,...`. The `=` and `,` inside a value — an array
/// `[0.0,-1.0]`, a table `{eps=1e-6}`, a quoted string — do not split it.
pub fn parse_set_list(spec: &str) -> Result<(Vec<String>, Vec<String>)> {
    let usage = || {
        anyhow!(
            "--set-list {spec}: expected KEY[=KEY...]=V1,V2,..., e.g. friction.mu=conductivity.ke=0.6,0.2"
        )
    };
    let mut keys = split_top_level(spec, '=');
    let values = keys.pop().filter(|_| !keys.is_empty()).ok_or_else(usage)?;
    let keys: Vec<String> = keys.iter().map(|k| k.trim().to_string()).collect();
    let values: Vec<String> = split_top_level(values, ',')
        .into_iter()
        .map(|v| v.trim().to_string())
        .filter(|v| !v.is_empty())
        .collect();
    if keys.iter().any(|k| k.is_empty()) || values.is_empty() {
        return Err(usage());
    }
    Ok((keys, values))
}

/// `text` split at each `separator` outside brackets, braces and quoted strings.
fn split_top_level(text: &str, separator: char) -> Vec<&str> {
    let (mut parts, mut start, mut depth, mut quote) = (Vec::new(), 0, 0_i32, None);
    for (k, c) in text.char_indices() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '[' | '{') => depth += 1,
            (None, ']' | '}') => depth -= 1,
            (None, c) if c == separator && depth == 0 => {
                parts.push(&text[start..k]);
                start = k + c.len_utf8();
            }
            _ => {}
        }
    }
    parts.push(&text[start..]);
    parts
}

/// A CSV field: quoted, its quotes doubled, when it holds a comma, a quote or a line break.
fn csv_field(value: &str) -> String {
    if value.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", value.replace('"', "\"\""))
    } else {
        value.to_string()
    }
}

/// What `sweep` was asked to do.
pub struct SweepRequest<'a> {
    pub case: &'a Path,
    pub set_list: &'a str,
    pub set: &'a [String],
    pub reference: &'a [String],
    pub jobs: Option<NonZeroUsize>,
    pub out: &'a Path,
}

/// Runs a sweep; returns whether every run converged. A run that stops at a cap keeps its
/// row and files, marked unconverged, and an error line on stderr names it, why it stopped
/// and its directory. A run that fails (the solver refused its case) keeps its row, marked
/// unconverged with its measures empty, its error goes to stderr, and the sweep fails once
/// sweep.csv is written; a case with a loading path is refused before any run.
pub fn sweep(request: &SweepRequest) -> Result<bool> {
    let (keys, values) = parse_set_list(request.set_list)?;
    let reference = if request.reference.is_empty() {
        None
    } else {
        let overrides: Vec<String> = request.set.iter().chain(request.reference).cloned().collect();
        let case = Case::load(request.case, &overrides)?;
        case.one_position()?;
        let out = request.out.join("reference");
        Some(run_jobs(vec![Job { label: "reference".into(), case, out: Some(out) }], 1)?.remove(0))
    };
    let labels: Vec<String> = values.iter().map(|v| format!("{}={v}", keys.join("="))).collect();
    let mut jobs = Vec::new();
    for (i, (value, label)) in values.iter().zip(&labels).enumerate() {
        let mut overrides = request.set.to_vec();
        overrides.extend(keys.iter().map(|k| format!("{k}={value}")));
        let case = Case::load(request.case, &overrides)?;
        case.one_position()?;
        jobs.push(Job {
            label: label.clone(),
            case,
            out: Some(request.out.join(run_directory(i))),
        });
    }
    let units = jobs[0].case.file.units.clone();
    let runs = run_each(jobs, threads(request.jobs));
    let mut csv = keys.join(",");
    csv.push_str(",outer_iterations,inner_iterations,converged,max_abs_sigma_nu,max_abs_sigma_tau,contact_length,stick_length,slip_length,distance_to_reference,wall_seconds\n");
    let (mut unconverged, mut failed) = (Vec::new(), 0);
    for (i, (value, run)) in values.iter().zip(&runs).enumerate() {
        let values = vec![csv_field(value); keys.len()].join(",");
        match run {
            Ok(Solved { built, run }) => {
                let distance = match &reference {
                    Some(r) => csv_number(run.distance_to(built, &r.run)?),
                    None => String::new(),
                };
                let _ = writeln!(csv, "{values},{}", row(run, &distance));
                if let Some(failure) = &run.solution.failure {
                    let out = request.out.join(run_directory(i));
                    unconverged.push(format!(
                        "run {}: {failure}; its partial result is in {} (marked \
                         \"converged\": false, as its row of sweep.csv)",
                        labels[i],
                        out.display()
                    ));
                }
            }
            Err(e) => {
                say_err!("error: {e:#}");
                let _ = writeln!(csv, "{values},,,false,,,,,,,");
                failed += 1;
            }
        }
    }
    write_atomic(&request.out.join("sweep.csv"), csv.as_bytes())?;
    say!("{}", csv.trim_end());
    if let Some(solved) = runs.iter().find_map(|r| r.as_ref().ok()) {
        say!("{}", units_line(&units, solved.built.problem.mesh.dim()));
    }
    say!("wrote {} and one directory per run", request.out.join("sweep.csv").display());
    for run in &unconverged {
        say_err!("error: {run}");
    }
    if failed > 0 {
        bail!(
            "{failed} of {} runs failed (the errors above); their rows in sweep.csv are marked \
             unconverged, without results",
            runs.len()
        );
    }
    Ok(unconverged.is_empty())
}

/// The directory of run i of a sweep, in its output directory.
fn run_directory(i: usize) -> String {
    format!("run-{i:02}")
}

/// What the columns of sweep.csv measure, in the case's units, for a `dim`-D body.
fn units_line(units: &piezocontact::case::Units, dim: usize) -> String {
    let (measure, power) = if dim == 3 { ("areas", "²") } else { ("lengths", "") };
    format!(
        "units: max_abs_sigma_nu, max_abs_sigma_tau in {}; contact_length, stick_length, \
         slip_length: {measure} of the zones on Γ3 in {}{power}; distance_to_reference: \
         ‖x − x_ref‖_X / ‖x_ref‖_X [-]; wall_seconds in s",
        units.stress, units.length
    )
}

/// The columns of sweep.csv after the swept values, for a run that ended.
fn row(run: &ContactRun, distance: &str) -> String {
    let (sigma_nu, sigma_tau) = run.peaks();
    let (contact, stick, slip) = run.zones();
    format!(
        "{},{},{},{},{},{},{},{},{distance},{:.3}",
        run.solution.outer_iterations(),
        run.solution.inner_iterations.iter().sum::<usize>(),
        run.solution.converged(),
        csv_number(sigma_nu),
        csv_number(sigma_tau),
        csv_number(contact),
        csv_number(stick),
        csv_number(slip),
        run.seconds
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A job of the paper's Example 7.1 on a coarse mesh, writing into `out`; with `broken`,
    /// a mesh file beside the rectangle, which the case loads and the run refuses.
    fn job(label: &str, out: PathBuf, broken: bool) -> Job {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/paper-7.1.toml");
        let mut overrides = vec!["mesh.nx=12".to_string(), "mesh.ny=2".to_string()];
        if broken {
            overrides.push("mesh.file=\"no-such-mesh.msh\"".into());
        }
        let case = Case::load(&path, &overrides).expect("the case loads");
        Job { label: label.into(), case, out: Some(out) }
    }

    /// On one thread the jobs run in their order. `run_jobs` (reproduce) starts none after the
    /// first that fails and returns its error; `run_each` (sweep) runs them all.
    #[test]
    fn the_first_failure_stops_the_jobs_of_run_jobs_not_those_of_run_each() {
        let dir = std::env::temp_dir().join(format!("piezocontact-jobs-{}", std::process::id()));
        let jobs = |tag: &str| {
            let out = |name: &str| dir.join(format!("{tag}-{name}"));
            vec![
                job("first", out("first"), false),
                job("broken", out("broken"), true),
                job("third", out("third"), false),
            ]
        };
        let error = run_jobs(jobs("jobs"), 1).err().map(|e| format!("{e:#}")).unwrap_or_default();
        assert!(error.contains("run broken") && error.contains("mesh.file"), "{error}");
        assert!(dir.join("jobs-first").exists() && !dir.join("jobs-third").exists());
        let each = run_each(jobs("each"), 1);
        assert!(each[0].is_ok() && each[1].is_err() && each[2].is_ok());
        assert!(dir.join("each-third").exists());
        let _ = std::fs::remove_dir_all(&dir);
    }
}

//! A loading path of a built case (model §14): one static contact solve per step, the
//! foundation moved rigidly along a direction and/or the applied loads scaled, each step
//! started from the last with the factorisation and the exact solver's condensation kept
//! ([`crate::algorithm::ContactSolver`]).

use super::contact_run::ContactRun;
use crate::algorithm::{ContactSolution, ContactSolver, Progress};
use crate::case::Built;
use crate::contact::ContactSurface;
use crate::contact::{ContactModel, LoadStep, Loading};
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::linalg::LinearSolver;
use crate::output::fields::ContactFields;
use crate::output::files::{self, Outputs};
use crate::output::plot::{self, LinePlot, PALETTE, Series};
use crate::output::vtu::Encoding;
use crate::problem::Problem;
use crate::report::{self, Column, CurveRow, Row, columns_csv, curve_columns};
use plotters::prelude::SeriesLabelPosition;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::time::Instant;

/// A loading path solved step after step.
pub struct PathRun {
    /// One row per step solved (the last one unconverged when the path stopped there).
    pub curve: Vec<CurveRow>,
    /// Per step solved: x and the Γ3 rows, for its solution-NNNN.vtu.
    states: Vec<(Vec<f64>, Vec<Row>)>,
    /// The last step solved, as a run: its model with the foundation where the step put it,
    /// its solution under the step's loads — what contact.csv and summary.json hold.
    pub last: ContactRun,
    /// Why the path stopped before its end: the step and the reason.
    pub failure: Option<String>,
    /// The steps' solution-NNNN.vtu written while the path went on, where it was asked to.
    written: Option<Box<Written>>,
}

/// Where a path writes each step's solution-NNNN.vtu as soon as it is solved, on a thread of
/// its own while the next step solves: the output directory and the encoding.
#[derive(Clone, Copy, Debug)]
pub struct StepFiles<'a> {
    /// The output directory (created before the solve).
    pub dir: &'a Path,
    /// The encoding of the .vtu files.
    pub vtu: Encoding,
}

/// What the steps' writer did: where, how many steps, the time it spent \[s\], or why it
/// stopped.
struct Written {
    dir: PathBuf,
    vtu: Encoding,
    steps: Result<usize>,
    seconds: f64,
}

/// One solved step for the writer: its number (from 0), x, its Γ3 rows, its DOF map and Γ3.
type Step = (usize, Vec<f64>, Vec<Row>, DofMap, ContactSurface);

/// Writes each step received into `files` until the path closes the channel: what it did.
fn write_steps(problem: &Problem, files: StepFiles, steps: Receiver<Step>) -> Written {
    let (mut count, mut seconds) = (0, 0.0);
    let mut write = |(k, x, rows, dofs, surface): Step| -> Result<()> {
        let start = Instant::now();
        let path = files.dir.join(files::step_name(k));
        step_vtu(problem, (&dofs, &surface), (&x, &rows), files.vtu, &path)?;
        (count, seconds) = (count + 1, seconds + start.elapsed().as_secs_f64());
        Ok(())
    };
    let steps = steps.into_iter().try_for_each(&mut write).map(|_| count);
    Written { dir: files.dir.to_path_buf(), vtu: files.vtu, steps, seconds }
}

/// Writes a step's solution-NNNN.vtu at `path`: its state `x` with its Γ3 `rows` as point
/// fields.
fn step_vtu(
    problem: &Problem,
    (dofs, surface): (&DofMap, &ContactSurface),
    (x, rows): (&[f64], &[Row]),
    vtu: Encoding,
    path: &Path,
) -> Result<()> {
    let fields = ContactFields::new(&problem.mesh, surface, rows);
    files::solution_vtu(problem, (dofs, x), &fields.fields(), vtu, path)
}

/// [`write_steps`] on a pool of one thread of its own: on the run's pool its parallel loops
/// could wait for a thread that waits for the writer (the run on one thread, as under
/// mpirun on as many processes as cores, deadlocked so). A pool that cannot be had: the
/// steps are written at the end.
fn on_a_pool_of_its_own(problem: &Problem, files: StepFiles, steps: Receiver<Step>) -> Written {
    match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
        Ok(pool) => pool.install(|| write_steps(problem, files, steps)),
        Err(e) => Written {
            dir: files.dir.to_path_buf(),
            vtu: files.vtu,
            steps: Err(Error::Io {
                what: format!("the steps' files in {}", files.dir.display()),
                cause: format!("no thread for their writer: {e}"),
            }),
            seconds: 0.0,
        },
    }
}

impl PathRun {
    /// Solves the steps of `loading` in order with the caller's `solver`, each from the last;
    /// stops at the first step that does not converge (kept, marked) or fails (the steps
    /// before it kept). An error when the first step fails. With `files`, each step's
    /// solution-NNNN.vtu is written while the next one solves.
    pub(super) fn solve(
        built: &Built,
        (model, loading): (&ContactModel, &Loading),
        (solver, progress): (Box<dyn LinearSolver>, &(dyn Fn(Progress) + Sync)),
        files: Option<StepFiles>,
    ) -> Result<Self> {
        let Some(files) = files else {
            return Self::solve_steps(built, (model, loading), (solver, progress), None);
        };
        std::thread::scope(|scope| {
            let (send, receive) = channel();
            let writer = scope.spawn(move || on_a_pool_of_its_own(&built.problem, files, receive));
            let path = Self::solve_steps(built, (model, loading), (solver, progress), Some(send));
            let written = writer.join().map_err(|_| Error::Io {
                what: format!("the steps' files in {}", files.dir.display()),
                cause: "their writer stopped".into(),
            });
            Ok(Self { written: Some(Box::new(written?)), ..path? })
        })
    }

    /// [`PathRun::solve`]: each step solved sent to `steps` where given.
    fn solve_steps(
        built: &Built,
        (model, loading): (&ContactModel, &Loading),
        (solver, progress): (Box<dyn LinearSolver>, &(dyn Fn(Progress) + Sync)),
        steps: Option<Sender<Step>>,
    ) -> Result<Self> {
        let start = Instant::now();
        let problem = &built.problem;
        let at_first = loading.at_first(model);
        let mut solver = ContactSolver::new(problem, &at_first, &built.settings, solver)
            .map_err(|e| built.context(e))?;
        let (mut curve, mut states, mut failure) = (Vec::new(), Vec::new(), None);
        let mut last: Option<(ContactModel, ContactSolution)> = None;
        let n = loading.steps.len();
        for (k, load) in loading.steps.iter().enumerate() {
            let what = step_name(k, n, load);
            log::info!("{what}");
            let step_model = loading.model_at(model, load);
            let solution = match solver.solve(problem, &step_model, load.factors(), progress) {
                Ok(solution) => solution,
                Err(e) if k > 0 => {
                    failure = Some(format!("{what} failed: {e}"));
                    break;
                }
                Err(e) => return Err(built.context(e)),
            };
            let rows = report::rows(problem, &step_model, &solution);
            curve.push(CurveRow::new(k + 1, load, &solution, &rows));
            if let Some(steps) = &steps {
                let (dofs, surface) = (solution.dofs.clone(), solution.surface.clone());
                // A writer that stopped has said why: the steps are written again at the end.
                let _ = steps.send((k, solution.x.clone(), rows.clone(), dofs, surface));
            }
            states.push((solution.x.clone(), rows));
            let stop = solution.failure.as_ref().map(|e| format!("{what} did not converge: {e}"));
            last = Some((step_model, solution));
            if stop.is_some() {
                failure = stop;
                break;
            }
        }
        let (model, solution) =
            last.ok_or_else(|| Error::Input("a loading path without steps".into()))?;
        let last = ContactRun::new(built, model, solution, start);
        Ok(Self { curve, states, last, failure, written: None })
    }

    /// The Γ3 rows of step k (from 0) of the steps solved.
    pub fn rows(&self, k: usize) -> &[Row] {
        &self.states[k].1
    }

    /// x = (u, ϕ) of each step solved, in order (global numbering of the last step's DOF
    /// map).
    pub fn states(&self) -> impl Iterator<Item = &[f64]> {
        self.states.iter().map(|(x, _)| x.as_slice())
    }

    /// The names of the grounded parts, whose charges curve.csv reports.
    pub fn electrodes(built: &Built) -> Vec<String> {
        let problem = &built.problem;
        problem.boundary.grounded.iter().map(|&p| problem.mesh.parts()[p].name.clone()).collect()
    }

    /// The names of the electrodes beside the grounded parts, whose potential and charge
    /// curve.csv reports.
    pub fn driven_electrodes(built: &Built) -> Vec<String> {
        built.problem.boundary.electrodes.iter().map(|e| e.name.clone()).collect()
    }

    /// The columns of curve.csv.
    pub fn columns(&self, built: &Built) -> Vec<(String, Column)> {
        let supports = built.problem.reported_supports();
        let (parts, driven) = (Self::electrodes(built), Self::driven_electrodes(built));
        curve_columns(&self.curve, built.problem.mesh.dim(), (&supports, &parts, &driven))
    }

    /// Whether every step converged and the path reached its end.
    pub fn converged(&self) -> bool {
        self.failure.is_none()
    }

    /// The summary.json of the path: the last step's, with the path's steps and its failure.
    pub fn summary(&self, built: &Built, loading: &Loading) -> Value {
        let mut summary = self.last.summary(built);
        summary["converged"] = json!(self.converged() && self.last.solution.converged());
        if let Some(failure) = &self.failure {
            summary["failure"] = json!(failure);
        }
        summary["path"] = json!({
            "steps": loading.steps.len(),
            "steps_solved": self.curve.len(),
            "direction": &loading.direction[..built.problem.mesh.dim()],
        });
        summary
    }

    /// Writes the last step's files (contact.csv, solution.vtu, the 3D contact map),
    /// curve.csv, solution-NNNN.vtu per step with solution.pvd, and the curves' figure
    /// (curve.png and .svg) into `outputs`.
    pub(super) fn write_files(
        &self,
        (built, loading): (&Built, &Loading),
        outputs: &mut Outputs,
    ) -> Result<()> {
        self.last.write_files(built, outputs)?;
        let problem = &built.problem;
        let mut parts = Self::electrodes(built);
        parts.extend(Self::driven_electrodes(built));
        let csv = || Ok(columns_csv(&self.columns(built), self.curve.len()).into_bytes());
        outputs.file("curve.csv", csv)?;
        let (solution, vtu, steps) = (&self.last.solution, outputs.vtu, self.states.len());
        match &self.written {
            Some(w)
                if w.dir == outputs.dir
                    && w.vtu == vtu
                    && w.steps.as_ref().ok() == Some(&steps) =>
            {
                outputs.written_meanwhile("solution-NNNN.vtu", w.seconds);
                outputs.series(steps, None)?;
            }
            _ => {
                let step = |k: usize, path: &Path| {
                    let (x, rows) = &self.states[k];
                    step_vtu(problem, (&solution.dofs, &solution.surface), (x, rows), vtu, path)
                };
                outputs.series(steps, Some(&step))?;
            }
        }
        let figures = self.figures((built, loading), &parts);
        outputs.timed("curve", |dir| plot::panels(&figures, &dir.join("curve")))
    }

    /// The curves against the depth (against the load factor when the foundation does not
    /// move): the force P = −F·direction (F·e_d without a direction), the charges of the
    /// electrodes `parts` (the grounded parts, then the others), and ϕ at the centre, in the
    /// mean over the contact zone and on each electrode beside the grounded parts.
    fn figures(&self, (built, loading): (&Built, &Loading), parts: &[String]) -> Vec<LinePlot> {
        let units = &built.units;
        let dim = built.problem.mesh.dim();
        let moves = loading.moves();
        let (x_label, x) = if moves {
            (format!("depth [{}]", units.length), (|r: &CurveRow| r.depth) as fn(&CurveRow) -> f64)
        } else {
            ("load factor [-]".to_string(), (|r: &CurveRow| r.load_factor) as fn(&CurveRow) -> f64)
        };
        // The force on the indenter against its travel, P = −F·d; F along the last axis
        // when the foundation does not move.
        let along = loading.direction.map(|v| -v);
        let force = |r: &CurveRow| {
            if moves { (0..dim).map(|k| r.force[k] * along[k]).sum() } else { r.force[dim - 1] }
        };
        // A body of revolution's forces and charges are totals, as in 3D.
        let totals = dim == 3 || built.problem.axisymmetric;
        let per_depth = if totals { String::new() } else { format!("/{}", units.length) };
        let line = |label: String, k: usize, y: &dyn Fn(&CurveRow) -> f64| Series {
            label,
            points: self.curve.iter().map(|r| (x(r), y(r))).collect(),
            color: PALETTE[k % PALETTE.len()],
            markers: true,
        };
        let area = if totals { format!("{}²", units.length) } else { units.length.clone() };
        let title = if built.title.is_empty() { "loading path" } else { built.title.as_str() };
        let plot = |title: String, y_label: String, series: Vec<Series>| LinePlot {
            title,
            x_label: x_label.clone(),
            y_label,
            series,
            log_log: false,
            legend: SeriesLabelPosition::UpperLeft,
        };
        let charges = parts
            .iter()
            .enumerate()
            .map(|(k, p)| line(format!("on {p}"), k + 1, &move |r: &CurveRow| r.charges[k]))
            .collect();
        let grounded = built.problem.boundary.grounded.len();
        let mut potentials = vec![
            line("at the largest pressure".into(), 1, &|r: &CurveRow| r.phi_center),
            line("mean over the contact zone".into(), 2, &|r: &CurveRow| r.phi_mean),
        ];
        for (j, name) in parts[grounded..].iter().enumerate() {
            potentials.push(line(format!("on {name}"), 3 + j, &move |r| r.potentials[j]));
        }
        vec![
            plot(
                title.to_string(),
                format!("force on the indenter [{}·{area}]", units.stress),
                vec![line("P".into(), 0, &force)],
            ),
            plot(
                "charge on the electrodes".into(),
                format!("charge [{}{per_depth}]", units.charge),
                charges,
            ),
            plot(
                "potential under the indenter".into(),
                format!("ϕ [{}]", units.potential),
                potentials,
            ),
        ]
    }
}

/// How step k (from 0) of `n` reads in messages.
fn step_name(k: usize, n: usize, load: &LoadStep) -> String {
    format!("step {} of {n} (depth {:e}, load factor {})", k + 1, load.depth, load.load_factor)
}

//! Loading paths (model §14): one static contact solve per step, the foundation moved
//! rigidly along a direction and/or the applied loads scaled, each step started from the
//! last with the factorisation and the exact solver's condensation kept
//! ([`crate::algorithm::ContactSolver`]).

use crate::algorithm::{ContactSolution, ContactSolver, Progress};
use crate::case::{Built, Case};
use crate::contact::{ContactModel, Foundation, NodeStatus};
use crate::error::{Error, Result};
use crate::linalg::LinearSolver;
use crate::output::files;
use crate::output::plot::{self, LinePlot, PALETTE, Series};
use crate::report::{self, Row};
use crate::run::{self, ContactFields, ContactRun};
use plotters::prelude::SeriesLabelPosition;
use serde_json::{Value, json};
use std::f64::consts::PI;
use std::path::Path;
use std::time::Instant;

/// A loading path: the steps of `[loading]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Loading {
    /// The unit vector along which the foundation travels (0 when it does not move).
    pub direction: [f64; 3],
    /// The steps, in order.
    pub steps: Vec<LoadStep>,
}

/// One step of a loading path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadStep {
    /// The foundation's displacement along the direction from its `[foundation]` position
    /// \[length\].
    pub depth: f64,
    /// The factor on every applied load [-].
    pub load_factor: f64,
}

impl Loading {
    /// `model` with its foundation where `step` moves it: rigidly, by depth · direction.
    pub fn model_at(&self, model: &ContactModel, step: &LoadStep) -> ContactModel {
        ContactModel { foundation: self.foundation_at(&model.foundation, step), ..model.clone() }
    }

    /// `foundation` where `step` moves it: rigidly, by depth · direction.
    pub fn foundation_at(&self, foundation: &Foundation, step: &LoadStep) -> Foundation {
        foundation.translated(self.direction.map(|v| v * step.depth))
    }

    /// `model` at the first step (as given without steps): where the solver is set up, the
    /// exact solver's first guess of the contact zone being that step's.
    pub fn at_first(&self, model: &ContactModel) -> ContactModel {
        self.steps.first().map_or_else(|| model.clone(), |s| self.model_at(model, s))
    }
}

/// One row of curve.csv: what the experimentalist reads at a step.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveRow {
    /// The step, from 1.
    pub step: usize,
    /// The factor on the applied loads [-].
    pub load_factor: f64,
    /// The foundation's displacement along the loading direction \[length\].
    pub depth: f64,
    /// The force the body exerts on the foundation, d components [stress·length^(d−1)].
    pub force: Vec<f64>,
    /// The measure of the contact zone [length^(d−1)].
    pub contact_measure: f64,
    /// √(measure/π) in 3D, half the measure in 2D \[length\].
    pub contact_radius: f64,
    /// The largest contact pressure −σ_ν \[stress\].
    pub max_pressure: f64,
    /// ϕ at the Γ3 node with the largest pressure \[potential\].
    pub phi_center: f64,
    /// The mean of ϕ over the contact zone (over Γ3 when nothing touches) \[potential\].
    pub phi_mean: f64,
    /// The measures of the stick and slip zones [length^(d−1)].
    pub stick_measure: f64,
    pub slip_measure: f64,
    /// Inner iterations (Newton steps or Uzawa iterations) of the step.
    pub newton_steps: usize,
    /// The largest relative KKT residual [-].
    pub kkt_residual: f64,
    /// Whether the step converged.
    pub converged: bool,
    /// The charge on each part of Γa [charge·length^(3−d)].
    pub charges: Vec<f64>,
}

impl CurveRow {
    /// The row of `step` (from 1) at `load` with its `solution` and Γ3 `rows`.
    pub fn new(step: usize, load: &LoadStep, solution: &ContactSolution, rows: &[Row]) -> Self {
        let dim = solution.surface.dim();
        let (contact, stick, slip) = report::zone_measures(solution, rows);
        let weight = &solution.surface.weight;
        let touching: Vec<usize> =
            (0..rows.len()).filter(|&i| rows[i].status != NodeStatus::Separated).collect();
        let zone = if touching.is_empty() { (0..rows.len()).collect() } else { touching };
        let measure: f64 = zone.iter().map(|&i| weight[i]).sum();
        let phi_mean = zone.iter().map(|&i| weight[i] * rows[i].phi).sum::<f64>()
            / measure.max(f64::MIN_POSITIVE);
        let center = (0..rows.len()).max_by(|&a, &b| rows[b].sigma_nu.total_cmp(&rows[a].sigma_nu));
        Self {
            step,
            load_factor: load.load_factor,
            depth: load.depth,
            force: solution.balance.contact.iter().map(|f| -f).collect(),
            contact_measure: contact,
            contact_radius: if dim == 3 { (contact / PI).sqrt() } else { 0.5 * contact },
            max_pressure: rows.iter().map(|r| -r.sigma_nu).fold(0.0, f64::max),
            phi_center: center.map_or(0.0, |i| rows[i].phi),
            phi_mean,
            stick_measure: stick,
            slip_measure: slip,
            newton_steps: solution.inner_iterations.iter().sum(),
            kkt_residual: solution.kkt.max,
            converged: solution.converged,
            charges: solution.balance.charges.clone(),
        }
    }
}

/// A column of curve.csv.
#[derive(Clone, Debug, PartialEq)]
pub enum Column {
    /// Counts (step, newton_steps).
    Integer(Vec<usize>),
    /// Quantities.
    Real(Vec<f64>),
    /// converged.
    Flag(Vec<bool>),
}

impl Column {
    fn cell(&self, k: usize) -> String {
        match self {
            Self::Integer(v) => v[k].to_string(),
            Self::Real(v) => format!("{:e}", v[k]),
            Self::Flag(v) => v[k].to_string(),
        }
    }
}

/// The columns of curve.csv, named and in order, for `rows` of a d-dimensional body whose
/// grounded parts are `parts` (one `charge_<part>` each).
pub fn curve_columns(rows: &[CurveRow], dim: usize, parts: &[String]) -> Vec<(String, Column)> {
    let real = |f: &dyn Fn(&CurveRow) -> f64| Column::Real(rows.iter().map(f).collect());
    let mut columns = vec![
        ("step".to_string(), Column::Integer(rows.iter().map(|r| r.step).collect())),
        ("load_factor".into(), real(&|r| r.load_factor)),
        ("depth".into(), real(&|r| r.depth)),
    ];
    for (k, name) in ["force_x", "force_y", "force_z"][..dim].iter().enumerate() {
        columns.push((name.to_string(), real(&|r| r.force[k])));
    }
    type Quantity = (&'static str, fn(&CurveRow) -> f64);
    let quantities: [Quantity; 7] = [
        ("contact_measure", |r| r.contact_measure),
        ("contact_radius", |r| r.contact_radius),
        ("max_pressure", |r| r.max_pressure),
        ("phi_center", |r| r.phi_center),
        ("phi_mean", |r| r.phi_mean),
        ("stick_measure", |r| r.stick_measure),
        ("slip_measure", |r| r.slip_measure),
    ];
    columns.extend(quantities.iter().map(|(name, f)| (name.to_string(), real(f))));
    columns.push((
        "newton_steps".into(),
        Column::Integer(rows.iter().map(|r| r.newton_steps).collect()),
    ));
    columns.push(("kkt_residual".into(), real(&|r| r.kkt_residual)));
    columns.push(("converged".into(), Column::Flag(rows.iter().map(|r| r.converged).collect())));
    for (k, part) in parts.iter().enumerate() {
        columns.push((format!("charge_{part}"), real(&|r| r.charges[k])));
    }
    columns
}

/// curve.csv: a header, then one line per row.
pub fn curve_csv(rows: &[CurveRow], dim: usize, parts: &[String]) -> String {
    let columns = curve_columns(rows, dim, parts);
    let header: Vec<&str> = columns.iter().map(|(name, _)| name.as_str()).collect();
    let mut csv = header.join(",") + "\n";
    for k in 0..rows.len() {
        let line: Vec<String> = columns.iter().map(|(_, c)| c.cell(k)).collect();
        csv += &(line.join(",") + "\n");
    }
    csv
}

/// A loading path solved step after step.
pub struct PathRun {
    /// The path.
    pub loading: Loading,
    /// One row per step solved (the last one unconverged when the path stopped there).
    pub curve: Vec<CurveRow>,
    /// Per step solved: x and the Γ3 rows, for its solution-NNNN.vtu.
    states: Vec<(Vec<f64>, Vec<Row>)>,
    /// The last step solved, as a run: its problem with the step's loads, its model with the
    /// foundation where the step put it — what contact.csv and summary.json hold.
    pub last: ContactRun,
    /// Why the path stopped before its end: the step and the reason.
    pub failure: Option<String>,
}

impl PathRun {
    /// Solves the steps of `built.loading` in order with the caller's `solver`, each from the
    /// last; stops at the first step that does not converge (kept, marked) or fails (the
    /// steps before it kept). An error when the first step fails.
    pub fn solve_built(
        case: &Case,
        built: Built,
        solver: Box<dyn LinearSolver>,
        progress: &(dyn Fn(Progress) + Sync),
    ) -> Result<Self> {
        let start = Instant::now();
        let Built { mut problem, model, settings, warnings, loading } = built;
        let model = run::contact_model(case, &problem, model)?;
        let loading = loading.ok_or_else(|| {
            Error::Input(format!("{}: the case has no [loading] table", case.path.display()))
        })?;
        let at_first = loading.at_first(&model);
        let mut solver = ContactSolver::new(&problem, &at_first, &settings, solver)
            .map_err(|e| case.context(e))?;
        let (mut curve, mut states, mut failure) = (Vec::new(), Vec::new(), None);
        let mut last: Option<(ContactModel, ContactSolution, Vec<Row>)> = None;
        let n = loading.steps.len();
        for (k, load) in loading.steps.iter().enumerate() {
            let what = format!(
                "step {} of {n} (depth {:e}, load factor {})",
                k + 1,
                load.depth,
                load.load_factor
            );
            log::info!("{what}");
            problem.load_factor = load.load_factor;
            let step_model = loading.model_at(&model, load);
            let solution = match solver.solve(&problem, &step_model, progress) {
                Ok(solution) => solution,
                Err(e) if k > 0 => {
                    failure = Some(format!("{what} failed: {e}"));
                    break;
                }
                Err(e) => return Err(case.context(e)),
            };
            let rows = report::rows(&problem, &step_model, &solution);
            curve.push(CurveRow::new(k + 1, load, &solution, &rows));
            states.push((solution.x.clone(), rows.clone()));
            let stop = solution.failure.as_ref().map(|e| format!("{what} did not converge: {e}"));
            last = Some((step_model, solution, rows));
            if stop.is_some() {
                failure = stop;
                break;
            }
        }
        let (model, solution, rows) =
            last.ok_or_else(|| Error::Input("a loading path without steps".into()))?;
        if let Some(k) = curve.last().map(|r| r.step) {
            problem.load_factor = loading.steps[k - 1].load_factor;
        }
        let seconds = start.elapsed().as_secs_f64();
        let last = ContactRun { problem, model, solution, rows, settings, warnings, seconds };
        Ok(Self { loading, curve, states, last, failure })
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
    pub fn electrodes(&self) -> Vec<String> {
        let problem = &self.last.problem;
        problem.boundary.grounded.iter().map(|&p| problem.mesh.parts()[p].name.clone()).collect()
    }

    /// The columns of curve.csv.
    pub fn columns(&self) -> Vec<(String, Column)> {
        curve_columns(&self.curve, self.last.problem.mesh.dim(), &self.electrodes())
    }

    /// Whether every step converged and the path reached its end.
    pub fn converged(&self) -> bool {
        self.failure.is_none()
    }

    /// The summary.json of the path: the last step's, with the path's steps and its failure.
    pub fn summary(&self, case: &Case) -> Value {
        let mut summary = self.last.summary(case);
        summary["converged"] = json!(self.converged() && self.last.solution.converged);
        if let Some(failure) = &self.failure {
            summary["failure"] = json!(failure);
        }
        summary["path"] = json!({
            "steps": self.loading.steps.len(),
            "steps_solved": self.curve.len(),
            "direction": &self.loading.direction[..self.last.problem.mesh.dim()],
        });
        summary
    }

    /// Writes the last step's files (contact.csv, solution.vtu, the 3D contact map),
    /// summary.json of the path, curve.csv, solution-NNNN.vtu per step with solution.pvd, and
    /// the curves' figure (curve.png and .svg).
    pub fn write(&self, case: &Case, out: &Path) -> Result<()> {
        self.last.write_with_summary(case, out, &self.summary(case))?;
        let problem = &self.last.problem;
        let parts = self.electrodes();
        let csv = curve_csv(&self.curve, problem.mesh.dim(), &parts);
        files::write_atomic(&out.join("curve.csv"), csv.as_bytes())?;
        let mut collection = Vec::new();
        let solution = &self.last.solution;
        for (k, (x, rows)) in self.states.iter().enumerate() {
            let name = format!("solution-{:04}.vtu", k + 1);
            let fields = ContactFields::new(problem, solution, rows);
            let vtu = files::solution_vtu(problem, &solution.dofs, x, &fields.fields())?;
            files::write_atomic(&out.join(&name), vtu.as_bytes())?;
            collection.push((k + 1, name));
        }
        files::write_atomic(&out.join("solution.pvd"), pvd(&collection).as_bytes())?;
        plot::panels(&self.figures(case, &parts), &out.join("curve"))
    }

    /// The curves against the depth (against the load factor when the foundation does not
    /// move): the force P = −F·direction (F·e_d without a direction), the charges of the
    /// electrodes, and ϕ at the centre and in the mean over the contact zone.
    fn figures(&self, case: &Case, parts: &[String]) -> Vec<LinePlot> {
        let units = &case.file.units;
        let dim = self.last.problem.mesh.dim();
        let moves = self.loading.direction.iter().any(|v| *v != 0.0);
        let (x_label, x) = if moves {
            (format!("depth [{}]", units.length), (|r: &CurveRow| r.depth) as fn(&CurveRow) -> f64)
        } else {
            ("load factor [-]".to_string(), (|r: &CurveRow| r.load_factor) as fn(&CurveRow) -> f64)
        };
        // The force on the indenter against its travel, P = −F·d; F along the last axis
        // when the foundation does not move.
        let along = self.loading.direction.map(|v| -v);
        let force = |r: &CurveRow| {
            if moves { (0..dim).map(|k| r.force[k] * along[k]).sum() } else { r.force[dim - 1] }
        };
        let per_depth = if dim == 2 { format!("/{}", units.length) } else { String::new() };
        let line = |label: String, k: usize, y: &dyn Fn(&CurveRow) -> f64| Series {
            label,
            points: self.curve.iter().map(|r| (x(r), y(r))).collect(),
            color: PALETTE[k % PALETTE.len()],
            markers: true,
        };
        let area = if dim == 3 { format!("{}²", units.length) } else { units.length.clone() };
        let title =
            if case.file.title.is_empty() { "loading path" } else { case.file.title.as_str() };
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
                vec![
                    line("at the largest pressure".into(), 1, &|r: &CurveRow| r.phi_center),
                    line("mean over the contact zone".into(), 2, &|r: &CurveRow| r.phi_mean),
                ],
            ),
        ]
    }
}

/// A ParaView collection of the steps' files, the step number as its time.
fn pvd(files: &[(usize, String)]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n",
    );
    for (step, name) in files {
        s += &format!("<DataSet timestep=\"{step}\" group=\"\" part=\"0\" file=\"{name}\"/>\n");
    }
    s + "</Collection>\n</VTKFile>\n"
}

//! One contact solve of a built case: solve, assess, summarise and write its results.

use crate::algorithm::{ContactSolution, Progress, solve_contact_with};
use crate::assembly::x_norm_squared;
use crate::case::Built;
use crate::contact::ContactModel;
use crate::error::{Error, Result};
use crate::linalg::LinearSolver;
use crate::output::fields::ContactFields;
use crate::output::files::Outputs;
use crate::output::plot::{self, ContactView, MapLabels};
use crate::output::vtu::Encoding;
use crate::report::summary::{
    common_summary, contact_summary, electrodes_json, hencky_tangent, merge, reactions_json,
};
use crate::report::{self, Row};
use serde_json::{Value, json};
use std::path::Path;
use std::time::Instant;

/// A solved contact case with its assessment.
pub struct ContactRun {
    /// The contact model solved (on a loading path, with the foundation where the step put
    /// it).
    pub model: ContactModel,
    /// The algorithms' result (converged or not: see `solution.failure`).
    pub solution: ContactSolution,
    /// The Γ3 table, ordered along Γ3.
    pub rows: Vec<Row>,
    /// Wall time of the solve and the assessment \[s\].
    pub seconds: f64,
}

impl ContactRun {
    /// Solves the contact problem of `built` (which has a contact model) with the caller's
    /// linear `solver`, telling `progress` of each outer step and inner iteration.
    pub(super) fn solve(
        built: &Built,
        model: &ContactModel,
        solver: Box<dyn LinearSolver>,
        progress: &(dyn Fn(Progress) + Sync),
    ) -> Result<Self> {
        let start = Instant::now();
        let solution = solve_contact_with(&built.problem, model, &built.settings, solver, progress)
            .map_err(|e| built.context(e))?;
        Ok(Self::new(built, model.clone(), solution, start))
    }

    /// The run of `solution` of `model`, started at `start`: its Γ3 table.
    pub(super) fn new(
        built: &Built,
        model: ContactModel,
        mut solution: ContactSolution,
        start: Instant,
    ) -> Self {
        let table = Instant::now();
        let rows = report::rows(&built.problem, &model, &solution);
        solution.timings.assessment += table.elapsed().as_secs_f64();
        Self { model, solution, rows, seconds: start.elapsed().as_secs_f64() }
    }

    /// max |σ_ν| and max |σ_τ| on Γ3 \[stress\].
    pub fn peaks(&self) -> (f64, f64) {
        let max = |f: fn(&Row) -> f64| self.rows.iter().map(|r| f(r).abs()).fold(0.0, f64::max);
        (max(|r| r.sigma_nu), max(|r| r.sigma_tau[0].hypot(r.sigma_tau[1])))
    }

    /// Measures of the contact, stick and slip zones.
    pub fn zones(&self) -> (f64, f64, f64) {
        report::zone_measures(&self.solution, &self.rows)
    }

    /// ‖x − x_ref‖_X / ‖x_ref‖_X, both runs of `built`'s mesh.
    pub fn distance_to(&self, built: &Built, reference: &ContactRun) -> Result<f64> {
        let dofs = &reference.solution.dofs;
        if self.solution.x.len() != reference.solution.x.len() {
            return Err(Error::Input(
                "the reference run has another mesh: distances need the same mesh".into(),
            ));
        }
        let d: Vec<f64> =
            self.solution.x.iter().zip(&reference.solution.x).map(|(a, b)| a - b).collect();
        let problem = &built.problem;
        Ok((x_norm_squared(problem, dofs, &d)?
            / x_norm_squared(problem, dofs, &reference.solution.x)?)
        .sqrt())
    }

    /// What the figures of the run draw.
    pub fn view<'a>(&'a self, built: &'a Built) -> ContactView<'a> {
        ContactView {
            problem: &built.problem,
            model: &self.model,
            solution: &self.solution,
            rows: &self.rows,
        }
    }

    /// The summary.json document.
    pub fn summary(&self, built: &Built) -> Value {
        let mut summary = common_summary(built, &self.solution.dofs);
        merge(&mut summary, contact_summary(&self.model, &self.solution, &self.rows));
        summary["timings_seconds"]["solver"] = json!(self.seconds);
        summary["timings_seconds"]["case"] = json!(built.seconds);
        summary["warnings"] = json!(built.warnings);
        summary["method"] = json!(built.method_name());
        let lags = built.settings.method.lags_contact();
        summary["hencky_tangent"] = json!(hencky_tangent(&self.solution, lags));
        let names = built.problem.support_names();
        summary["reactions"] = reactions_json(&names, &self.solution.balance.supports);
        let (dofs, x, charges) =
            (&self.solution.dofs, &self.solution.x, &self.solution.balance.charges);
        summary["electrodes"] = electrodes_json(built, dofs, x, charges);
        summary
    }

    /// Writes the run's files into `out` (created if needed) as [`crate::run::Run::write`]
    /// does for one contact solve (a sweep's runs); returns summary.json's document.
    pub fn write(&self, built: &Built, out: &Path, vtu: Encoding) -> Result<Value> {
        let mut outputs = Outputs::new(out, vtu)?;
        self.write_files(built, &mut outputs)?;
        outputs.finish(built, self.summary(built))
    }

    /// Writes the files of the run but summary.json into `outputs`: contact.csv and
    /// solution.vtu, and for a 3D body the map of Γ3 (contact_map.png and .svg).
    pub(super) fn write_files(&self, built: &Built, outputs: &mut Outputs) -> Result<()> {
        let (problem, solution) = (&built.problem, &self.solution);
        let dim = problem.mesh.dim();
        outputs.file("contact.csv", || Ok(report::contact_csv(&self.rows, dim).into_bytes()))?;
        let fields = ContactFields::new(&problem.mesh, &solution.surface, &self.rows);
        outputs.solution(problem, (&solution.dofs, &solution.x), &fields.fields())?;
        if dim == 3 {
            let units = &built.units;
            let title = if built.title.is_empty() { "Γ3" } else { built.title.as_str() };
            let labels = MapLabels { title, length: &units.length, stress: &units.stress };
            outputs.timed("contact_map", |dir| {
                plot::contact_map(&self.view(built), &labels, &dir.join("contact_map"))
            })?;
        }
        Ok(())
    }
}

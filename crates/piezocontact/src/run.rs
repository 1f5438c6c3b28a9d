//! One contact run of a case: solve, assess, summarise and write its results — what
//! `piezocontact run`, `sweep` and `reproduce` do for each case, and what a library user calls.

use crate::algorithm::{ContactSolution, Progress, Settings, solve_contact_with};
use crate::assembly::x_norm_squared;
use crate::case::{Built, Case};
use crate::contact::{ContactModel, NodeStatus};
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::linalg::LinearSolver;
use crate::output::files;
use crate::output::plot::{self, MapLabels};
use crate::output::vtu::Field;
use crate::problem::Problem;
use crate::report::{self, Row};
use crate::solver::{StaticSolution, solve_without_contact};
use serde_json::{Value, json};
use std::path::Path;
use std::time::Instant;

/// A solved contact case with its assessment.
pub struct ContactRun {
    /// The checked problem.
    pub problem: Problem,
    /// Its contact model.
    pub model: ContactModel,
    /// The algorithms' result (converged or not: see `solution.failure`).
    pub solution: ContactSolution,
    /// The Γ3 table, ordered along Γ3.
    pub rows: Vec<Row>,
    /// The algorithms' settings.
    pub settings: Settings,
    /// The case's warnings (the paper's hypotheses, unused keys).
    pub warnings: Vec<String>,
    /// Wall time of the solve and the assessment \[s\].
    pub seconds: f64,
}

impl ContactRun {
    /// Solves a case that has a `[contact]` table and contact parts, with the default linear
    /// solver.
    pub fn solve(case: &Case) -> Result<Self> {
        Self::solve_with(case, case.linear_solver()?, &|_| {})
    }

    /// [`ContactRun::solve`] with the caller's linear `solver`, telling `progress` of each
    /// outer step and inner iteration.
    pub fn solve_with(
        case: &Case,
        solver: Box<dyn LinearSolver>,
        progress: &(dyn Fn(Progress) + Sync),
    ) -> Result<Self> {
        Self::solve_built(case, case.build()?, solver, progress)
    }

    /// [`ContactRun::solve_with`] on a case already built; one with a loading path is refused
    /// ([`Case::path_in_one_run`]).
    pub fn solve_built(
        case: &Case,
        built: Built,
        solver: Box<dyn LinearSolver>,
        progress: &(dyn Fn(Progress) + Sync),
    ) -> Result<Self> {
        if built.loading.is_some() {
            return Err(case.path_in_one_run());
        }
        let start = Instant::now();
        let Built { problem, model, settings, warnings, .. } = built;
        let model = contact_model(case, &problem, model)?;
        let solution = solve_contact_with(&problem, &model, &settings, solver, progress)
            .map_err(|e| case.context(e))?;
        let rows = report::rows(&problem, &model, &solution);
        Ok(Self {
            problem,
            model,
            solution,
            rows,
            settings,
            warnings,
            seconds: start.elapsed().as_secs_f64(),
        })
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

    /// ‖x − x_ref‖_X / ‖x_ref‖_X, both runs on the same mesh.
    pub fn distance_to(&self, reference: &ContactRun) -> Result<f64> {
        let dofs = &reference.solution.dofs;
        if self.solution.x.len() != reference.solution.x.len() {
            return Err(Error::Input(
                "the reference run has another mesh: distances need the same mesh".into(),
            ));
        }
        let d: Vec<f64> =
            self.solution.x.iter().zip(&reference.solution.x).map(|(a, b)| a - b).collect();
        Ok((x_norm_squared(&reference.problem, dofs, &d)?
            / x_norm_squared(&reference.problem, dofs, &reference.solution.x)?)
        .sqrt())
    }

    /// The summary.json document.
    pub fn summary(&self, case: &Case) -> Value {
        let mut summary = common_summary(case, &self.problem, &self.solution.dofs);
        merge(&mut summary, report::contact_summary(&self.model, &self.solution, &self.rows));
        summary["timings_seconds"]["total"] = json!(self.seconds);
        summary["warnings"] = json!(self.warnings);
        summary["method"] = json!(self.settings.method.name());
        let lags = self.settings.method.lags_contact();
        summary["hencky_tangent"] = json!(report::hencky_tangent(&self.solution, lags));
        summary
    }

    /// Writes the files of a contact run into `out`: contact.csv, summary.json and
    /// solution.vtu, and for a 3D body the map of Γ3 (contact_map.png and .svg).
    pub fn write(&self, case: &Case, out: &Path) -> Result<()> {
        self.write_with_summary(case, out, &self.summary(case))
    }

    /// [`ContactRun::write`] with `summary` as summary.json (a loading path's, which adds the
    /// path to the last step's).
    pub fn write_with_summary(&self, case: &Case, out: &Path, summary: &Value) -> Result<()> {
        self.write_results(out, summary)?;
        if self.problem.mesh.dim() == 3 {
            let units = &case.file.units;
            let title = if case.file.title.is_empty() { "Γ3" } else { case.file.title.as_str() };
            let labels = MapLabels { title, length: &units.length, stress: &units.stress };
            plot::contact_map(self, &labels, &out.join("contact_map"))?;
        }
        Ok(())
    }

    /// contact.csv, `summary` as summary.json, and solution.vtu.
    fn write_results(&self, out: &Path, summary: &Value) -> Result<()> {
        std::fs::create_dir_all(out).map_err(|e| Error::Io {
            what: format!("cannot create {}", out.display()),
            cause: e.to_string(),
        })?;
        let (problem, solution) = (&self.problem, &self.solution);
        let fields = ContactFields::new(problem, solution, &self.rows);
        let csv = report::contact_csv(&self.rows, problem.mesh.dim());
        files::write_atomic(&out.join("contact.csv"), csv.as_bytes())?;
        let extra = fields.fields();
        files::write_results(out, summary, problem, &solution.dofs, &solution.x, &extra)
    }
}

/// The contact fields of solution.vtu at every node (0 off Γ3).
pub struct ContactFields {
    /// 1 separated, 2 contact or stick, 3 slip.
    status: Vec<f64>,
    /// −σ_ν [stress].
    pressure: Vec<f64>,
    /// σ_τ, 3 components [stress].
    traction: Vec<f64>,
    /// The gap [length].
    gap: Vec<f64>,
}

impl ContactFields {
    /// The fields of `solution` with its Γ3 `rows`.
    pub fn new(problem: &Problem, solution: &ContactSolution, rows: &[Row]) -> Self {
        let n = problem.mesh.n_nodes();
        let (mut status, mut pressure, mut gap) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut traction = vec![0.0; 3 * n];
        for (row, &node) in rows.iter().zip(&solution.surface.nodes) {
            status[node] = match row.status {
                NodeStatus::Separated => 1.0,
                NodeStatus::Contact | NodeStatus::Stick => 2.0,
                NodeStatus::Slip => 3.0,
            };
            pressure[node] = -row.sigma_nu;
            gap[node] = row.gap;
            traction[3 * node..3 * node + 3].copy_from_slice(&row.friction_traction);
        }
        Self { status, pressure, traction, gap }
    }

    /// As point fields of a .vtu file.
    pub fn fields(&self) -> [Field<'_>; 4] {
        [
            Field { name: "contact_status", components: 1, values: &self.status },
            Field { name: "contact_pressure", components: 1, values: &self.pressure },
            Field { name: "friction_traction", components: 3, values: &self.traction },
            Field { name: "gap", components: 1, values: &self.gap },
        ]
    }
}

/// The contact model of a built case, refused without a `[contact]` table or without
/// contact parts.
pub fn contact_model(
    case: &Case,
    problem: &Problem,
    model: Option<ContactModel>,
) -> Result<ContactModel> {
    let model = model.ok_or_else(|| {
        Error::Input(format!("{}: the case has no [contact] table", case.path.display()))
    })?;
    if problem.boundary.contact.is_empty() {
        return Err(Error::Input(format!(
            "{}: [contact] is given but boundary.contact names no boundary part",
            case.locate("boundary")
        )));
    }
    Ok(model)
}

/// A solved case without contact (no `[contact]` table: Γ3, if named, is free).
pub struct StaticRun {
    /// The checked problem.
    pub problem: Problem,
    /// The solution.
    pub solution: StaticSolution,
    /// max ‖u‖ over the nodes \[length\].
    pub max_u: f64,
    /// The smallest and the largest nodal ϕ \[potential\].
    pub phi_range: (f64, f64),
    /// Wall time \[s\].
    pub seconds: f64,
}

impl StaticRun {
    /// Solves the coupled problem of a case without contact.
    pub fn solve(case: &Case) -> Result<Self> {
        let start = Instant::now();
        let problem = case.problem()?;
        let solution =
            solve_without_contact(&problem, case.linear_solver()?).map_err(|e| case.context(e))?;
        let (dofs, x) = (&solution.dofs, &solution.x);
        let (dim, n) = (problem.mesh.dim(), problem.mesh.n_nodes());
        let max_u = (0..n)
            .map(|a| (0..dim).map(|i| x[dofs.u(a, i)].powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let phi_range = (0..n)
            .map(|a| x[dofs.phi(a)])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
        let seconds = start.elapsed().as_secs_f64();
        Ok(Self { problem, solution, max_u, phi_range, seconds })
    }

    /// The summary.json document.
    pub fn summary(&self, case: &Case) -> Value {
        let (solution, t) = (&self.solution, self.solution.timings);
        let mut summary = common_summary(case, &self.problem, &solution.dofs);
        merge(
            &mut summary,
            json!({
                "problem": "coupled electro-elastic, no contact",
                "converged": true,
                "norms": {
                    "max_abs_u": self.max_u,
                    "min_phi": self.phi_range.0,
                    "max_phi": self.phi_range.1,
                    "relative_residual": solution.relative_residual,
                },
                "timings_seconds": report::timings(&t),
                "memory": report::memory(&t),
            }),
        );
        summary["timings_seconds"]["total"] = json!(self.seconds);
        summary
    }

    /// Writes summary.json and solution.vtu into `out`.
    pub fn write(&self, case: &Case, out: &Path) -> Result<()> {
        let (problem, solution) = (&self.problem, &self.solution);
        files::write_results(out, &self.summary(case), problem, &solution.dofs, &solution.x, &[])
    }
}

/// The summary.json of a validated case that the solver refused before it had a result (a
/// factor too large for the memory, a backend without a capability the method needs): the
/// fields common to every summary (`header`, [`common_summary`]), `converged` false and the
/// `failure`.
pub fn refusal_summary(mut header: Value, case: &Case, failure: &Error) -> Value {
    merge(
        &mut header,
        json!({ "converged": false, "failure": failure.to_string(), "method": case.method_name() }),
    );
    header
}

/// Fields common to every summary.json.
pub fn common_summary(case: &Case, problem: &Problem, dofs: &DofMap) -> Value {
    let units = &case.file.units;
    json!({
        "case": case.path.display().to_string(),
        "title": case.file.title,
        "units": { "length": units.length, "stress": units.stress, "charge": units.charge, "potential": units.potential },
        "dim": problem.mesh.dim(),
        "nodes": problem.mesh.n_nodes(),
        "elements": problem.mesh.n_cells(),
        "dofs": { "total": dofs.n_total(), "free": dofs.n_free(), "free_u": dofs.n_free_u(), "free_phi": dofs.n_free() - dofs.n_free_u() },
        "backend": { "name": case.backend_name(), "processes": crate::linalg::processes() },
        "threads": rayon::current_num_threads(),
    })
}

/// Adds the fields of `b` to the object `a`.
pub fn merge(a: &mut Value, b: Value) {
    if let (Some(a), Value::Object(b)) = (a.as_object_mut(), b) {
        a.extend(b);
    }
}

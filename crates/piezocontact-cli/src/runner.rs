//! One contact run of a case: solve, assess, and write or print its results. Shared by
//! `run`, `sweep` and `reproduce`.

use crate::case::Case;
use crate::output;
use crate::report::{self, Row};
use anyhow::{Result, anyhow};
use piezocontact::algorithm::residual::{Balance, KktResidual, assess};
use piezocontact::algorithm::{ContactModel, ContactSolution, NodeStatus, solve_contact};
use piezocontact::assembly::x_norm_squared;
use piezocontact::dofs::DofMap;
use piezocontact::output::vtu::Field;
use piezocontact::problem::Problem;
use serde_json::{Value, json};
use std::path::Path;
use std::time::Instant;

/// A solved contact case with its assessment.
pub struct ContactRun {
    pub problem: Problem,
    pub model: ContactModel,
    pub solution: ContactSolution,
    pub kkt: KktResidual,
    pub balance: Balance,
    pub rows: Vec<Row>,
    /// Wall time of the solve and the assessment [s].
    pub seconds: f64,
}

impl ContactRun {
    /// Solves a case that has a `[contact]` table and contact parts.
    pub fn solve(case: &Case) -> Result<Self> {
        let start = Instant::now();
        let problem = case.problem()?;
        let model = case
            .contact_model(&problem)?
            .ok_or_else(|| anyhow!("{}: the case has no [contact] table", case.path.display()))?;
        if problem.boundary.contact.is_empty() {
            anyhow::bail!(
                "{}: [contact] is given but boundary.contact names no boundary part",
                case.locate("boundary")
            );
        }
        let settings = case.settings();
        let solution = solve_contact(&problem, &model, &settings)
            .map_err(|e| anyhow!("{}: {e}", case.path.display()))?;
        let (kkt, balance) = assess(&problem, &model, &settings, &solution)?;
        let rows = report::rows(&problem, &model, &solution);
        Ok(Self {
            problem,
            model,
            solution,
            kkt,
            balance,
            rows,
            seconds: start.elapsed().as_secs_f64(),
        })
    }

    /// max |σ_ν| and max |σ_τ| on Γ3 [stress].
    pub fn peaks(&self) -> (f64, f64) {
        let max = |f: fn(&Row) -> f64| self.rows.iter().map(|r| f(r).abs()).fold(0.0, f64::max);
        (max(|r| r.sigma_nu), max(|r| r.sigma_tau))
    }

    /// Measures of the contact, stick and slip zones.
    pub fn zones(&self) -> (f64, f64, f64) {
        report::zone_measures(&self.solution, &self.rows)
    }

    /// ‖x − x_ref‖_X / ‖x_ref‖_X, both runs on the same mesh.
    pub fn distance_to(&self, reference: &ContactRun) -> Result<f64> {
        let dofs = &reference.solution.dofs;
        if self.solution.x.len() != reference.solution.x.len() {
            anyhow::bail!("the reference run has another mesh: distances need the same mesh");
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
        merge(
            &mut summary,
            report::contact_summary(
                &self.model,
                &self.solution,
                &self.kkt,
                &self.balance,
                &self.rows,
            ),
        );
        summary["timings_seconds"]["total"] = json!(self.seconds);
        summary["warnings"] = json!(case.hypothesis_warnings(&self.problem.material));
        summary
    }

    /// Writes contact.csv, summary.json and solution.vtu into `out`.
    pub fn write(&self, case: &Case, out: &Path) -> Result<()> {
        std::fs::create_dir_all(out)
            .map_err(|e| anyhow!("cannot create {}: {e}", out.display()))?;
        let (problem, solution) = (&self.problem, &self.solution);
        let mut status = vec![0.0; problem.mesh.n_nodes()];
        let mut pressure = vec![0.0; problem.mesh.n_nodes()];
        for (row, &node) in self.rows.iter().zip(&solution.surface.nodes) {
            status[node] = match row.status {
                NodeStatus::Separated => 1.0,
                NodeStatus::Contact | NodeStatus::Stick => 2.0,
                NodeStatus::Slip => 3.0,
            };
            pressure[node] = -row.sigma_nu;
        }
        let extra = [
            Field { name: "contact_status", components: 1, values: &status },
            Field { name: "contact_pressure", components: 1, values: &pressure },
        ];
        output::write_atomic(&out.join("contact.csv"), report::contact_csv(&self.rows).as_bytes())?;
        output::write_results(
            out,
            &self.summary(case),
            problem,
            &solution.dofs,
            &solution.x,
            &extra,
        )
    }

    /// Prints the run's figures, each with its unit.
    pub fn print(&self, case: &Case, out: &Path) {
        let (units, solution, kkt) = (&case.file.units, &self.solution, &self.kkt);
        let (sigma_nu, sigma_tau) = self.peaks();
        let (c, st, sl) = self.zones();
        let t = solution.timings;
        println!(
            "{}: {}, {} nodes, {} elements",
            case.path.display(),
            self.model.name(),
            self.problem.mesh.n_nodes(),
            self.problem.mesh.n_cells()
        );
        println!(
            "  outer iterations   = {} ({})",
            solution.outer_iterations,
            if solution.converged { "converged" } else { "NOT converged" }
        );
        println!("  inner iterations   = {:?}", solution.inner_iterations);
        println!("  max |sigma_nu|     = {sigma_nu:.6e} {}", units.stress);
        println!("  max |sigma_tau|    = {sigma_tau:.6e} {}", units.stress);
        println!("  contact / stick / slip measure = {c:.4} / {st:.4} / {sl:.4} {}", units.length);
        println!(
            "  KKT residual       = {:.3e} (equilibrium u {:.1e}, phi {:.1e}; contact {:.1e}; friction {:.1e})",
            kkt.max, kkt.equilibrium_u, kkt.equilibrium_phi, kkt.contact, kkt.friction
        );
        println!("  force balance      = relative imbalance {:.1e}", self.balance.imbalance);
        println!(
            "  time: assembly {:.3} s, symbolic {:.3} s, numeric {:.3} s ({} factorisations), solves {:.3} s ({}), total {:.3} s",
            t.assembly,
            t.symbolic,
            t.numeric,
            t.numeric_count,
            t.solve,
            t.solve_count,
            self.seconds
        );
        println!("  wrote contact.csv, summary.json, solution.vtu in {}", out.display());
    }
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
    })
}

/// Adds the fields of `b` to the object `a`.
pub fn merge(a: &mut Value, b: Value) {
    if let (Some(a), Value::Object(b)) = (a.as_object_mut(), b) {
        a.extend(b);
    }
}

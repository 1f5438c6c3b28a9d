//! A solve of a built case without contact (no `[contact]` table: Γ3, if named, is free).

use crate::algorithm::residual::{Reactions, reactions_without_contact};
use crate::assembly::secant_moduli;
use crate::case::Built;
use crate::error::Result;
use crate::linalg::LinearSolver;
use crate::output::files;
use crate::report::summary::{common_summary, memory, merge, reactions_json, timings};
use crate::system::{StaticSolution, solve_without_contact};
use serde_json::{Value, json};
use std::path::Path;
use std::time::Instant;

/// A solved case without contact.
pub struct StaticRun {
    /// The solution.
    pub solution: StaticSolution,
    /// max ‖u‖ over the nodes \[length\].
    pub max_u: f64,
    /// The smallest and the largest nodal ϕ \[potential\].
    pub phi_range: (f64, f64),
    /// The reactions of the clamps and supports and the electrodes' charges.
    pub reactions: Reactions,
    /// Elements where Hencky's law departs from its small-strain modulus at this solution
    /// (‖ε^D‖² > t0), which the solve without contact does not follow: 0 for a linear law.
    pub beyond_limit: usize,
    /// Wall time \[s\].
    pub seconds: f64,
}

impl StaticRun {
    /// Solves the coupled problem of `built` without contact with the caller's `solver`.
    pub(super) fn solve(built: &Built, solver: Box<dyn LinearSolver>) -> Result<Self> {
        let start = Instant::now();
        let solution =
            solve_without_contact(&built.problem, solver).map_err(|e| built.context(e))?;
        let reactions =
            reactions_without_contact(&built.problem, &solution.dofs, &solution.x, 1.0)?;
        Self::new(built, (solution, reactions), start)
    }

    /// The run of `solution` with its `reactions`, started at `start`.
    pub(super) fn new(
        built: &Built,
        (solution, reactions): (StaticSolution, Reactions),
        start: Instant,
    ) -> Result<Self> {
        let (dofs, x) = (&solution.dofs, &solution.x);
        let mu1 = built.problem.material.elasticity.mu1;
        let moduli = secant_moduli(&built.problem, dofs, x)?;
        let beyond_limit = moduli.iter().filter(|g| **g != mu1).count();
        let mesh = &built.problem.mesh;
        let (dim, n) = (mesh.dim(), mesh.n_nodes());
        let max_u = (0..n)
            .map(|a| (0..dim).map(|i| x[dofs.u(a, i)].powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let phi_range = (0..n)
            .map(|a| x[dofs.phi(a)])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
        let seconds = start.elapsed().as_secs_f64();
        Ok(Self { solution, max_u, phi_range, reactions, beyond_limit, seconds })
    }

    /// The warning of a solution beyond Hencky's elasticity limit, `None` within it.
    pub fn hencky_warning(&self, built: &Built) -> Option<String> {
        (self.beyond_limit > 0).then(|| {
            format!(
                "{} of {} elements exceed Hencky's elasticity limit (‖ε^D‖² > t0) at this solution, and the solve without contact uses the law at small strain (g = µ1) throughout: there its stresses are larger than Hencky's law gives; lower the loads, or set material.law = \"linear\" to take the linear law as meant",
                self.beyond_limit,
                built.problem.mesh.n_cells()
            )
        })
    }

    /// The summary.json document.
    pub fn summary(&self, built: &Built) -> Value {
        let (solution, t) = (&self.solution, self.solution.timings);
        let mut summary = common_summary(built, &solution.dofs);
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
                "reactions": reactions_json(&built.problem.support_names(), &self.reactions.supports),
                "charges": self.reactions.charges,
                "timings_seconds": timings(&t),
                "memory": memory(&t),
            }),
        );
        summary["timings_seconds"]["total"] = json!(self.seconds);
        let mut warnings = built.warnings.clone();
        warnings.extend(self.hencky_warning(built));
        summary["warnings"] = json!(warnings);
        summary
    }

    /// Writes `summary` as summary.json and solution.vtu into `out`.
    pub(super) fn write(&self, built: &Built, out: &Path, summary: &Value) -> Result<()> {
        let solution = &self.solution;
        files::write_results(out, summary, &built.problem, &solution.dofs, &solution.x, &[])
    }
}

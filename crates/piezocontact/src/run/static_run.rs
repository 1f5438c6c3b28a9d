//! A solve of a built case without contact (no `[contact]` table: Γ3, if named, is free).

use crate::algorithm::residual::{Reactions, reactions_without_contact};
use crate::case::Built;
use crate::error::Result;
use crate::linalg::LinearSolver;
use crate::output::files::Outputs;
use crate::report::summary::{
    common_summary, electrodes_json, linear, memory, merge, reactions_json, timings,
};
use crate::system::{StaticSolution, solve_without_contact};
use serde_json::{Value, json};
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
    /// Wall time of the solve and the assessment \[s\].
    pub seconds: f64,
}

impl StaticRun {
    /// Solves the coupled problem of `built` without contact with the caller's `solver`.
    pub(super) fn solve(built: &Built, solver: Box<dyn LinearSolver>) -> Result<Self> {
        let start = Instant::now();
        let mut solution =
            solve_without_contact(&built.problem, solver).map_err(|e| built.context(e))?;
        let assessed = Instant::now();
        let reactions =
            reactions_without_contact(&built.problem, &solution.dofs, &solution.x, 1.0)?;
        solution.timings.assessment = assessed.elapsed().as_secs_f64();
        Ok(Self::new(built, (solution, reactions), start))
    }

    /// The run of `solution` with its `reactions`, started at `start`.
    pub(super) fn new(
        built: &Built,
        (mut solution, reactions): (StaticSolution, Reactions),
        start: Instant,
    ) -> Self {
        let extremes = Instant::now();
        let (dofs, x) = (&solution.dofs, &solution.x);
        let mesh = &built.problem.mesh;
        let (dim, n) = (mesh.dim(), mesh.n_nodes());
        let max_u = (0..n)
            .map(|a| (0..dim).map(|i| x[dofs.u(a, i)].powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let phi_range = (0..n)
            .map(|a| x[dofs.phi(a)])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
        solution.timings.assessment += extremes.elapsed().as_secs_f64();
        let seconds = start.elapsed().as_secs_f64();
        Self { solution, max_u, phi_range, reactions, seconds }
    }

    /// The summary.json document.
    pub fn summary(&self, built: &Built) -> Value {
        let (solution, t) = (&self.solution, &self.solution.timings);
        let mut summary = common_summary(built, &solution.dofs);
        merge(
            &mut summary,
            json!({
                "problem": "coupled electro-elastic, no contact",
                "converged": solution.failure.is_none(),
                "failure": solution.failure.as_ref().map(ToString::to_string),
                "norms": {
                    "max_abs_u": self.max_u,
                    "min_phi": self.phi_range.0,
                    "max_phi": self.phi_range.1,
                    "relative_residual": solution.relative_residual,
                },
                "reactions": reactions_json(&built.problem.support_names(), &self.reactions.supports),
                "charges": self.reactions.charges,
                "electrodes": electrodes_json(built, &solution.dofs, &solution.x, &self.reactions.charges),
                "timings_seconds": timings(t),
                "memory": memory(t),
                "linear": linear(&t.linear),
            }),
        );
        summary["timings_seconds"]["solver"] = json!(self.seconds);
        summary["timings_seconds"]["case"] = json!(built.seconds);
        summary["warnings"] = json!(built.warnings);
        summary["factorisations"] = json!(self.solution.factorisations);
        summary
    }

    /// Writes solution.vtu into `outputs`.
    pub(super) fn write_files(&self, built: &Built, outputs: &mut Outputs) -> Result<()> {
        let solution = &self.solution;
        outputs.solution(&built.problem, (&solution.dofs, &solution.x), &[])
    }
}

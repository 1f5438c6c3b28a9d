//! A loading path of a built case without contact (`[loading]` with `load_factors` and no
//! `[contact]`): one solve without contact per step, every applied load scaled by the step's
//! factor, with one factorisation for the whole path.

use super::path_run::PathRun;
use super::static_run::StaticRun;
use crate::algorithm::residual::{Reactions, reactions_without_contact};
use crate::case::Built;
use crate::contact::Loading;
use crate::error::Result;
use crate::linalg::LinearSolver;
use crate::output::files::{self, Outputs};
use crate::output::plot::{self, LinePlot, PALETTE, Series};
use crate::problem::Factors;
use crate::report::{Column, StaticCurveRow, columns_csv, static_curve_columns};
use crate::system::{StaticSolution, solve_without_contact, solve_without_contact_at};
use plotters::prelude::SeriesLabelPosition;
use serde_json::{Value, json};
use std::path::Path;
use std::time::Instant;

/// A loading path without contact, solved.
pub struct StaticPathRun {
    /// One row per step.
    pub curve: Vec<StaticCurveRow>,
    /// x = (u, ϕ) of each step, for its solution-NNNN.vtu.
    states: Vec<Vec<f64>>,
    /// The last step, as a run: what summary.json and solution.vtu hold.
    pub last: StaticRun,
}

impl StaticPathRun {
    /// Solves the steps of `loading` (load factors only: the foundation that depths move
    /// needs `[contact]`) with the caller's `solver`. With the linear law the problem is
    /// linear (B̌ x = f̌ with the prescribed displacements lifted), so one solve at factor 1
    /// gives every step, x_k = λ_k x_1 — loads and prescribed displacements scaled alike;
    /// with Hencky's law each step is solved, from the last one's secant moduli.
    pub(super) fn solve(
        built: &Built,
        loading: &Loading,
        solver: Box<dyn LinearSolver>,
    ) -> Result<Self> {
        let start = Instant::now();
        let problem = &built.problem;
        let factors: Vec<f64> = loading.steps.iter().map(|s| s.load_factor).collect();
        let steps: Vec<Factors> = loading.steps.iter().map(|s| s.factors()).collect();
        // A linear body's path is its solution at factor 1 scaled, where one factor scales all.
        let one_factor = loading.steps.iter().all(|s| s.electrode_factor == s.load_factor);
        let solutions = if problem.materials.is_linear() && one_factor {
            let unit = solve_without_contact(problem, solver);
            let unit = unit.map_err(|e| built.context(e))?;
            let scaled = |&factor: &f64| StaticSolution {
                x: unit.x.iter().map(|v| factor * v).collect(),
                ..unit.clone()
            };
            factors.iter().map(scaled).collect()
        } else {
            solve_without_contact_at(problem, solver, &steps).map_err(|e| built.context(e))?
        };
        let mut curve = Vec::with_capacity(factors.len());
        let mut last_reactions = Reactions::default();
        for (k, (solution, &load_factor)) in solutions.iter().zip(&factors).enumerate() {
            let (dofs, x) = (&solution.dofs, &solution.x);
            let reactions = reactions_without_contact(problem, dofs, x, load_factor)?;
            curve.push(StaticCurveRow {
                step: k + 1,
                load_factor,
                reaction: reactions.total.clone(),
                supports: reactions.supports.clone(),
                charges: reactions.charges.clone(),
                potentials: reactions.potentials.clone(),
            });
            last_reactions = reactions;
        }
        let states: Vec<Vec<f64>> = solutions.iter().map(|s| s.x.clone()).collect();
        let solution = solutions.into_iter().last().expect("a path has steps");
        let last = StaticRun::new(built, (solution, last_reactions), start);
        Ok(Self { curve, states, last })
    }

    /// Why the path stopped before its end: the step whose secant steps reached their cap.
    pub fn failure(&self) -> Option<String> {
        let failure = self.last.solution.failure.as_ref()?;
        let step = self.curve.len();
        Some(format!(
            "step {step} (load factor {}) did not converge: {failure}",
            self.curve[step - 1].load_factor
        ))
    }

    /// x = (u, ϕ) of each step, in order.
    pub fn states(&self) -> impl Iterator<Item = &[f64]> {
        self.states.iter().map(Vec::as_slice)
    }

    /// The columns of curve.csv.
    pub fn columns(&self, built: &Built) -> Vec<(String, Column)> {
        let parts = PathRun::electrodes(built);
        let supports = built.problem.reported_supports();
        let driven = PathRun::driven_electrodes(built);
        static_curve_columns(&self.curve, built.problem.mesh.dim(), (&supports, &parts, &driven))
    }

    /// The summary.json of the path: the last step's, with the path's steps.
    pub fn summary(&self, built: &Built) -> Value {
        let mut summary = self.last.summary(built);
        summary["path"] = json!({ "steps": built.loading.as_ref().map_or(0, |l| l.steps.len()), "steps_solved": self.curve.len() });
        if let Some(failure) = self.failure() {
            summary["failure"] = json!(failure);
        }
        summary
    }

    /// Writes the last step's solution.vtu, curve.csv, solution-NNNN.vtu per step with
    /// solution.pvd, and the curves' figure (curve.png/.svg) into `outputs`.
    pub(super) fn write_files(&self, built: &Built, outputs: &mut Outputs) -> Result<()> {
        self.last.write_files(built, outputs)?;
        let problem = &built.problem;
        let csv = || Ok(columns_csv(&self.columns(built), self.curve.len()).into_bytes());
        outputs.file("curve.csv", csv)?;
        let (dofs, vtu) = (&self.last.solution.dofs, outputs.vtu);
        let step = |k: usize, path: &Path| {
            files::solution_vtu(problem, (dofs, &self.states[k]), &[], vtu, path)
        };
        outputs.series(self.states.len(), Some(&step))?;
        outputs.timed("curve", |dir| plot::panels(&self.figures(built), &dir.join("curve")))
    }

    /// The clamps' reaction and the electrodes' charges against the load factor.
    fn figures(&self, built: &Built) -> Vec<LinePlot> {
        let (units, dim) = (&built.units, built.problem.mesh.dim());
        let per_depth = if dim == 2 { format!("/{}", units.length) } else { String::new() };
        let area = if dim == 3 { format!("{}²", units.length) } else { units.length.clone() };
        let line = |label: String, k: usize, y: &dyn Fn(&StaticCurveRow) -> f64| Series {
            label,
            points: self.curve.iter().map(|r| (r.load_factor, y(r))).collect(),
            color: PALETTE[k % PALETTE.len()],
            markers: true,
        };
        let plot = |title: &str, y_label: String, series: Vec<Series>| LinePlot {
            title: title.to_string(),
            x_label: "load factor [-]".into(),
            y_label,
            series,
            log_log: false,
            legend: SeriesLabelPosition::UpperLeft,
        };
        let reactions = ["x", "y", "z"][..dim]
            .iter()
            .enumerate()
            .map(|(k, c)| {
                line(format!("reaction_{c}"), k, &move |r: &StaticCurveRow| r.reaction[k])
            })
            .collect();
        let charges = PathRun::electrodes(built)
            .iter()
            .enumerate()
            .map(|(k, p)| line(format!("on {p}"), k + 1, &move |r: &StaticCurveRow| r.charges[k]))
            .collect();
        vec![
            plot("reaction of the clamps", format!("force [{}·{area}]", units.stress), reactions),
            plot(
                "charge on the electrodes",
                format!("charge [{}{per_depth}]", units.charge),
                charges,
            ),
        ]
    }
}

//! The result of Algorithm 1 or 3 ([`ContactSolution`]) and how an outer step adds to it.

use super::inner::InnerResult;
use super::residual::{Balance, KktResidual, SolutionView};
use crate::contact::{ContactModel, ContactState, ContactSurface, NodalFriction, NodeStatus};
use crate::dofs::DofMap;
use crate::error::Error;
use crate::problem::Factors;
use crate::system::Timings;

/// The result of Algorithm 1 or 3.
#[derive(Clone, Debug)]
pub struct ContactSolution {
    /// x = (u, ϕ), global vector.
    pub x: Vec<f64>,
    /// The DOF numbering of `x`.
    pub dofs: DofMap,
    /// Γ3 and its nodal geometry.
    pub surface: ContactSurface,
    /// The factor on the applied loads of the problem solved [-] (1 but on a loading path).
    pub load_factor: f64,
    /// The factor on the electrodes' voltages and charges [-] (the load factor but where a
    /// path gives `electrode_factors`).
    pub electrode_factor: f64,
    /// The multipliers of the last inner solve.
    pub state: ContactState,
    /// s_{n+1} = µ|Rσ_ν(x_{n+1})|: the friction bound of the last outer step \[stress\].
    pub s: Vec<f64>,
    /// σ_ν on the Γ3 nodes \[stress\].
    pub sigma_nu: Vec<f64>,
    /// Each Γ3 node's status: separated where σ_ν ≥ 0, else what the inner method's friction
    /// law said at its last iterate.
    pub status: Vec<NodeStatus>,
    /// Why the loops did not both meet their stopping rules; `None` when they did.
    pub failure: Option<Error>,
    /// Inner iterations of each outer step.
    pub inner_iterations: Vec<usize>,
    /// The outer criterion at each step.
    pub outer_history: Vec<f64>,
    /// The inner criterion at each iteration of each outer step.
    pub inner_history: Vec<Vec<f64>>,
    /// Time spent in each phase.
    pub timings: Timings,
    /// The Γ3 nodes in the exact solver's dense problem at the end (0 for Uzawa).
    pub condensed_nodes: usize,
    /// The residual of the discrete KKT conditions at `x` (model §10).
    pub kkt: KktResidual,
    /// The global force balance at `x`.
    pub balance: Balance,
    /// The state the slip is measured from (global), empty for the static law.
    pub slip_origin: Vec<f64>,
    /// The outer steps in which the exact solver floored Hencky's tangent beyond e·t0
    /// (model §13).
    pub floored_steps: usize,
    /// The outer steps that were chord steps on a kept factorisation of the floored tangent
    /// instead of a factorisation (model §13).
    pub chord_steps: usize,
}

impl ContactSolution {
    /// The state before the first outer step on `surface` with the DOFs `dofs`: x_0 = 0,
    /// λ = 0, s_0 = 0.
    pub(super) fn start(surface: ContactSurface, dofs: DofMap, factors: Factors) -> Self {
        let n3 = surface.len();
        Self {
            kkt: KktResidual::default(),
            balance: Balance::default(),
            condensed_nodes: 0,
            x: vec![0.0; dofs.n_total()],
            dofs,
            surface,
            load_factor: factors.loads,
            electrode_factor: factors.electrodes,
            state: ContactState::cold(n3),
            s: vec![0.0; n3],
            sigma_nu: vec![0.0; n3],
            status: vec![NodeStatus::Separated; n3],
            failure: None,
            inner_iterations: Vec::new(),
            outer_history: Vec::new(),
            inner_history: Vec::new(),
            timings: Timings::default(),
            slip_origin: Vec::new(),
            floored_steps: 0,
            chord_steps: 0,
        }
    }

    /// Whether both loops met their stopping rules.
    pub fn converged(&self) -> bool {
        self.failure.is_none()
    }

    /// Outer iterations, counted as Table 2 counts them: n + 1 at the stop of step n.
    pub fn outer_iterations(&self) -> usize {
        self.inner_iterations.len()
    }

    /// What the assessment reads ([`super::residual::assess`]).
    pub fn view(&self) -> SolutionView<'_> {
        SolutionView {
            x: &self.x,
            dofs: &self.dofs,
            surface: &self.surface,
            load_factor: self.load_factor,
            electrode_factor: self.electrode_factor,
            state: &self.state,
            sigma_nu: &self.sigma_nu,
            s: &self.s,
            slip_origin: &self.slip_origin,
        }
    }

    /// Takes the inner result of a step: x_{n+1}, λ, σ_ν, s_{n+1} = µ|Rσ_ν(x_{n+1})| with
    /// `friction` (zero without), and the statuses. Returns x_n.
    pub(super) fn record(
        &mut self,
        inner: InnerResult,
        model: &ContactModel,
        friction: Option<&NodalFriction>,
    ) -> Vec<f64> {
        self.inner_iterations.push(inner.iterations);
        self.inner_history.push(inner.history);
        let x_previous = std::mem::replace(&mut self.x, inner.x);
        self.state = inner.state;
        self.sigma_nu = self.state.normal_stress(&self.dofs, &self.surface, model, &self.x);
        self.s =
            friction.map_or_else(|| vec![0.0; self.surface.len()], |f| f.bound(&self.sigma_nu));
        let law = |status| friction.is_some().then_some(status);
        self.status = self
            .sigma_nu
            .iter()
            .zip(inner.status)
            .map(|(&s, t)| NodeStatus::at(s, law(t)))
            .collect();
        x_previous
    }

    /// ‖s_{n+1} − s_n‖ / ‖s_{n+1}‖ in L2(Γ3), (6.13), from the bound `s_n` the step was solved
    /// with; `None` when s ≡ 0.
    pub(super) fn friction_bound_change(&self, s_n: &[f64]) -> Option<f64> {
        let w = &self.surface.weight;
        let s_norm: f64 = self.s.iter().zip(w).map(|(s, w)| w * s.powi(2)).sum();
        let ds: f64 = self.s.iter().zip(s_n).zip(w).map(|((s, t), w)| w * (s - t).powi(2)).sum();
        (s_norm > 0.0).then(|| (ds / s_norm).sqrt())
    }
}

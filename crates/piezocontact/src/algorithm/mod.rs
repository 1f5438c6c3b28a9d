//! The fixed-point iterations of [P] Section 6 around the Uzawa loop:
//! Algorithm 1 (PV2: friction and conduction, inner Algorithm 2) and Algorithm 3 (PV1,
//! inner Algorithm 4), as restated in SPEC §7.
//!
//! ```text
//! x_0 = 0, s_0 = 0
//! step n:  g_n = g(‖ε^D(u_n)‖²) per element;  factor B̌(x_n) + r M   (only when g_n changed)
//!          f_{1,n} = f̌ − j̃1(x_n, ·) − ľ(x_n, ·)          (PV1: f̌ − j̃1(x_n, ·))
//!          x_{n+1} = Uzawa(f_{1,n}, s_n)                   (cold start)
//!          s_{n+1} = µ |R σ_ν(x_{n+1})|,  σ_ν = −(λ_c + h_ν(ϕ−ϕ0) p_ν(u_ν − g_a))
//! stop:    ‖s_{n+1} − s_n‖ / ‖s_{n+1}‖ < ε_fp   (6.13, PV2 with s ≢ 0)
//!          ‖x_{n+1} − x_n‖ / ‖x_{n+1}‖ < ε_fp   (6.15, PV1; PV2 when s ≡ 0; and also
//!                                                  whenever the Hencky secant is active)
//! ```
//!
//! The reported number of outer iterations is n + 1 at the stop, as Table 2 counts.
//! Hitting an iteration cap is not a silent stop: the result carries
//! [`Error::NotConverged`] naming the loop and its last criterion. A growing criterion
//! ([`Error::Diverged`]), a singular matrix or a NaN ([`Error::NumericalFailure`]) stop the run
//! the same way, keeping the last finite iterate.

pub mod residual;
pub mod uzawa;

use crate::assembly::{MassNorm, NodalBlock, secant_moduli};
use crate::contact::ContactSurface;
use crate::contact::law::{Conduction, Friction, NormalCompliance, Regularization};
use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::{Error, Result};
use crate::problem::Problem;
use crate::solver::{CoupledSystem, Timings};
pub use uzawa::ContactState;
use uzawa::Uzawa;

/// Parameters of the algorithms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// r > 0: augmented Lagrangian parameter [stress/length] (paper: 0.25 E).
    pub r: f64,
    /// ε of (6.12)/(6.16) (paper: 1e−4).
    pub eps: f64,
    /// ε_fp of (6.13)/(6.15) (paper: 1e−4).
    pub eps_fp: f64,
    /// Cap on Uzawa iterations per outer step.
    pub max_inner: usize,
    /// Cap on fixed-point iterations.
    pub max_outer: usize,
}

/// The contact model: normal compliance, and for PV2 friction and conduction.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactModel {
    /// p_ν, h_ν, the gap and the stop.
    pub compliance: NormalCompliance,
    /// `None`: PV1 (frictionless, nonconductive). `Some`: PV2.
    pub pv2: Option<(Friction, Conduction)>,
}

impl ContactModel {
    /// "PV1" or "PV2".
    pub fn name(&self) -> &'static str {
        if self.pv2.is_some() { "PV2" } else { "PV1" }
    }
}

/// The result of Algorithm 1 or 3.
#[derive(Clone, Debug)]
pub struct ContactSolution {
    /// x = (u, ϕ), global vector.
    pub x: Vec<f64>,
    /// The DOF numbering of `x`.
    pub dofs: DofMap,
    /// Γ3 and its nodal geometry.
    pub surface: ContactSurface,
    /// The multipliers of the last Uzawa loop.
    pub state: ContactState,
    /// s_n: the friction bound used in the last Uzawa loop [stress].
    pub s_used: Vec<f64>,
    /// s_{n+1} = µ|Rσ_ν(x_{n+1})|: the friction bound of the last outer step [stress].
    pub s: Vec<f64>,
    /// σ_ν on the Γ3 nodes [stress].
    pub sigma_nu: Vec<f64>,
    /// Whether both loops met their stopping rules.
    pub converged: bool,
    /// Why not, if not.
    pub failure: Option<Error>,
    /// Outer iterations, counted as Table 2 counts them.
    pub outer_iterations: usize,
    /// Uzawa iterations of each outer step.
    pub inner_iterations: Vec<usize>,
    /// The outer criterion at each step.
    pub outer_history: Vec<f64>,
    /// The Uzawa criterion at each iteration of each outer step.
    pub inner_history: Vec<Vec<f64>>,
    /// Time spent in each phase.
    pub timings: Timings,
}

/// Solves PV1 (Algorithm 3 with 4) or PV2 (Algorithm 1 with 2).
pub fn solve_contact(
    problem: &Problem,
    model: &ContactModel,
    settings: &Settings,
) -> Result<ContactSolution> {
    let dofs = DofMap::new(problem)?;
    let surface = ContactSurface::new(problem, &dofs)?;
    let mut system = CoupledSystem::new(problem, &surface.nodes)?;
    let mass = MassNorm::new(problem)?;
    let blocks = step1_blocks(&surface, settings.r, model.pv2.is_some());
    let mollifier = Mollifier::new(problem, &surface, model);
    let mu = model
        .pv2
        .as_ref()
        .map_or_else(Vec::new, |(friction, _)| nodal_mu(problem, &surface, friction));
    let n3 = surface.len();
    let mut solution = ContactSolution {
        x: vec![0.0; dofs.n_total()],
        dofs: dofs.clone(),
        surface: surface.clone(),
        state: ContactState::cold(n3),
        s_used: vec![0.0; n3],
        s: vec![0.0; n3],
        sigma_nu: vec![0.0; n3],
        converged: false,
        failure: None,
        outer_iterations: 0,
        inner_iterations: Vec::new(),
        outer_history: Vec::new(),
        inner_history: Vec::new(),
        timings: Timings::default(),
    };
    let mut g = secant_moduli(problem, &dofs, &solution.x)?;
    let mut factorised_with: Option<Vec<f64>> = None;
    for n in 0..settings.max_outer {
        if factorised_with.as_ref() != Some(&g) {
            if let Err(e) = system.factorize(problem, &g, &blocks) {
                solution.failure = Some(Error::NumericalFailure {
                    what: format!("the factorisation of B̌(x_n) + r M in outer step {}", n + 1),
                    iteration: n + 1,
                    cause: e.to_string(),
                    hint: "check the case with `piezocontact check`; a singular matrix means the \
                           body is not held (Γ1, Γa) or a material constant is not physical"
                        .into(),
                });
                break;
            }
            factorised_with = Some(g.clone());
        }
        let base = lagged_loads(&dofs, &surface, model, &solution.x);
        let s_n = solution.s.clone();
        let uzawa = Uzawa {
            problem,
            dofs: &dofs,
            mass: &mass,
            surface: &surface,
            compliance: &model.compliance,
            friction_bound: model.pv2.as_ref().map(|_| s_n.as_slice()),
            base: &base,
            settings,
        };
        let inner = uzawa.run(&mut system)?;
        solution.inner_iterations.push(inner.iterations);
        solution.inner_history.push(inner.history.clone());
        solution.outer_iterations = n + 1;
        let x_previous = std::mem::replace(&mut solution.x, inner.x);
        solution.state = inner.state;
        solution.s_used = s_n;
        solution.sigma_nu = normal_stress(&dofs, &surface, model, &solution.x, &solution.state);
        solution.s = match &model.pv2 {
            Some(_) => mollifier
                .apply(&solution.sigma_nu)
                .iter()
                .zip(&mu)
                .map(|(sn, mu)| mu * sn.abs())
                .collect(),
            None => vec![0.0; n3],
        };
        let what = format!(
            "the Uzawa loop (Algorithm {}) of outer step {}",
            if model.pv2.is_some() { 2 } else { 4 },
            n + 1
        );
        let r_hint = format!(
            "r too small or too large for this problem: try solver.r = {:.4e} or {:.4e} (now {:.4e}; the paper uses 0.25 E)",
            2.0 * settings.r,
            0.5 * settings.r,
            settings.r
        );
        let failure = match inner.stop {
            uzawa::Stop::Converged => None,
            uzawa::Stop::Cap => Some(Error::NotConverged {
                what,
                iterations: inner.iterations,
                criterion: inner.history.last().copied().unwrap_or(f64::NAN),
                tolerance: settings.eps,
                history: tail(&inner.history),
                hint: format!("raise solver.max_inner (now {}), or {r_hint}", settings.max_inner),
            }),
            uzawa::Stop::Diverged => Some(Error::Diverged {
                what,
                iteration: inner.iterations,
                history: tail(&inner.history),
                hint: r_hint,
            }),
            uzawa::Stop::NotFinite(cause) => Some(Error::NumericalFailure {
                what,
                iteration: inner.iterations,
                cause,
                hint: r_hint,
            }),
        };
        if failure.is_some() {
            solution.failure = failure;
            break;
        }
        let g_next = secant_moduli(problem, &dofs, &solution.x)?;
        let x_criterion = relative_change(problem, &dofs, &mass, &solution.x, &x_previous);
        let s_norm: f64 = (0..n3).map(|i| surface.weight[i] * solution.s[i].powi(2)).sum();
        let criterion = if model.pv2.is_some() && s_norm > 0.0 {
            let ds: f64 = (0..n3)
                .map(|i| surface.weight[i] * (solution.s[i] - solution.s_used[i]).powi(2))
                .sum();
            let s_criterion = (ds / s_norm).sqrt();
            if g_next != g { s_criterion.max(x_criterion) } else { s_criterion }
        } else {
            x_criterion
        };
        solution.outer_history.push(criterion);
        g = g_next;
        if criterion < settings.eps_fp {
            solution.converged = true;
            break;
        }
        if let Some(failure) = outer_failure(model, &solution) {
            solution.failure = Some(failure);
            break;
        }
    }
    if !solution.converged && solution.failure.is_none() {
        solution.failure = Some(Error::NotConverged {
            what: format!(
                "the fixed-point loop (Algorithm {})",
                if model.pv2.is_some() { 1 } else { 3 }
            ),
            iterations: solution.outer_iterations,
            criterion: solution.outer_history.last().copied().unwrap_or(f64::NAN),
            tolerance: settings.eps_fp,
            history: tail(&solution.outer_history),
            hint: format!(
                "raise solver.max_outer (now {}); a criterion that stalls means the lagged contact \
                 terms (h_ν, ψ) are too strong for the fixed point",
                settings.max_outer
            ),
        });
    }
    solution.timings = system.timings();
    Ok(solution)
}

/// The last values of a criterion history, for messages.
fn tail(history: &[f64]) -> String {
    let start = history.len().saturating_sub(5);
    let values: Vec<String> = history[start..].iter().map(|v| format!("{v:.3e}")).collect();
    values.join(", ")
}

/// A non-finite outer criterion or friction bound, or a growing outer criterion.
fn outer_failure(model: &ContactModel, solution: &ContactSolution) -> Option<Error> {
    let n = solution.outer_iterations;
    let what =
        format!("the fixed-point loop (Algorithm {})", if model.pv2.is_some() { 1 } else { 3 });
    let last = *solution.outer_history.last()?;
    let hint = "the lagged contact terms are too strong for the fixed point: reduce \
                conductivity.ke, contact.c_nu or contact.penetration";
    if !last.is_finite() || solution.s.iter().any(|v| !v.is_finite()) {
        let cause = "the criterion or the friction bound s is not finite".into();
        return Some(Error::NumericalFailure { what, iteration: n, cause, hint: hint.into() });
    }
    let smallest = solution.outer_history.iter().copied().fold(f64::INFINITY, f64::min);
    (n >= 3 && last > uzawa::DIVERGENCE * smallest).then(|| Error::Diverged {
        what,
        iteration: n,
        history: tail(&solution.outer_history),
        hint: hint.into(),
    })
}

/// µ on each Γ3 node: the case's µ, or the mean of the µ of the parts a node belongs to.
fn nodal_mu(problem: &Problem, surface: &ContactSurface, friction: &Friction) -> Vec<f64> {
    let mut sum = vec![0.0; surface.len()];
    let mut count = vec![0usize; surface.len()];
    let index: std::collections::HashMap<usize, usize> =
        surface.nodes.iter().enumerate().map(|(i, &n)| (n, i)).collect();
    for &(part, mu) in &friction.mu_parts {
        let mut nodes: Vec<usize> = problem.mesh.part_facets(part).flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        for i in nodes.iter().filter_map(|n| index.get(n)) {
            sum[*i] += mu;
            count[*i] += 1;
        }
    }
    (0..surface.len())
        .map(|i| if count[i] > 0 { sum[i] / count[i] as f64 } else { friction.mu })
        .collect()
}

/// State of a Γ3 node at the solution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeStatus {
    /// σ_ν = 0: no contact force.
    Separated,
    /// σ_ν < 0 in PV1.
    Contact,
    /// PV2, σ_ν < 0 and ‖λ_f‖ < s: u_τ = 0.
    Stick,
    /// PV2, σ_ν < 0 and ‖λ_f‖ = s.
    Slip,
}

impl NodeStatus {
    /// The name used in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Self::Separated => "separated",
            Self::Contact => "contact",
            Self::Stick => "stick",
            Self::Slip => "slip",
        }
    }
}

impl ContactSolution {
    /// The status of Γ3 node i: separated when σ_ν = 0; in PV2 slip when λ_f is on the
    /// friction bound s_n of the last Uzawa loop (to a relative 1e−9), stick otherwise.
    pub fn status(&self, i: usize, pv2: bool) -> NodeStatus {
        if self.sigma_nu[i] >= 0.0 {
            return NodeStatus::Separated;
        }
        if !pv2 {
            return NodeStatus::Contact;
        }
        let traction = self.state.lambda_f[i].iter().map(|v| v * v).sum::<f64>().sqrt();
        if traction >= self.s_used[i] * (1.0 - 1e-9) { NodeStatus::Slip } else { NodeStatus::Stick }
    }
}

/// r M on the Γ3 nodes: r w_i I with friction (Algorithm 2), r w_i ν_i ν_iᵀ without (Algorithm 4).
fn step1_blocks(surface: &ContactSurface, r: f64, friction: bool) -> Vec<NodalBlock> {
    (0..surface.len())
        .map(|i| {
            let (w, n) = (surface.weight[i], surface.normal[i]);
            let mut block = [[0.0; 3]; 3];
            for a in 0..surface.dim() {
                for b in 0..surface.dim() {
                    let identity = if a == b && friction { 1.0 } else { 0.0 };
                    block[a][b] = r * w * if friction { identity } else { n[a] * n[b] };
                }
            }
            block
        })
        .collect()
}

/// −j̃1(x_n, ·) − ľ(x_n, ·) on the free DOFs (nodal quadrature on Γ3): −w h_ν p_ν ν on the u
/// rows; + w ψ φ_L on the ϕ row (PV2 only).
fn lagged_loads(
    dofs: &DofMap,
    surface: &ContactSurface,
    model: &ContactModel,
    x: &[f64],
) -> Vec<f64> {
    let mut base = vec![0.0; dofs.n_free()];
    for i in 0..surface.len() {
        let (u_nu, _) = surface.split(dofs, x, i);
        let phi = surface.phi(dofs, x, i);
        let (w, node) = (surface.weight[i], surface.nodes[i]);
        let pressure = model.compliance.pressure(u_nu, phi);
        for c in 0..surface.dim() {
            let k = dofs.free_index(dofs.u(node, c));
            if k != CONSTRAINED {
                base[k] -= w * pressure * surface.normal[i][c];
            }
        }
        if let Some((_, conduction)) = &model.pv2 {
            let k = dofs.free_index(dofs.phi(node));
            if k != CONSTRAINED {
                base[k] += w * conduction.flux(u_nu, phi, model.compliance.gap);
            }
        }
    }
    base
}

/// σ_ν = −(λ_c + h_ν(ϕ − ϕ0) p_ν(u_ν − g_a)) on the Γ3 nodes (SPEC §6).
pub fn normal_stress(
    dofs: &DofMap,
    surface: &ContactSurface,
    model: &ContactModel,
    x: &[f64],
    state: &ContactState,
) -> Vec<f64> {
    (0..surface.len())
        .map(|i| {
            let (u_nu, _) = surface.split(dofs, x, i);
            -(state.lambda_c[i] + model.compliance.pressure(u_nu, surface.phi(dofs, x, i)))
        })
        .collect()
}

/// ‖a − b‖ / ‖a‖ in the L2(Ω) norm of (6.15).
fn relative_change(problem: &Problem, dofs: &DofMap, mass: &MassNorm, a: &[f64], b: &[f64]) -> f64 {
    let difference: Vec<f64> = a.iter().zip(b).map(|(p, q)| p - q).collect();
    let norm = mass.squared(problem, dofs, a);
    if norm > 0.0 { (mass.squared(problem, dofs, &difference) / norm).sqrt() } else { 0.0 }
}

/// The regularisation R as a sparse averaging operator on the Γ3 nodes.
struct Mollifier {
    /// For each node, (j, weight) with weights summing to 1; empty for R = identity.
    rows: Vec<Vec<(usize, f64)>>,
}

impl Mollifier {
    fn new(problem: &Problem, surface: &ContactSurface, model: &ContactModel) -> Self {
        let Some((Friction { regularization: Regularization::Mollifier { radius }, .. }, _)) =
            &model.pv2
        else {
            return Self { rows: Vec::new() };
        };
        let rows = (0..surface.len())
            .map(|i| {
                let xi = surface.position(problem, i);
                let mut row: Vec<(usize, f64)> = (0..surface.len())
                    .filter_map(|j| {
                        let xj = surface.position(problem, j);
                        let d2: f64 = xi.iter().zip(xj).map(|(a, b)| (a - b).powi(2)).sum();
                        let t = d2 / (radius * radius);
                        (t < 1.0).then(|| (j, surface.weight[j] * (1.0 - t).powi(2)))
                    })
                    .collect();
                let total: f64 = row.iter().map(|(_, w)| w).sum();
                row.iter_mut().for_each(|(_, w)| *w /= total);
                row
            })
            .collect();
        Self { rows }
    }

    fn apply(&self, sigma_nu: &[f64]) -> Vec<f64> {
        if self.rows.is_empty() {
            return sigma_nu.to_vec();
        }
        self.rows.iter().map(|row| row.iter().map(|&(j, w)| w * sigma_nu[j]).sum()).collect()
    }
}

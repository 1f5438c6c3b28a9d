//! How accurate a contact solution is (model §10): the true residual of the discrete problem
//! with the true Hencky law, the natural residuals of the contact and friction conditions,
//! and the global force balance.
//!
//! At a solution of the discrete problem,
//!
//! ```text
//! R = F_int(x) − f̌ − F_c − Q = 0 on the free DOFs,
//! F_c,i = w_i (σ_ν,i ν_i + σ_τ,i),  σ_ν = −(λ_c + h_ν p_ν),  σ_τ = −λ_f       (u rows of Γ3)
//! Q_i   = w_i ψ(u_ν − g_a) φ_L(ϕ − ϕ0)                                      (ϕ rows, PV2)
//! λ_c = max(0, λ_c + c(u_ν − ρ)),   λ_f = P_{B(0,s)}(λ_f + c u_τ),  s = µ|Rσ_ν(x)|
//! ```
//!
//! The last two are the complementarity and Coulomb conditions written as projections, with the
//! method's constant c ([`super::InnerMethod::complementarity_constant`], the case's r); their
//! defects divided by c are lengths, reported relative to max ‖u‖.

use crate::assembly::{internal_force, load_vector, secant_moduli};
use crate::contact::law::{coulomb, stop_complementarity};
use crate::contact::{ContactModel, ContactState, ContactSurface};
use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::Result;
use crate::problem::Problem;

/// Relative residuals of the discrete problem.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct KktResidual {
    /// ‖R_u‖ / ‖row scale‖ over the free u rows (equilibrium, true law).
    pub equilibrium_u: f64,
    /// ‖R_ϕ‖ / ‖row scale‖ over the free ϕ rows (Gauss's law).
    pub equilibrium_phi: f64,
    /// max_i |λ_c − max(0, λ_c + c(u_ν − ρ))| / c / max‖u‖.
    pub contact: f64,
    /// max_i ‖λ_f − P_s(λ_f + c u_τ)‖ / c / max‖u‖, with s = µ|Rσ_ν(x)| (PV2).
    pub friction: f64,
    /// max_i (u_ν − ρ)₊ \[length\].
    pub penetration: f64,
    /// The largest of the four relative residuals.
    pub max: f64,
}

/// Resultant forces on the body [stress·length^(d−1)], d components.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Balance {
    /// Applied loads: ∫ f0 + ∫Γ2 f2.
    pub applied: Vec<f64>,
    /// Force of the foundation on the body: Σ_i w_i (σ_ν ν + σ_τ).
    pub contact: Vec<f64>,
    /// Reactions of the clamp on Γ1 and of the supports, in all.
    pub reaction: Vec<f64>,
    /// The reaction of each clamp and support, in the order of [`Problem::support_names`].
    pub supports: Vec<Vec<f64>>,
    /// |applied + contact + reaction| / (|applied| + |contact| + |reaction|).
    pub imbalance: f64,
    /// The charge on each part of Γa (in the order of `boundary.grounded`): the reaction of
    /// the electric equation, what an electrometer between it and ground reads; a node shared
    /// by two parts counts in the first [charge·length^(3−d)].
    pub charges: Vec<f64>,
    /// The potential of each electrode beyond the grounded parts \[potential\].
    pub potentials: Vec<f64>,
}

/// What the assessment reads of a contact solution.
pub struct SolutionView<'a> {
    /// x = (u, ϕ), global.
    pub x: &'a [f64],
    /// The DOF numbering of x.
    pub dofs: &'a DofMap,
    /// Γ3 with its gaps.
    pub surface: &'a ContactSurface,
    /// The factor on the applied loads [-].
    pub load_factor: f64,
    /// The factor on the electrodes' voltages and charges [-].
    pub electrode_factor: f64,
    /// λ_c, λ_f.
    pub state: &'a ContactState,
    /// σ_ν on the Γ3 nodes \[stress\].
    pub sigma_nu: &'a [f64],
    /// s = µ|Rσ_ν(x)| on the Γ3 nodes \[stress\].
    pub s: &'a [f64],
    /// The state the slip is measured from (global), empty for the static law.
    pub slip_origin: &'a [f64],
}

/// Residuals and balance of a contact solution, with the complementarity constant c =
/// `constant` [stress/length].
pub fn assess(
    problem: &Problem,
    model: &ContactModel,
    constant: f64,
    solution: &SolutionView,
) -> Result<(KktResidual, Balance)> {
    let (dofs, x) = (solution.dofs, solution.x);
    let dim = problem.mesh.dim();
    let g = secant_moduli(problem, dofs, x)?;
    let (f_int, scale) = internal_force(problem, dofs, x, &g)?;
    let f_ext = load_vector(problem, dofs, solution.load_factor);
    let (contact_force, mut kkt) = contact_conditions(problem, model, constant, solution);
    let (mut r_u, mut s_u, mut r_phi, mut s_phi) = (0.0, 0.0, 0.0, 0.0);
    let mut balance = Balance {
        applied: vec![0.0; dim],
        contact: vec![0.0; dim],
        reaction: vec![0.0; dim],
        supports: Vec::new(),
        imbalance: 0.0,
        charges: Vec::new(),
        potentials: Vec::new(),
    };
    // The radial forces of a body of revolution sum to no resultant: only y counts.
    let first = usize::from(problem.axisymmetric);
    for gdof in (0..dim * problem.mesh.n_nodes()).filter(|g| g % dim >= first) {
        balance.applied[gdof % dim] += f_ext[gdof];
        balance.contact[gdof % dim] += contact_force[gdof];
    }
    let mut row_scale: Vec<f64> =
        (0..dofs.n_total()).map(|g| scale[g] + f_ext[g].abs() + contact_force[g].abs()).collect();
    let mut residual: Vec<f64> =
        (0..dofs.n_total()).map(|g| f_int[g] - f_ext[g] - contact_force[g]).collect();
    dofs.to_frames(&mut residual);
    dofs.frame_bound(&mut row_scale);
    dofs.sum_floating(&mut residual, &mut row_scale, solution.electrode_factor);
    for gdof in 0..dofs.n_total() {
        let (residual, row_scale) = (residual[gdof], row_scale[gdof]);
        let is_u = gdof < dim * problem.mesh.n_nodes();
        match (dofs.free_index(gdof) == CONSTRAINED, is_u) {
            (true, _) => {}
            (false, true) => {
                r_u += residual * residual;
                s_u += row_scale * row_scale;
            }
            (false, false) => {
                r_phi += residual * residual;
                s_phi += row_scale * row_scale;
            }
        }
    }
    let reactions = reactions(problem, (dofs, x), (&f_int, &f_ext), &contact_force);
    (balance.reaction, balance.supports, balance.charges, balance.potentials) =
        (reactions.total, reactions.supports, reactions.charges, reactions.potentials);
    let ratio = |r: f64, s: f64| if s > 0.0 { (r / s).sqrt() } else { r.sqrt() };
    kkt.equilibrium_u = ratio(r_u, s_u);
    kkt.equilibrium_phi = ratio(r_phi, s_phi);
    kkt.max = kkt.equilibrium_u.max(kkt.equilibrium_phi).max(kkt.contact).max(kkt.friction);
    let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let total: Vec<f64> =
        (0..dim).map(|c| balance.applied[c] + balance.contact[c] + balance.reaction[c]).collect();
    let size = norm(&balance.applied) + norm(&balance.contact) + norm(&balance.reaction);
    balance.imbalance = if size > 0.0 { norm(&total) / size } else { 0.0 };
    Ok((kkt, balance))
}

/// The contact forces and fluxes on the Γ3 rows, Q_c = F_c + Q (module docs), and the
/// contact, friction and penetration parts of the KKT residual.
fn contact_conditions(
    problem: &Problem,
    model: &ContactModel,
    constant: f64,
    solution: &SolutionView,
) -> (Vec<f64>, KktResidual) {
    let dofs = solution.dofs;
    let (surface, state, x) = (solution.surface, solution.state, solution.x);
    let dim = problem.mesh.dim();
    let mut contact_force = vec![0.0; dofs.n_total()];
    let mut kkt = KktResidual::default();
    let max_u = (0..problem.mesh.n_nodes())
        .map(|a| (0..dim).map(|c| x[dofs.u(a, c)].powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for i in 0..surface.len() {
        let (u_nu, mut u_tau) = surface.split(dofs, x, i);
        if !solution.slip_origin.is_empty() {
            let (_, origin) = surface.split(dofs, solution.slip_origin, i);
            (0..3).for_each(|k| u_tau[k] -= origin[k]);
        }
        let phi = surface.phi(dofs, x, i);
        let (w, node) = (surface.weight[i], surface.nodes[i]);
        for c in 0..dim {
            contact_force[dofs.u(node, c)] +=
                w * (solution.sigma_nu[i] * surface.normal[i][c] - state.lambda_f[i][c]);
        }
        let (lambda_c, rho) = (state.lambda_c[i], model.compliance.stop(surface.gap[i]));
        let projected = stop_complementarity(lambda_c, constant, u_nu, rho).projected;
        kkt.contact = kkt.contact.max((lambda_c - projected).abs() / constant / max_u);
        kkt.penetration = kkt.penetration.max(u_nu - rho);
        if model.conduction.is_some() {
            contact_force[dofs.phi(node)] += w * model.flux(u_nu, phi, surface.gap[i]);
        }
        if model.friction.is_some() {
            let z = [0, 1, 2].map(|k| state.lambda_f[i][k] + constant * u_tau[k]);
            let (p, _) = coulomb(z, solution.s[i]);
            let defect = (0..3).map(|k| (state.lambda_f[i][k] - p[k]).powi(2)).sum::<f64>().sqrt();
            kkt.friction = kkt.friction.max(defect / constant / max_u);
        }
    }
    (contact_force, kkt)
}

/// The reactions of the constrained rows of the state `x`, from the internal and applied
/// forces (`f_int`, `f_ext`) and the contact forces and fluxes on the Γ3 rows: the force of
/// the clamps on the body (d components, [stress·length^(d−1)]) and the charge on each part
/// of Γa and each electrode (the reactions of its ϕ rows, with their sign turned), with the
/// electrodes' potentials.
pub fn reactions(
    problem: &Problem,
    (dofs, x): (&DofMap, &[f64]),
    (f_int, f_ext): (&[f64], &[f64]),
    contact_force: &[f64],
) -> Reactions {
    let (dim, n) = (problem.mesh.dim(), problem.mesh.n_nodes());
    let mut total = vec![0.0; dim];
    let mut supports = vec![vec![0.0; dim]; problem.n_support_tables()];
    let mut phi_reaction = vec![0.0; n];
    let mut force: Vec<f64> = f_int[..dim * n].iter().zip(f_ext).map(|(i, e)| i - e).collect();
    dofs.to_frames(&mut force);
    // Every ϕ row's reaction: a floating electrode's nodes are free, its charge theirs.
    let phi = |g: usize| g >= dim * n;
    for gdof in (0..dofs.n_total()).filter(|&g| phi(g) || dofs.free_index(g) == CONSTRAINED) {
        if gdof < dim * n {
            let direction = dofs.direction(gdof / dim, gdof % dim);
            for (c, n_c) in direction.iter().enumerate().take(dim).filter(|(_, n)| **n != 0.0) {
                total[c] += force[gdof] * n_c;
                if let Some(table) = supports.get_mut(dofs.support_table(gdof)) {
                    table[c] += force[gdof] * n_c;
                }
            }
        } else {
            phi_reaction[gdof - dim * n] = f_int[gdof] - f_ext[gdof] - contact_force[gdof];
        }
    }
    if problem.axisymmetric {
        // The radial forces of a body of revolution sum to no resultant.
        total[0] = 0.0;
        supports.iter_mut().for_each(|s| s[0] = 0.0);
    }
    let charges = electrode_charges(problem, &phi_reaction);
    let first = |e: &crate::problem::Electrode| problem.part_nodes(&e.parts).first().copied();
    let potentials =
        problem.boundary.electrodes.iter().map(|e| first(e).map_or(0.0, |a| x[dofs.phi(a)]));
    Reactions { total, supports, charges, potentials: potentials.collect() }
}

/// The reactions of the constrained rows ([`reactions`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Reactions {
    /// The force of every clamp and support on the body, d components
    /// [stress·length^(d−1)].
    pub total: Vec<f64>,
    /// The force of each clamp and support, in the order of
    /// [`Problem::support_names`] (a component fixed by several counts in the first).
    pub supports: Vec<Vec<f64>>,
    /// The charge on each part of Γa and each electrode [charge·length^(3−d)].
    pub charges: Vec<f64>,
    /// The potential of each electrode beyond the grounded parts \[potential\].
    pub potentials: Vec<f64>,
}

/// The reactions ([`reactions`]) of a state `x` without contact, with Hencky's law at x (as
/// [`crate::system::solve_without_contact`] solves) under the loads scaled by `load_factor`
/// [-].
pub fn reactions_without_contact(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    load_factor: f64,
) -> Result<Reactions> {
    let moduli = secant_moduli(problem, dofs, x)?;
    let (f_int, _) = internal_force(problem, dofs, x, &moduli)?;
    let f_ext = load_vector(problem, dofs, load_factor);
    let none = vec![0.0; dofs.n_total()];
    Ok(reactions(problem, (dofs, x), (&f_int, &f_ext), &none))
}

/// The charge on each part of Γa (the grounded parts, then the electrodes) from the reactions
/// of the ϕ rows at its nodes: the ϕ equations are Gauss's law with its sign turned (model
/// §5), so the charge the electrode holds is minus the reaction (positive on the electrode at
/// the higher potential of a charged capacitor); a node shared counts in the first.
fn electrode_charges(problem: &Problem, phi_reaction: &[f64]) -> Vec<f64> {
    let mut counted = vec![false; problem.mesh.n_nodes()];
    let mut charges = Vec::new();
    for &part in &problem.boundary.grounded {
        let mut charge = 0.0;
        for &node in problem.mesh.part_facets(part).flatten() {
            if !std::mem::replace(&mut counted[node], true) {
                charge -= phi_reaction[node];
            }
        }
        charges.push(charge);
    }
    for electrode in &problem.boundary.electrodes {
        let nodes = problem.part_nodes(&electrode.parts);
        let charge: f64 = nodes
            .into_iter()
            .filter(|&node| !std::mem::replace(&mut counted[node], true))
            .map(|node| -phi_reaction[node])
            .sum();
        charges.push(charge);
    }
    charges
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithm::solve_contact;
    use crate::testing::{PAPER_71, built};

    /// At the exact solver's solution the residuals vanish and the forces balance; a defect
    /// put into one multiplier shows, with its size, in the contact and equilibrium residuals.
    #[test]
    fn the_residuals_measure_defects_and_the_forces_balance() {
        let overrides = ["mesh.nx=24", "mesh.ny=4", "solver.method=\"newton\""];
        let built = built(PAPER_71, &overrides);
        let (problem, model) = (&built.problem, built.model.as_ref().unwrap());
        let solution = solve_contact(problem, model, &built.settings).unwrap();
        let c = built.settings.method.complementarity_constant();
        let (kkt, balance) = assess(problem, model, c, &solution.view()).unwrap();
        assert!(solution.converged() && kkt.max < 1e-10, "{kkt:?}");
        assert!(balance.imbalance < 1e-10, "{balance:?}");
        let applied = balance.applied[1];
        assert!(applied < 0.0 && balance.contact[1] > 0.0 && balance.reaction[1] > 0.0);
        // A separated node, clear of the stop: λ_c = δ breaks complementarity by δ/c.
        let dofs = &solution.dofs;
        let surface = &solution.surface;
        let clearance = |i: usize| {
            model.compliance.stop(surface.gap[i]) - surface.split(dofs, &solution.x, i).0
        };
        let i = (0..surface.len())
            .filter(|&i| solution.state.lambda_c[i] == 0.0)
            .max_by(|&a, &b| clearance(a).total_cmp(&clearance(b)))
            .expect("a separated node");
        let delta = 1e-3;
        assert!(c * clearance(i) > delta, "node {i} is too close to the stop");
        let mut broken = solution.clone();
        broken.state.lambda_c[i] = delta;
        broken.sigma_nu[i] -= delta;
        let (kkt_broken, balance_broken) = assess(problem, model, c, &broken.view()).unwrap();
        let max_u = (0..problem.mesh.n_nodes())
            .map(|a| (0..2).map(|k| solution.x[dofs.u(a, k)].powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let expected = delta / c / max_u;
        assert!((kkt_broken.contact - expected).abs() < 1e-12 * expected, "{kkt_broken:?}");
        assert!(kkt_broken.equilibrium_u > 1e3 * kkt.equilibrium_u, "{kkt_broken:?}");
        // The force the node's λ_c adds to the foundation's: w δ along −ν.
        let extra = balance_broken.contact[1] - balance.contact[1];
        let w_nu = surface.weight[i] * surface.normal[i][1];
        assert!((extra + delta * w_nu).abs() < 1e-12, "{extra}");
    }
}

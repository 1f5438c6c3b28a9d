//! # piezocontact
//!
//! Finite elements for the static contact of a piezoelectric body with a foundation, after
//! \[P\]: a piezoelectric body with nonlinear Hencky elasticity in contact with a foundation
//! through normal compliance with finite penetration; problem PV1 (frictionless,
//! nonconductive foundation) and PV2 (regularised Coulomb friction, conductive foundation).
//! P1 elements in 2D (triangles) and 3D (tetrahedra) share every code path.
//!
//! The library computes and never prints; it reports through `log`.
//!
//! ## Notation
//!
//! One meaning per symbol in code. Units are those of the case's consistent system (model §9):
//! length, stress, charge, potential.
//! A quantity's doc comment gives its unit in brackets, \[stress\] (escaped in the source,
//! `\[stress\]`, so that rustdoc does not take it for a link).
//!
//! | symbol | identifier | meaning | unit | \[P\] |
//! |---|---|---|---|---|
//! | u, ϕ, x | `u`, `phi`, `x` | displacement, electric potential, x = (u, ϕ) | length, potential | (2.1) |
//! | σ | `sigma` | stress | stress | (2.2) |
//! | D | `D`, `electric_displacement` | electric displacement | charge/length² (3D) | (2.2) |
//! | E(ϕ) = −∇ϕ | `grad_phi` (its negative) | electric field | potential/length | (2.2) |
//! | E_Y, ν_P | `young`, `poisson` | Young's modulus, Poisson's ratio (case file) | stress, – | §7 |
//! | ε(u), ε^D | `eps` | strain, its deviator | – | (2.3) |
//! | k0, µ1 | `k0`, `mu1` | bulk coefficient, small-strain shear modulus | stress | §7 |
//! | g(t), t0 | `Elasticity::g`, `t0` | Hencky's secant modulus, elasticity limit (t = ‖ε^D‖²) | stress, – | (2.3), §7 |
//! | g_e | `moduli` | g per element at the iterate, with which B̌ is assembled | stress | (6.5) |
//! | e_ijk | `e`, `e31`, `e33`, `e15` | piezoelectric tensor | charge/length² | (2.2) |
//! | β_ij | `beta`, `beta11`, `beta33` | permittivity | charge/(potential·length) | (2.2) |
//! | f0, q0 | `f0`, `q0` | body force, volume charge | stress/length, charge/length³ | (2.1) |
//! | f2, q2 | `traction`, `charge` | traction on Γ2, surface charge on Γb | stress, charge/length² | (2.4) |
//! | Γ1, Γ2, Γ3 | `clamped`, `traction`, `contact` | clamped, loaded, contact boundary | – | (2.4) |
//! | Γa, Γb | `grounded`, `charge` | ϕ = 0, D·ν = q2 | – | (2.4) |
//! | w_i, ν_i, τ_i | `weight`, `normal`, `tangent`, `frame` | nodal weight, normal and tangents of Γ3 node i | length^(d−1), – | model §6 |
//! | u_ν, u_τ | `u_nu`, `u_tau` | normal and tangential displacement on Γ3 | length | (2.5) |
//! | σ_ν, σ_τ | `sigma_nu`, `sigma_tau` | normal and tangential stress on Γ3 | stress | (2.5) |
//! | g_a, g_p, ρ | `gap`, `penetration`, `stop` | gap, penetration, rigid stop ρ = g_a + g_p | length | (2.5), model §9 |
//! | p_ν, h_ν | `p_nu`, `h_nu` | normal compliance functions; the pressure h_ν p_ν | length, stress/length | (2.5) |
//! | ϕ0 | `phi0` | potential of the foundation (stored once, in `ContactModel`) | potential | (2.5), (2.8) |
//! | ψ, k_e, φ_L | `psi`, `ke`, `phi_l` | conductivity, its coefficient, truncation | charge/(potential·length^d), –, potential | (2.8) |
//! | µ, R, s | `mu`, `Mollifier`, `s` / `friction_bound` | friction coefficient, regularisation, bound s = µ\|Rσ_ν\| | –, –, stress | (2.7) |
//! | λ_c, λ_f | `lambda_c`, `lambda_f` | contact pressure of the stop, friction traction (σ_τ = −λ_f) | stress | (6.6) |
//! | p_c, p_f | `p_c`, `p_f` | Uzawa's auxiliary displacements | length | (6.9) |
//! | r | `r` (`solver.r`) | augmented Lagrangian parameter; the exact solver's constant | stress/length | (6.9) |
//! | c, c_i | `complementarity_constant`, `c` | constant of the complementarity functions; Newton's per node | stress/length | model §10, §11 |
//! | ε, ε_fp | `eps`, `eps_fp` | stopping tolerances of (6.12) and (6.13)/(6.15) | – | (6.12)–(6.16) |
//! | B̌(x_n; ·,·) | `Assembler::matrix` | symmetric form with g frozen at x_n | – | (6.5) |
//! | f̌ | `Assembler::load_vector` | symmetric right-hand side | – | (6.3) |
//! | S, b, F | `schur`, `load`, `forces` | Schur complement of the Γ3 unknowns, condensed load, contact forces | – | model §11 |
//! | E_n, E_t, E_ϕ | `residual` | the exact solver's equations | – | model §11 |
//!
//! Indices of unknowns are `dof` (global) and `k` (free); `residual` is always a defect of
//! equations, never the parameter r.
//!
//! ## Modules (each imports only those above it)
//!
//! - [`error`], [`limits`], [`interrupt`]: errors, the machine's limits, Ctrl-C.
//! - [`linalg`]: the linear-solver seam (backends and their capabilities) and sparse LDLᵀ, the
//!   only module naming faer.
//! - [`element`]: P1 simplex geometry and quadrature.
//! - [`mesh`]: meshes with named boundary parts and regions (structured rectangle, Gmsh MSH
//!   4.1).
//! - [`material`]: Hencky law g, full tensors in Voigt notation (both forms), orientation, the
//!   cited library, the materials of the cells.
//! - [`oracles`]: closed-form solutions the tests and the reproduction compare with.
//! - [`problem`]: a checked problem: mesh, material, boundary roles, loads.
//! - [`dofs`]: DOF numbering [u; ϕ] and Dirichlet elimination.
//! - [`assembly`]: element kernels, B̌ (pattern once, parallel refills), f̌, fields and norms.
//! - [`system`]: the coupled system on the caller's backend; the solve without contact.
//! - [`contact`]: Γ3 (w_i, ν_i, u_ν, u_τ), each contact law written once (complementarity,
//!   Coulomb's ball, a node's status), the contact model, friction bounds, the mollifier, the
//!   foundation and loading paths.
//! - [`algorithm`]: the outer fixed point (Algorithms 1, 3) around an inner method — Uzawa
//!   (Algorithms 2, 4) or the exact solver — Hencky's linearisation, residuals and balances.
//! - [`case`]: case files — schema and defaults, overrides, validation, one build
//!   ([`case::Built`]: everything a run reads).
//! - [`report`]: the Γ3 table, the curve of a path, summary.json.
//! - [`output`]: ParaView `.vtu`, figures, atomic files.
//! - [`run`]: a run of a built case — without contact, one contact solve or a loading path,
//!   chosen in one place — and its files.
//!
//! Within a module folder, files import their siblings' files, never the folder's `mod.rs`,
//! which declares and re-exports.
//!
//! ## Running a case
//!
//! ```no_run
//! use piezocontact::{case::Case, run::Run};
//! # fn main() -> piezocontact::Result<()> {
//! let built = Case::load("cases/paper-7.1.toml".as_ref(), &["mesh.nx=48".into()])?.build()?;
//! let run = Run::solve(&built, built.linear_solver()?, &|_| {})?;
//! if let Some(contact) = run.contact() {
//!     let solution = &contact.solution;
//!     println!("{} outer iterations, KKT residual {:.1e}", solution.outer_iterations(), solution.kkt.max);
//! }
//! run.write(&built, "out/example".as_ref(), Default::default())?;
//! # Ok(())
//! # }
//! ```
//!
//! ## Reference
//!
//! The model and the method are stated in `docs/model.md` of the repository; "model §n" in doc
//! comments is its section n. \[P\] is the paper whose model and method piezocontact implements:
//! equation numbers (2.x), (6.x), the Algorithms 1–4 and the Examples 7.1–7.2 are its.

/// The one dimension dispatch: calls `f::<D, N>(args)` with (D, N) = (2, 3) on a triangle
/// mesh and (3, 4) on a tetrahedron mesh, so that element code is written once, generic over
/// the dimension. [`mesh::Mesh::new`] admits d = 2 and d = 3 only.
macro_rules! with_simplex {
    ($dim:expr, $($f:ident)::+ ($($arg:expr),* $(,)?)) => {
        match $dim {
            2 => $($f)::+::<2, 3>($($arg),*),
            _ => $($f)::+::<3, 4>($($arg),*),
        }
    };
}

pub mod algorithm;
pub mod assembly;
pub mod case;
pub mod contact;
pub mod dofs;
pub mod element;
pub mod error;
pub mod frames;
pub mod interrupt;
pub mod limits;
pub mod linalg;
pub mod material;
pub mod mesh;
pub mod oracles;
pub mod output;
pub mod problem;
pub mod report;
pub mod run;
pub mod system;
#[cfg(test)]
mod testing;

pub use error::{Error, Result};

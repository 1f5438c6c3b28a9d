//! # piezocontact
//!
//! Finite elements for the static contact of a piezoelectric body with a foundation, after
//! [P]: a piezoelectric body with nonlinear Hencky elasticity in contact with a foundation
//! through normal compliance with finite penetration; problem PV1 (frictionless,
//! nonconductive foundation) and PV2 (regularised Coulomb friction, conductive foundation).
//! P1 elements in 2D (triangles) and 3D (tetrahedra) share every code path.
//!
//! The library computes and never prints; it reports through `log`.
//!
//! ## Notation
//!
//! | symbol | identifier | meaning | unit | [P] |
//! |---|---|---|---|---|
//! | u | `u` | displacement | length | (2.1) |
//! | ϕ | `phi` | electric potential | potential | (2.1) |
//! | σ | `sigma` | stress | stress | (2.2) |
//! | D | `D`, `electric_displacement` | electric displacement | charge/length² (3D) | (2.2) |
//! | ε(u), ε^D | `eps` | strain, its deviator | – | (2.3) |
//! | k0, µ1 | `k0`, `mu1` | bulk coefficient, small-strain shear modulus | stress | §7 |
//! | g(t), t0 | `g`, `t0` | Hencky secant modulus, elasticity limit (t = ‖ε^D‖²) | stress, – | (2.3), §7 |
//! | e_ijk | `e`, `e31`, `e33`, `e15` | piezoelectric tensor | charge/length² | (2.2) |
//! | β_ij | `beta`, `beta11`, `beta33` | permittivity | charge/(potential·length) | (2.2) |
//! | f0, q0 | `f0`, `q0` | body force, volume charge | stress/length, charge/length³ | (2.1) |
//! | f2, q2 | `traction`, `charge` | traction on Γ2, surface charge on Γb | stress, charge/length² | (2.4) |
//! | Γ1, Γ2, Γ3 | `clamped`, `traction`, `contact` | clamped, loaded, contact boundary | – | (2.4) |
//! | Γa, Γb | `grounded`, `charge` | ϕ = 0, D·ν = q2 | – | (2.4) |
//! | B̌(x_n; ·,·) | `Assembler::matrix` | symmetric form with g frozen at x_n | – | (6.5) |
//! | f̌ | `Assembler::load_vector` | symmetric right-hand side | – | (6.3) |
//!
//! ## Modules (data flow top to bottom)
//!
//! - [`mesh`]: meshes with named boundary parts (structured rectangle, Gmsh MSH 4.1).
//! - [`element`]: P1 simplex geometry and quadrature.
//! - [`material`]: Hencky law g, piezoelectric and permittivity tensors.
//! - [`problem`]: a checked problem: mesh, material, boundary roles, loads.
//! - [`dofs`]: DOF numbering [u; ϕ] and Dirichlet elimination.
//! - [`assembly`]: element kernels, B̌ (pattern once, parallel refills), f̌, fields and norms.
//! - [`linalg`]: the linear-solver seam and sparse LDLᵀ (the only module naming faer).
//! - [`solver`]: the coupled solve without contact; element fields σ, D.
//! - [`contact`]: Γ3 kinematics (w_i, ν_i, u_ν, u_τ) and the contact laws.
//! - [`algorithm`]: the outer fixed point (Algorithms 1, 3) around an inner method (Uzawa,
//!   Algorithms 2, 4), residuals and balances.
//! - [`case`]: case files — schema, defaults, overrides, validation, hypotheses.
//! - [`report`], [`run`]: a run of a case, its Γ3 table, summary and files.
//! - [`output`]: ParaView `.vtu`, atomic files.
//!
//! ## Running a case
//!
//! ```no_run
//! use piezocontact::{case::Case, run::ContactRun};
//! # fn main() -> piezocontact::Result<()> {
//! let case = Case::load("cases/paper-7.1.toml".as_ref(), &["mesh.nx=48".into()])?;
//! let run = ContactRun::solve(&case)?;
//! println!("{} outer iterations, KKT residual {:.1e}", run.solution.outer_iterations, run.solution.kkt.max);
//! run.write(&case, "out/example".as_ref())?;
//! # Ok(())
//! # }
//! ```
//!
//! ## Reference
//!
//! The model and the method are stated in `docs/model.md` of the repository; "model §n" in doc
//! comments is its section n. [P] is the paper whose model and method piezocontact implements:
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
pub mod limits;
pub mod linalg;
pub mod material;
pub mod mesh;
pub mod output;
pub mod problem;
pub mod report;
pub mod run;
pub mod solver;

pub use error::{Error, Result};

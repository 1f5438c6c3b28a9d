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
//! - [`assembly`]: B̌ and f̌, pattern once, values refilled.
//! - [`linalg`]: sparse LDLᵀ (the only module naming faer).
//! - [`solver`]: the coupled solve without contact; element fields σ, D.
//! - [`contact`]: Γ3 kinematics (w_i, ν_i, u_ν, u_τ) and the contact laws.
//! - [`algorithm`]: Algorithms 1–4 (fixed point around Uzawa), residuals and balances.
//! - [`output`]: ParaView `.vtu`.
//!
//! ## Reference
//!
//! [P] The paper in `shared/paper/`, restated in `SPEC.md`: equation numbers (2.x), (6.x)
//! and the Algorithms 1–4 are the paper's.

pub mod algorithm;
pub mod assembly;
pub mod contact;
pub mod dofs;
pub mod element;
pub mod error;
pub mod linalg;
pub mod material;
pub mod mesh;
pub mod output;
pub mod problem;
pub mod solver;

pub use error::{Error, Result};

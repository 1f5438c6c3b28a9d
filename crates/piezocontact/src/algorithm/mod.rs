//! The contact algorithms (model §7): the outer fixed point of \[P\] Section 6 — Algorithm 1
//! (PV2) and Algorithm 3 (PV1) — around an inner method: the paper's Uzawa block relaxation
//! ([`uzawa`], Algorithms 2 and 4) or the exact solver ([`newton`], model §11, on the problem
//! condensed onto Γ3 by [`condensed`], or on the whole system, of which each process holds
//! its part: `held`).
//!
//! - [`outer`]: the outer loop ([`ContactSolver`]), a short loop of named steps;
//! - [`hencky`]: Hencky's law linearised at x_n — the secant, or the consistent tangent with
//!   its floor and chord steps (model §13);
//! - [`inner`]: the seam between the outer loop and a method ([`InnerMethod`]);
//! - [`solution`]: what a solve returns ([`ContactSolution`]);
//! - [`residual`]: how accurate it is (model §10);
//! - [`stops`]: where the loops' stops become errors.
//!
//! The outer loop knows no method: it asks an [`InnerMethod`] to set up the coupled system
//! with the caller's linear solver, to solve each outer step, and to say how its stops read;
//! adding a method touches the method's own module and the case's `solver.method` table.
//! Each file imports its siblings' files, never this one.
//!
//! One outer step of a contact solve visits, in order: [`outer`] (the loop); [`hencky`]
//! (`prepare`: a factorisation or a chord step, through `system` and `assembly`); the method
//! — [`newton`] with [`condensed`], or [`uzawa`] — which applies the laws of `contact::law`;
//! [`solution`] (`record`: σ_ν from `contact::state`, the friction bound from
//! `contact::friction` and its mollifier); [`hencky`] again (`relinearise`); [`residual`]
//! and [`stops`] for its criterion and its stops. No file of these imports one above it.

pub mod condensed;
mod held;
pub mod hencky;
pub mod inner;
pub mod newton;
pub mod outer;
pub mod residual;
pub mod solution;
pub mod stops;
pub mod uzawa;

pub use inner::{DIVERGENCE, InnerMethod, InnerResult, Progress, Setup, Step, Stop, StopContext};
pub use outer::{ContactSolver, Settings, solve_contact, solve_contact_with};
pub use residual::{Balance, KktResidual};
pub use solution::ContactSolution;

//! Fixtures of the unit tests: the paper's cases on coarse meshes, built as a run builds them.

use crate::algorithm::{Setup, Step};
use crate::assembly::{Linearisation, MassNorm};
use crate::case::{Built, Case};
use crate::contact::{ContactModel, ContactSurface, NodalFriction};
use crate::dofs::DofMap;
use crate::problem::Problem;

/// Example 7.1 (PV1) as the case file gives it.
pub const PAPER_71: &str = include_str!("../../../cases/paper-7.1.toml");
/// Example 7.2 (PV2) as the case file gives it.
pub const PAPER_72: &str = include_str!("../../../cases/paper-7.2.toml");
/// The 3D indentation (a ball pressed into a PZT block, PV2) as the case file gives it; its
/// mesh path is relative to `cases/`, so a test names a mesh by its absolute path.
pub const INDENTATION_3D: &str = include_str!("../../../cases/indentation-3d.toml");

/// The case `text` with `overrides`, validated and built.
pub fn built(text: &str, overrides: &[&str]) -> Built {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Case::from_text("case.toml".as_ref(), text, &overrides).unwrap().build().unwrap()
}

/// A built contact case with what the outer loop keeps over its steps, to make [`Step`]s.
pub struct Fixture {
    /// The case, built.
    pub built: Built,
    /// Γ3 with the gaps to the foundation.
    pub surface: ContactSurface,
    /// The L2(Ω) norm of the stopping rules.
    pub mass: MassNorm,
    /// µ_i and R of the friction bound (PV2).
    pub friction: Option<NodalFriction>,
}

impl Fixture {
    /// The contact case `text` with `overrides`.
    pub fn new(text: &str, overrides: &[&str]) -> Self {
        let built = built(text, overrides);
        let (problem, model) = (&built.problem, built.model.as_ref().unwrap());
        let dofs = DofMap::new(problem).unwrap();
        let surface = ContactSurface::new(problem, &dofs).unwrap().with_gaps(
            problem,
            &model.foundation,
            model.compliance.gap,
        );
        let friction =
            model.friction.as_ref().map(|f| NodalFriction::new(problem, &surface, f).unwrap());
        let mass = MassNorm::new(problem).unwrap();
        Self { built, surface, mass, friction }
    }

    /// The problem.
    pub fn problem(&self) -> &Problem {
        &self.built.problem
    }

    /// The contact model.
    pub fn model(&self) -> &ContactModel {
        self.built.model.as_ref().unwrap()
    }

    /// What `method.prepare` takes.
    pub fn setup(&self) -> Setup<'_> {
        let dofs = DofMap::new(self.problem()).unwrap();
        Setup { problem: self.problem(), dofs, surface: &self.surface, model: self.model() }
    }

    /// An outer step from x_n = `previous` with s_n = `friction_bound` and Hencky's law
    /// `linearisation`.
    pub fn step<'a>(
        &'a self,
        previous: &'a [f64],
        friction_bound: &'a [f64],
        linearisation: &'a Linearisation,
    ) -> Step<'a> {
        Step {
            problem: self.problem(),
            mass: &self.mass,
            surface: &self.surface,
            model: self.model(),
            friction: self.friction.as_ref(),
            previous,
            friction_bound,
            linearisation,
            slip_origin: None,
            progress: &|_| {},
        }
    }
}

//! Loading paths (model §14): the steps along which the foundation moves rigidly and the
//! applied loads are scaled, each step one static contact problem.

use super::foundation::Foundation;
use super::model::ContactModel;

/// A loading path: the steps of `[loading]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Loading {
    /// The unit vector along which the foundation travels (0 when it does not move).
    pub direction: [f64; 3],
    /// The steps, in order.
    pub steps: Vec<LoadStep>,
}

/// One step of a loading path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadStep {
    /// The foundation's displacement along the direction from its `[foundation]` position
    /// \[length\].
    pub depth: f64,
    /// The factor on every applied load and support displacement [-].
    pub load_factor: f64,
    /// The factor on the electrodes' voltages and charges [-]: `loading.electrode_factors`,
    /// else the load factor.
    pub electrode_factor: f64,
}

impl LoadStep {
    /// The step's factors on the loads and on the electrodes.
    pub fn factors(&self) -> crate::problem::Factors {
        crate::problem::Factors { loads: self.load_factor, electrodes: self.electrode_factor }
    }
}

impl Loading {
    /// `model` with its foundation where `step` moves it: rigidly, by depth · direction.
    pub fn model_at(&self, model: &ContactModel, step: &LoadStep) -> ContactModel {
        ContactModel { foundation: self.foundation_at(&model.foundation, step), ..model.clone() }
    }

    /// `foundation` where `step` moves it: rigidly, by depth · direction.
    pub fn foundation_at(&self, foundation: &Foundation, step: &LoadStep) -> Foundation {
        foundation.translated(self.direction.map(|v| v * step.depth))
    }

    /// `model` at the first step (as given without steps): where the solver is set up, the
    /// exact solver's first guess of the contact zone being that step's.
    pub fn at_first(&self, model: &ContactModel) -> ContactModel {
        self.steps.first().map_or_else(|| model.clone(), |s| self.model_at(model, s))
    }

    /// Whether the foundation moves along the path.
    pub fn moves(&self) -> bool {
        self.direction.iter().any(|v| *v != 0.0)
    }
}

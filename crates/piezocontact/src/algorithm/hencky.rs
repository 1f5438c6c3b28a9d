//! Hencky's law linearised at x_n, as the outer loop uses it (model §7, §13): the secant
//! moduli of the paper's fixed point when the inner method lags the contact terms, and else the
//! consistent tangent — a Newton iteration on the law around an exact inner solve — with its
//! floor and its chord steps:
//!
//! - the whole tangent can cycle, or make a pivot of B̌ change sign, where the law is not
//!   positive beyond e·t0; when its criterion grows, or B̌ loses its signs (on an iterative
//!   route, which sees no pivots: when the first solve with it fails), it fails once, and
//!   the floored tangent ([`Beyond::Floored`]) takes the next step. On an iterative route
//!   the floored tangent is the whole one's preconditioner where they differ (the operator
//!   stays the whole tangent: [`CoupledSystem::factorize_preconditioned`]);
//! - after a second failure the floor stays, and the steps on a factorisation of the floored
//!   tangent are chord steps (solves on the kept factor) while they contract.

use super::inner::{InnerMethod, Progress};
use crate::assembly::{Beyond, Linearisation, secant_moduli};
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::problem::Problem;
use crate::system::CoupledSystem;

/// Hencky's law linearised at the last iterate, with what decides the next linearisation and
/// whether B̌ is factorised again.
pub struct Hencky {
    /// The secant (the method lags the contact terms) or the consistent tangent.
    secant: bool,
    /// The linearisation at the last iterate (at 0 before the first step).
    current: Linearisation,
    /// Whether B̌ must be factorised with `current` before the next step.
    changed: bool,
    /// What the tangent does beyond t = e·t0.
    beyond: Beyond,
    /// How often the whole tangent failed in this solve: once (or floored by the last
    /// solve), the floored tangent takes one step; twice, every step after.
    whole_failures: usize,
    /// Whether the factorisation holds B̌ with the floored tangent.
    floored_factor: bool,
    /// Chord steps since the last factorisation.
    chords: usize,
    /// The steps of this solve taken with the floored tangent.
    floored_steps: usize,
    /// The steps of this solve that were chord steps.
    chord_steps: usize,
}

/// How the linearisation steps of a solve went: for summary.json's `hencky_tangent`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HenckySteps {
    /// Outer steps taken with the floored tangent beyond e·t0.
    pub floored: usize,
    /// Outer steps that were chord steps on a kept factorisation of the floored tangent.
    pub chords: usize,
}

impl Hencky {
    /// The linearisation at x = 0: the secant when `secant`, else the whole tangent.
    pub fn new(problem: &Problem, dofs: &DofMap, secant: bool) -> Result<Self> {
        let zero = vec![0.0; dofs.n_total()];
        Ok(Self {
            secant,
            current: linearise(problem, dofs, &zero, secant, Beyond::Whole)?,
            changed: true,
            beyond: Beyond::Whole,
            whole_failures: 0,
            floored_factor: false,
            chords: 0,
            floored_steps: 0,
            chord_steps: 0,
        })
    }

    /// The linearisation B̌ was last made with.
    pub fn current(&self) -> &Linearisation {
        &self.current
    }

    /// Starts a solve: the linearisation of the last solve is kept (floored or not), its
    /// failures and counts are not; `reassemble` (the prescribed displacements changed) has
    /// the first step assemble B̌ again, which lifts them.
    pub fn start(&mut self, reassemble: bool) {
        (self.whole_failures, self.chords, self.floored_steps, self.chord_steps) = (0, 0, 0, 0);
        self.changed |= reassemble;
    }

    /// The counts of this solve's steps.
    pub fn steps(&self) -> HenckySteps {
        HenckySteps { floored: self.floored_steps, chords: self.chord_steps }
    }

    /// Before an outer step from x_n = `x`: when the linearisation changed, a chord step on
    /// the factorisation held where it contracts (`history`: the outer criteria so far), else
    /// B̌ factorised with it (told to `progress`).
    pub fn prepare(
        &mut self,
        (problem, x, history): (&Problem, &[f64], &[f64]),
        method: &mut dyn InnerMethod,
        system: &mut CoupledSystem,
        progress: &(dyn Fn(Progress) + Sync),
    ) -> Result<()> {
        if self.changed && self.chord_contracts(history) {
            system.chord(problem, &self.current, method.blocks(), x)?;
            self.chord_steps += 1;
            self.chords += 1;
        } else if self.changed {
            self.chords = 0;
            progress(Progress::Factorising { unknowns: system.dofs().n_free() });
            self.factorise(problem, x, method, system)?;
        }
        self.changed = false;
        self.floored_steps += usize::from(self.beyond == Beyond::Floored);
        Ok(())
    }

    /// After an outer step: the law linearised at its solution `x` for the next step, and the
    /// step's criterion, `criterion(changed)` (whether the linearisation changed). The whole
    /// tangent fails when the criterion grows over the last of `history` while some element
    /// is beyond e·t0, and the floored tangent takes the next step.
    pub fn relinearise(
        &mut self,
        (problem, dofs, x): (&Problem, &DofMap, &[f64]),
        history: &[f64],
        criterion: impl FnOnce(bool) -> f64,
    ) -> Result<f64> {
        if self.beyond == Beyond::Floored && self.whole_failures < 2 {
            self.beyond = Beyond::Whole;
        }
        let mut next = linearise(problem, dofs, x, self.secant, self.beyond)?;
        let criterion = criterion(next != self.current);
        let grows = history.last().is_some_and(|last| criterion > *last);
        if !self.secant && self.beyond == Beyond::Whole && grows {
            let floored = linearise(problem, dofs, x, self.secant, Beyond::Floored)?;
            if floored != next {
                next = floored;
                self.fail_whole();
            }
        }
        self.changed = next != self.current;
        self.current = next;
        Ok(criterion)
    }

    /// The whole tangent failed: the floor takes over.
    fn fail_whole(&mut self) {
        (self.beyond, self.whole_failures) = (Beyond::Floored, self.whole_failures + 1);
    }

    /// Whether the next step is a chord step on the factorisation held: once the floor stays
    /// (the whole tangent failed twice) and B̌ was factorised with it, when the last step's
    /// criterion fell and, after a chord step, by a ratio at most the square root of the last
    /// fresh factorisation's (half its digits or more). The floored tangent converges
    /// linearly, and so does the chord on it, at the cost of solves instead of a
    /// factorisation per step.
    fn chord_contracts(&self, history: &[f64]) -> bool {
        let ratio = |k: usize| history[k] / history[k - 1];
        let n = history.len();
        // The ratio of the last step on a fresh factorisation, and of the last step.
        let fresh = n.checked_sub(self.chords + 1).filter(|&k| k >= 1).map(ratio);
        let last = (n >= 2).then(|| ratio(n - 1));
        let contracts = match (fresh, last) {
            (Some(fresh), Some(last)) if self.chords > 0 => last <= fresh.sqrt(),
            (_, Some(last)) => last < 1.0,
            _ => false,
        };
        self.floored_factor && self.whole_failures >= 2 && contracts
    }

    /// Factorises B̌ with the linearisation made at `x` (x_n). When the whole tangent gives a
    /// pivot of the wrong sign (Hencky's law not positive beyond e·t0 in enough elements that
    /// B̌ is no longer quasi-definite), it fails and the floored tangent at x is factorised
    /// instead.
    fn factorise(
        &mut self,
        problem: &Problem,
        x: &[f64],
        method: &mut dyn InnerMethod,
        system: &mut CoupledSystem,
    ) -> Result<()> {
        method.before_factorisation(system)?;
        let blocks = method.blocks();
        let iterative = system.is_iterative();
        let whole = iterative && !self.secant && self.beyond == Beyond::Whole;
        // On an iterative route the floored tangent preconditions the whole one where they
        // differ.
        let floored = match whole {
            true => Some(linearise(problem, system.dofs(), x, self.secant, Beyond::Floored)?),
            false => None,
        };
        let mut factorised = match floored.as_ref().filter(|floored| **floored != self.current) {
            Some(floored) => {
                system.factorize_preconditioned(problem, (&self.current, floored), blocks)
            }
            None => system.factorize_linearised(problem, &self.current, blocks),
        };
        if whole && factorised.is_ok() {
            // An iterative route cannot see a pivot of the wrong sign: its solve fails
            // instead. The first solve, kept by the system for the step that follows.
            factorised = system.check_solve().map(|_| ());
        }
        self.floored_factor = self.beyond == Beyond::Floored && factorised.is_ok();
        let lost_signs = match &factorised {
            Err(Error::SingularSystem { .. }) => true,
            Err(Error::LinearAlgebra(_)) => iterative,
            _ => false,
        };
        if !lost_signs || self.beyond != Beyond::Whole {
            return factorised;
        }
        // The floored tangent made above on an iterative route, else made now.
        let floored = match floored {
            Some(floored) => floored,
            None => linearise(problem, system.dofs(), x, self.secant, Beyond::Floored)?,
        };
        if floored == self.current {
            return factorised;
        }
        self.current = floored;
        self.fail_whole();
        let factorised = system.factorize_linearised(problem, &self.current, blocks);
        self.floored_factor = factorised.is_ok();
        factorised
    }
}

/// Hencky's law at x: the secant (model §7) when `secant`, else the consistent tangent that
/// does `beyond` past e·t0 (model §13).
fn linearise(
    problem: &Problem,
    dofs: &DofMap,
    x: &[f64],
    secant: bool,
    beyond: Beyond,
) -> Result<Linearisation> {
    // A body of revolution takes the secant: the tangent's rank-one part is the plane
    // element's.
    if secant || problem.axisymmetric {
        Ok(Linearisation::secant(secant_moduli(problem, dofs, x)?))
    } else {
        Linearisation::tangent(problem, dofs, x, beyond)
    }
}

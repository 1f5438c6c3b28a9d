//! What a process holds of the semismooth Newton method on the whole system (model §11): its
//! positions are the free unknowns whose rows it owns and every Γ3 unknown
//! ([`super::condensed::Condensed::whole`]), so that no process holds a vector of all the
//! unknowns along the iteration. The contact laws read and write the Γ3 positions alike on
//! every process; a sum over the processes of a vector of the Γ3 positions alone brings their
//! rows from the processes that own them, and sums and maxima over the owned positions,
//! reduced over the processes, give each process the same merit and step sizes.

use crate::error::Result;
use crate::linalg::{masked, unmasked};
use crate::system::CoupledSystem;

/// The positions of the whole system's Newton iteration that this process holds.
#[derive(Debug)]
pub(super) struct Held {
    /// The Γ3 positions, increasing: every process holds them, in the same order of the
    /// unknowns.
    pub(super) contact: Vec<usize>,
    /// Per position, whether this process owns its row; `None`: every one (one process).
    owned: Option<Vec<bool>>,
}

impl Held {
    /// The Γ3 positions `contact` (increasing) among the positions `free` (the free unknowns
    /// held, increasing), of which this process owns those whose rows are `complete` (per
    /// free unknown; `None`: every one).
    pub(super) fn new(contact: Vec<usize>, free: &[usize], complete: Option<&[bool]>) -> Self {
        let owned = complete.map(|complete| free.iter().map(|&k| complete[k]).collect());
        Self { contact, owned }
    }

    /// Whether this process owns position k's row.
    pub(super) fn owns(&self, k: usize) -> bool {
        self.owned.as_ref().is_none_or(|owned| owned[k])
    }

    /// The entries of a vector of the positions on this process's rows, increasing — a
    /// vector of the seam's ([`CoupledSystem::product`]).
    pub(super) fn owned_part(&self, values: Vec<f64>) -> Vec<f64> {
        masked(self.owned.as_deref(), values)
    }

    /// A vector of this process's rows ([`Held::owned_part`]) spread over the positions:
    /// 0 at the others, which [`Held::complete`] fills where it matters.
    pub(super) fn spread(&self, values: Vec<f64>) -> Vec<f64> {
        unmasked(self.owned.as_deref(), values)
    }

    /// `values`, right on the owned positions, made right on the Γ3 positions whose rows
    /// others own: their owners' values, by a sum over the processes of a vector of the Γ3
    /// positions (each owner's value, 0 from the others).
    pub(super) fn complete(&self, values: &mut [f64], system: &mut CoupledSystem) -> Result<()> {
        let Some(owned) = &self.owned else { return Ok(()) };
        let mut contact: Vec<f64> =
            self.contact.iter().map(|&k| if owned[k] { values[k] } else { 0.0 }).collect();
        system.sum_over_processes(&mut contact)?;
        self.contact.iter().zip(contact).for_each(|(&k, v)| values[k] = v);
        Ok(())
    }

    /// Σ f(k) over the positions this process owns, summed over the processes (in the
    /// positions' order on one process).
    pub(super) fn sum(
        &self,
        system: &mut CoupledSystem,
        terms: impl Iterator<Item = (usize, f64)>,
    ) -> Result<f64> {
        let own: f64 = terms.filter(|(k, _)| self.owns(*k)).map(|(_, v)| v).sum();
        match self.owned {
            None => Ok(own),
            Some(_) => {
                let mut total = [own];
                system.sum_over_processes(&mut total)?;
                Ok(total[0])
            }
        }
    }

    /// max |v_k| over the positions this process owns, the largest over the processes.
    pub(super) fn max_norm(&self, system: &mut CoupledSystem, values: &[f64]) -> Result<f64> {
        let own = (values.iter().enumerate())
            .filter(|(k, _)| self.owns(*k))
            .fold(0.0, |m: f64, (_, v)| m.max(v.abs()));
        match self.owned {
            None => Ok(own),
            Some(_) => system.max_over_processes(own),
        }
    }
}

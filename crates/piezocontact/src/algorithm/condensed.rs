//! The Γ3 unknowns that the exact solver condenses (model §11): which nodes, where their
//! unknowns sit in the condensed vector, and the active-set check that grows the set when a
//! node left out touches the foundation.

use crate::contact::ContactSurface;
use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::{Error, Result};
use crate::linalg::{DenseMatrix, SolverStats};
use crate::system::CoupledSystem;
use std::collections::HashMap;

/// The Γ3 unknowns kept by the condensation, in the order of the Schur complement.
#[derive(Clone, Debug)]
pub struct Condensed {
    /// Free indices of the condensed unknowns.
    pub free: Vec<usize>,
    /// Global indices of the condensed unknowns.
    pub(super) global: Vec<usize>,
    /// Per Γ3 node: the positions of its u components in the condensed vector (in local
    /// coordinates during the iteration: normal first, then tangents).
    pub(super) u: Vec<[usize; 3]>,
    /// Per Γ3 node: how many u components are condensed (d, or 1 for the normal alone) and
    /// the global axis of each.
    axes: Vec<(usize, [usize; 3])>,
    /// Per Γ3 node: its ϕ.
    pub(super) phi: Vec<Phi>,
    /// Per Γ3 node: whether it is condensed. A node whose normal misses the foundation (an
    /// infinite gap) cannot touch it, and stays with the interior, as do the nodes left out
    /// of a Γ3 too large to condense whole.
    pub(super) kept: Vec<bool>,
    /// Whether ϕ of the nodes is condensed.
    with_phi: bool,
    /// Free unknowns of the problem: the length of each right-hand side a growth solves.
    n_free: usize,
    /// Whether friction is absent, so that a node whose normal is a coordinate axis condenses
    /// u_ν alone (its tangential components carry no contact force and stay with the interior).
    frictionless: bool,
}

/// The u components of `node` that no support fixes: how many, and which (the first so
/// many entries). A node on a support keeps its normal and its free tangent: the frame of
/// [`ContactSurface::frame`] puts them first.
fn free_axes(dofs: &DofMap, node: usize, dim: usize) -> (usize, [usize; 3]) {
    let mut axes = [0; 3];
    let mut n = 0;
    for k in (0..dim).filter(|&k| dofs.free_index(dofs.u(node, k)) != CONSTRAINED) {
        axes[n] = k;
        n += 1;
    }
    (n, axes)
}

/// How the exact solver guesses the Γ3 nodes to condense first, and at most how many.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Guess {
    /// Every node within the foundation's reach, or this many nearest to it.
    Nearest(usize),
    /// The nodes inside the foundation when the undeformed body penetrates it — for a ball
    /// pressed in by d, the disc of radius √(2Rd), which holds Hertz's contact disc of radius
    /// √(Rd) — else as [`Guess::Nearest`]; at most this many. Nodes of the contact zone
    /// outside it are added by [`Condensed::grown`].
    Interpenetration(usize),
}

impl Guess {
    /// The same guess of at most `cap` nodes (`None`: no cap).
    pub fn at_most(self, cap: Option<usize>) -> Self {
        let capped = |n: usize| cap.map_or(n, |cap| n.min(cap));
        match self {
            Guess::Nearest(n) => Guess::Nearest(capped(n)),
            Guess::Interpenetration(n) => Guess::Interpenetration(capped(n)),
        }
    }
}

/// ϕ of a Γ3 node in the condensed problem.
#[derive(Clone, Copy, Debug)]
pub(super) enum Phi {
    /// An unknown, at this position of the condensed vector (shared by the nodes of a
    /// floating electrode).
    Unknown(usize),
    /// Prescribed (the node is on Γa): its global index.
    Prescribed(usize),
    /// Not condensed: without penetration (g_p = 0) the laws that read ϕ, p_ν and ψ at
    /// u_ν − g_a, vanish on every admissible state, and ϕ stays with the interior.
    Interior,
}

impl Condensed {
    /// The first guess of the Γ3 nodes to condense: with [`Guess::Interpenetration`] and a
    /// foundation that the undeformed body already penetrates, the nodes inside it
    /// (g_a ≤ 0); else every node within the foundation's reach. When they are more than the
    /// guess's count, that many nearest to the foundation (smallest gap; the first of equal
    /// ones). [`Condensed::grown`] corrects the guess. A node's u is condensed, and its ϕ when
    /// `with_phi` (the laws that read ϕ can act: a penetration g_p > 0); a prescribed ϕ (a Γ3
    /// node on Γa) is not an unknown.
    pub fn new(
        dofs: &DofMap,
        surface: &ContactSurface,
        (with_phi, frictionless): (bool, bool),
        guess: Guess,
    ) -> Self {
        let gap = &surface.gap;
        let mut reach: Vec<usize> = (0..surface.len()).filter(|&i| gap[i].is_finite()).collect();
        let inside = reach.iter().filter(|&&i| gap[i] <= 0.0).count();
        let max_nodes = match guess {
            Guess::Interpenetration(n) if inside > 0 => {
                reach.retain(|&i| gap[i] <= 0.0);
                n
            }
            Guess::Interpenetration(n) | Guess::Nearest(n) => n,
        };
        if reach.len() > max_nodes {
            reach.sort_by(|&a, &b| gap[a].total_cmp(&gap[b]).then(a.cmp(&b)));
            reach.truncate(max_nodes);
        }
        let mut kept = vec![false; surface.len()];
        reach.into_iter().for_each(|i| kept[i] = true);
        Self::with_nodes(dofs, surface, (with_phi, frictionless), kept)
    }

    /// The unknowns of the `kept` nodes: without friction, u_ν alone at every kept node when
    /// all their normals are coordinate axes (a flat face along the axes), else every u
    /// component.
    fn with_nodes(
        dofs: &DofMap,
        surface: &ContactSurface,
        (with_phi, frictionless): (bool, bool),
        kept: Vec<bool>,
    ) -> Self {
        let dim = surface.dim();
        // The normal along a mesh axis, at a node in the mesh's frame.
        let axis = |i: usize| {
            let nu = surface.normal[i];
            dofs.frame(surface.nodes[i]).is_none().then_some(())?;
            let k = (0..dim).find(|&k| nu[k].abs() > 1.0 - 1e-14)?;
            (0..dim).all(|j| j == k || nu[j].abs() < 1e-14).then_some(k)
        };
        let normal_only =
            frictionless && (0..surface.len()).filter(|&i| kept[i]).all(|i| axis(i).is_some());
        let mut this = Self {
            free: Vec::new(),
            global: Vec::new(),
            u: Vec::new(),
            axes: Vec::new(),
            phi: Vec::new(),
            kept: Vec::new(),
            with_phi,
            n_free: dofs.n_free(),
            frictionless,
        };
        let push = |this: &mut Self, dof: usize| {
            this.free.push(dofs.free_index(dof));
            this.global.push(dof);
            this.free.len() - 1
        };
        // A floating electrode's nodes share its one unknown: condensed once, at the
        // position kept here by its free index.
        let mut floating: HashMap<usize, usize> = HashMap::new();
        for (i, &node) in surface.nodes.iter().enumerate() {
            if !kept[i] {
                this.u.push([usize::MAX; 3]);
                this.axes.push((0, [0; 3]));
                this.phi.push(Phi::Interior);
                continue;
            }
            let axes = match axis(i).filter(|_| normal_only) {
                Some(k) => (1, [k, 0, 0]),
                None => free_axes(dofs, node, dim),
            };
            let mut u = [usize::MAX; 3];
            for (slot, &k) in u.iter_mut().zip(&axes.1[..axes.0]) {
                *slot = push(&mut this, dofs.u(node, k));
            }
            this.u.push(u);
            this.axes.push(axes);
            let dof = dofs.phi(node);
            let phi = if !with_phi {
                Phi::Interior
            } else if dofs.free_index(dof) == CONSTRAINED {
                Phi::Prescribed(dof)
            } else if dofs.floating_of(node).is_some() {
                let k = dofs.free_index(dof);
                Phi::Unknown(*floating.entry(k).or_insert_with(|| push(&mut this, dof)))
            } else {
                Phi::Unknown(push(&mut this, dof))
            };
            this.phi.push(phi);
        }
        this.kept = kept;
        this
    }

    /// The whole system as the "condensed" unknowns, for the semismooth Newton method on the
    /// whole system (model §11): every Γ3 node that can touch the foundation (a finite gap) is
    /// kept with each of its free u components, and its ϕ as for [`Condensed::new`] with
    /// `with_phi`; the other unknowns are the interior's. The positions are the free unknowns
    /// this process holds, increasing: every one on one process (position k is free unknown
    /// k), else those whose rows it owns (`complete`, per free unknown) and every kept node's.
    pub fn whole(
        dofs: &DofMap,
        surface: &ContactSurface,
        with_phi: bool,
        complete: Option<&[bool]>,
    ) -> Self {
        let dim = surface.dim();
        let kept: Vec<bool> = surface.gap.iter().map(|g| g.is_finite()).collect();
        let axes: Vec<(usize, [usize; 3])> = (surface.nodes.iter().zip(&kept))
            .map(|(&node, &kept)| if kept { free_axes(dofs, node, dim) } else { (0, [0; 3]) })
            .collect();
        let phi_of = |i: usize| {
            let dof = dofs.phi(surface.nodes[i]);
            match dofs.free_index(dof) {
                _ if !with_phi || !kept[i] => Phi::Interior,
                CONSTRAINED => Phi::Prescribed(dof),
                k => Phi::Unknown(k),
            }
        };
        let free_u = |i: usize| axes[i].1[..axes[i].0].iter().map(move |&k| (i, k));
        let u_index = |(i, k): (usize, usize)| dofs.free_index(dofs.u(surface.nodes[i], k));
        let free = match complete {
            None => (0..dofs.n_free()).collect(),
            Some(complete) => {
                let mut held: Vec<usize> = (0..dofs.n_free()).filter(|&k| complete[k]).collect();
                held.extend((0..surface.len()).flat_map(free_u).map(u_index));
                held.extend((0..surface.len()).filter_map(|i| match phi_of(i) {
                    Phi::Unknown(k) => Some(k),
                    _ => None,
                }));
                held.sort_unstable();
                held.dedup();
                held
            }
        };
        // Every free unknown looked up is held, by the construction above.
        let position = |k: usize| free.partition_point(|&f| f < k);
        let mut global = vec![0; free.len()];
        for g in (0..dofs.n_total()).filter(|&g| dofs.free_index(g) != CONSTRAINED) {
            if let Ok(p) = free.binary_search(&dofs.free_index(g)) {
                global[p] = g;
            }
        }
        let (mut u, mut phi) = (Vec::new(), Vec::new());
        for i in 0..surface.len() {
            let mut slots = [usize::MAX; 3];
            free_u(i).zip(&mut slots).for_each(|(k, slot)| *slot = position(u_index(k)));
            u.push(slots);
            phi.push(match phi_of(i) {
                Phi::Unknown(k) => Phi::Unknown(position(k)),
                other => other,
            });
        }
        Self {
            free,
            global,
            u,
            axes,
            phi,
            kept,
            with_phi,
            n_free: dofs.n_free(),
            frictionless: false,
        }
    }

    /// The active-set check of the nodes left out (model §11): at the solution `x` of the
    /// condensed problem, a left-out node carries no contact force, which is its law only
    /// while u_ν ≤ g_a and its friction bound `bound` (s = µ|Rσ_ν| per Γ3 node, which a
    /// nonlocal R spreads from the touching nodes to their neighbours, even to those whose
    /// normal misses the foundation) is 0. `None` when every left-out node is there. Else
    /// the condensation with those that fail it added, and with them the left-out nodes as
    /// near to touching (u_ν − g_a above minus the largest excess e), deepest first. When
    /// that would exceed `max_nodes` (`None`: no cap), condensed nodes clear of the
    /// foundation and without a bound make room, the clearest first; an error when none can.
    pub fn grown(
        &self,
        (dofs, surface): (&DofMap, &ContactSurface),
        (x, bound): (&[f64], &[f64]),
        max_nodes: Option<usize>,
    ) -> Result<Option<Self>> {
        let excess = |i: usize| {
            let nu = surface.frame(i)[0];
            let u_nu: f64 =
                (0..surface.dim()).map(|k| nu[k] * x[dofs.u(surface.nodes[i], k)]).sum();
            u_nu - surface.gap[i]
        };
        // A node whose normal misses the foundation cannot touch it, but may bear friction.
        let in_play = |i: &usize| surface.gap[*i].is_finite() || bound[*i] > 0.0;
        let ranked = |kept: bool| {
            let mut nodes: Vec<(usize, f64)> = (0..surface.len())
                .filter(|i| in_play(i) && self.kept[*i] == kept)
                .map(|i| (i, excess(i)))
                .collect();
            nodes.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
            nodes
        };
        let fails = |&(i, v): &(usize, f64)| v > 0.0 || bound[i] > 0.0;
        let mut left_out = ranked(false);
        // Those that fail their law first (a stable sort keeps the deepest first).
        left_out.sort_by_key(|node| !fails(node));
        let failing = left_out.iter().filter(|node| fails(node)).count();
        if failing == 0 {
            return Ok(None);
        }
        let largest = left_out[..failing].iter().fold(0.0_f64, |e, (_, v)| e.max(*v));
        left_out.retain(|node| fails(node) || node.1 > -largest);
        let mut kept = self.kept.clone();
        let count = self.node_count();
        let cap = max_nodes.unwrap_or(usize::MAX);
        let short = (count + left_out.len()).saturating_sub(cap);
        let clear = ranked(true).into_iter().rev().filter(|(i, _)| bound[*i] == 0.0);
        let clear = clear.take_while(|(_, v)| *v < 0.0).take(short);
        clear.for_each(|(i, _)| kept[i] = false);
        let room = cap.saturating_sub(kept.iter().filter(|k| **k).count());
        if room == 0 {
            return Err(Error::Input(format!(
                "the contact zone is larger than solver.max_condensed = {cap} nodes: with that many Γ3 nodes condensed and touching, {failing} more still touch the foundation or bear friction from nodes that do; raise solver.max_condensed to at least {} (its dense matrices grow as its square), or use solver.method = \"uzawa\"",
                count + failing
            )));
        }
        left_out.into_iter().take(room).for_each(|(i, _)| kept[i] = true);
        Ok(Some(Self::with_nodes(dofs, surface, (self.with_phi, self.frictionless), kept)))
    }

    /// Node i's condensed u positions and, for each, its global axis (the normal alone, or
    /// every component).
    pub(super) fn slots(&self, i: usize) -> (&[usize], &[usize]) {
        let (n, axes) = &self.axes[i];
        (&self.u[i][..*n], &axes[..*n])
    }

    /// The free unknowns at node i's slots ([`Condensed::slots`]), in their order.
    pub(super) fn slot_unknowns(&self, i: usize) -> Vec<usize> {
        self.slots(i).0.iter().map(|&k| self.free[k]).collect()
    }

    /// Number of condensed Γ3 nodes.
    pub fn node_count(&self) -> usize {
        self.kept.iter().filter(|k| **k).count()
    }

    /// The bytes of the dense work of the condensation: the Schur complement, its factor
    /// block, the one kept for the next set, the block inverted to reach a new set and the
    /// Newton systems, about 7 dense m × m matrices; and the [`SOLVE_BLOCK`] right-hand sides
    /// of n free unknowns that a growth solves at once.
    pub fn dense_bytes(&self) -> f64 {
        let m = self.len() as f64;
        8.0 * (7.0 * m * m + (SOLVE_BLOCK * self.n_free) as f64)
    }

    /// Checks that [`Self::dense_bytes`] fit in `available` bytes.
    pub fn check_memory(&self, available: f64) -> Result<()> {
        crate::limits::check_memory(
            self.dense_bytes(),
            available,
            &format!("the exact solver's dense matrices of {} condensed Γ3 unknowns", self.len()),
            "use solver.method = \"uzawa\", lower solver.max_condensed, or name a smaller contact part (boundary.contact)",
        )
    }

    /// Number of condensed unknowns.
    pub fn len(&self) -> usize {
        self.free.len()
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.free.is_empty()
    }
}

/// Where the exact solver's Schur complements come from (model §11): the trailing block of
/// the factor, whose ordering kept the unknowns `analysed` last, and the last Schur
/// complement taken by solves from the same factorisation, which the next set starts from.
#[derive(Clone, Debug, Default)]
pub struct SchurSource {
    /// The free unknowns last in the factorisation's ordering.
    analysed: Vec<usize>,
    /// The last set served, the factorisation it came from (the count of numeric
    /// factorisations then) and its Schur complement.
    last: Option<(Vec<usize>, usize, DenseMatrix)>,
}

impl SchurSource {
    /// The factor's ordering keeps `analysed` last.
    pub fn new(analysed: &[usize]) -> Self {
        Self { analysed: analysed.to_vec(), last: None }
    }

    /// Whether the factor's ordering keeps `set` last, in that order.
    pub fn analyses(&self, set: &[usize]) -> bool {
        self.analysed == set
    }

    /// The solves [`SchurSource::get`] would make for `wanted` with the current
    /// factorisation of `system`: the wanted unknowns outside the set it would start from.
    pub fn solves_for(&self, system: &CoupledSystem, wanted: &[usize]) -> usize {
        let generation = system.solver_stats().numeric_count;
        let base = match &self.last {
            Some((set, g, _)) if *g == generation => set,
            _ => &self.analysed,
        };
        let base: std::collections::HashSet<usize> = base.iter().copied().collect();
        wanted.iter().filter(|k| !base.contains(k)).count()
    }

    /// The Schur complement S_W of the free unknowns `wanted` from the current factorisation
    /// of `system`, without analysing or factorising again: read off the factor when W is the
    /// analysed set, the last one again when W and the factorisation are the same, else from
    /// the last one of this factorisation (or the factor's) by [`schur_from`].
    pub fn get(&mut self, system: &mut CoupledSystem, wanted: &[usize]) -> Result<DenseMatrix> {
        let generation = system.solver_stats().numeric_count;
        let current = self.last.take().filter(|(_, g, _)| *g == generation);
        let schur = match current {
            Some((set, _, s)) if set == wanted => s,
            Some((set, _, s)) => schur_from(system, &set, s, wanted)?,
            None if self.analysed == wanted => system.schur_complement()?,
            None => {
                let base = system.schur_complement()?;
                schur_from(system, &self.analysed.clone(), base, wanted)?
            }
        };
        self.last = Some((wanted.to_vec(), generation, schur.clone()));
        Ok(schur)
    }
}

/// Right-hand sides solved at once by [`schur_from`]: the factor is read once per block.
pub const SOLVE_BLOCK: usize = 32;

/// The Schur complement S_W of the free unknowns `wanted` from `base`, the Schur complement
/// S_B of the free unknowns `base_set` of the current factorisation of `system`. The (W, W)
/// block of B̌⁻¹ is S_W⁻¹: its entries between unknowns of B are those of S_B⁻¹, the others
/// come from one solve per wanted unknown outside B (B̌⁻¹ is symmetric), made
/// [`SOLVE_BLOCK`] at a time; S_W is the inverse of that block, made symmetric.
pub fn schur_from(
    system: &mut CoupledSystem,
    base_set: &[usize],
    base: DenseMatrix,
    wanted: &[usize],
) -> Result<DenseMatrix> {
    let position: HashMap<usize, usize> =
        base_set.iter().enumerate().map(|(p, &k)| (k, p)).collect();
    let inverse = base.inverse()?;
    drop(base);
    let n = system.dofs().n_free();
    let new: Vec<usize> = wanted.iter().copied().filter(|k| !position.contains_key(k)).collect();
    let mut solved: HashMap<usize, Vec<f64>> = HashMap::new();
    for block in new.chunks(SOLVE_BLOCK) {
        let mut columns = vec![0.0; n * block.len()];
        block.iter().enumerate().for_each(|(c, &k)| columns[c * n + k] = 1.0);
        system.solve_free(&mut columns)?;
        for (column, &k) in columns.chunks(n).zip(block) {
            solved.insert(k, wanted.iter().map(|&row| column[row]).collect());
        }
    }
    let m = wanted.len();
    let mut block = DenseMatrix::zeros(m);
    for (b, &kb) in wanted.iter().enumerate() {
        let column = block.col_mut(b);
        for (a, &ka) in wanted.iter().enumerate() {
            column[a] = match (position.get(&ka), position.get(&kb)) {
                (Some(&pa), Some(&pb)) => inverse.get(pa, pb),
                (_, None) => solved[&kb][a],
                (None, Some(_)) => solved[&ka][b],
            };
        }
    }
    let mut schur = block.inverse()?;
    schur.symmetrize();
    Ok(schur)
}

/// How many times the flop rate of a numeric factorisation (dense kernels on supernodes)
/// exceeds that of a solve (memory-bound triangular sweeps), as measured on 2 cores: the
/// whole-face block's factorisation ran 206 Gflop in 1.66 s, its solves 4 × 94M entries in
/// 0.055 s each (124 against 6.9 Gflop/s).
const FACTORISATION_RATE_OVER_SOLVES: f64 = 16.0;

/// What each column of a block of [`SOLVE_BLOCK`] right-hand sides adds to the time of one
/// right-hand side alone: the block reads the factor once each way, its flops run in dense
/// kernels. Measured with `bench --mesh` on 2 cores (solve32_s over solve_s, 1 and 2
/// threads): 3.2–4.4 on the whole-face block (41.5M factor entries) and 3.2–3.3 on the
/// 183k-unknown indentation (316M), that is 0.07–0.11 per further column; 8–9 on a factor of
/// 1.9M entries that stays in cache.
const BLOCK_COLUMN_SHARE: f64 = 0.1;

/// Whether growing the condensation by [`schur_from`] (one solve per new unknown, in blocks
/// of [`SOLVE_BLOCK`]) is cheaper than analysing and factorising again with them last,
/// judged by the flops the analysis counted — the same verdict on any number of threads and
/// in every run, so that the answer does not depend on them — or, from a backend that counts
/// none (and solves one right-hand side at a time), by the mean times of the solves and
/// factorisations so far.
pub fn cheaper_by_solves(new_unknowns: usize, stats: &SolverStats) -> bool {
    if stats.factor_flops > 0.0 {
        let solve = 4.0 * stats.factor_len as f64 * FACTORISATION_RATE_OVER_SOLVES;
        let block = |b: usize| match b {
            0 => 0.0,
            b => solve * (1.0 + (b - 1) as f64 * BLOCK_COLUMN_SHARE),
        };
        let blocks = (new_unknowns / SOLVE_BLOCK) as f64 * block(SOLVE_BLOCK);
        return blocks + block(new_unknowns % SOLVE_BLOCK) < stats.factor_flops;
    }
    let mean = |seconds: f64, count: usize| seconds / count.max(1) as f64;
    let solve = mean(stats.solve_seconds, stats.solve_count);
    let factorisation = mean(stats.numeric_seconds, stats.numeric_count);
    new_unknowns as f64 * solve < factorisation
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cap bounds the first guess's count and keeps its kind; no cap changes nothing.
    #[test]
    fn a_cap_bounds_the_first_guess() {
        assert_eq!(Guess::Nearest(2000).at_most(Some(4)), Guess::Nearest(4));
        assert_eq!(Guess::Interpenetration(3).at_most(Some(4)), Guess::Interpenetration(3));
        assert_eq!(Guess::Interpenetration(2000).at_most(None), Guess::Interpenetration(2000));
    }

    #[test]
    fn a_condensed_problem_too_large_for_memory_is_refused() {
        let many = Condensed {
            free: vec![0; 30_000],
            global: Vec::new(),
            u: Vec::new(),
            phi: Vec::new(),
            axes: Vec::new(),
            kept: Vec::new(),
            with_phi: false,
            n_free: 1_000_000,
            frictionless: false,
        };
        // 8 bytes × (7 × 30000² + 32 × 10⁶) = 47.2 GiB.
        assert!(many.check_memory(64.0 * 2f64.powi(30)).is_ok());
        let e = many.check_memory(16.0 * 2f64.powi(30)).unwrap_err().to_string();
        assert!(
            e.contains("30000 condensed Γ3 unknowns")
                && e.contains("47.2 GiB")
                && e.contains("uzawa"),
            "{e}"
        );
    }
}

#[cfg(test)]
mod slot_tests {
    use super::*;
    use crate::testing::Fixture;

    /// The indentation's flat top face: without friction one slot per node, on the z axis;
    /// with friction every component.
    #[test]
    fn a_flat_face_without_friction_condenses_the_normal_alone() {
        let text = include_str!("../../../../cases/indentation-3d.toml");
        let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/../../meshes/indent-3d-h0.05.msh");
        let file = format!("mesh.file={mesh:?}");
        let fixture = Fixture::new(text, &[&file]);
        let dofs = DofMap::new(fixture.problem()).unwrap();
        let surface = &fixture.surface;
        for (frictionless, per_node) in [(true, 1), (false, 3)] {
            let c = Condensed::new(&dofs, surface, (false, frictionless), Guess::Nearest(2000));
            assert_eq!(c.len(), per_node * c.node_count(), "frictionless: {frictionless}");
            let i = (0..surface.len()).find(|&i| c.kept[i]).unwrap();
            let axes = c.slots(i).1.to_vec();
            assert_eq!(axes, if frictionless { vec![2] } else { vec![0, 1, 2] });
        }
    }

    /// The whole system's positions on a process that owns the rows of every other free
    /// unknown: those unknowns and every kept Γ3 node's, increasing, each position at its free
    /// unknown and its global one; a kept node's slots at its free u components (in its
    /// axes' order) and its ϕ at its own; on one process position k is free unknown k.
    #[test]
    fn the_whole_system_s_positions_are_the_owned_rows_and_the_contact_unknowns() {
        let text = include_str!("../../../../cases/indentation-3d.toml");
        let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/../../meshes/indent-3d-h0.05.msh");
        let fixture = Fixture::new(text, &[&format!("mesh.file={mesh:?}")]);
        let dofs = DofMap::new(fixture.problem()).unwrap();
        let surface = &fixture.surface;
        let one = Condensed::whole(&dofs, surface, true, None);
        assert_eq!(one.free, (0..dofs.n_free()).collect::<Vec<_>>());
        let complete: Vec<bool> = (0..dofs.n_free()).map(|k| k % 2 == 0).collect();
        let part = Condensed::whole(&dofs, surface, true, Some(&complete));
        let mut contact = Vec::new();
        for i in (0..surface.len()).filter(|&i| part.kept[i]) {
            let (slots, axes) = part.slots(i);
            assert_eq!(slots.len(), one.slots(i).0.len());
            for (&p, &axis) in slots.iter().zip(axes) {
                assert_eq!(part.free[p], dofs.free_index(dofs.u(surface.nodes[i], axis)));
                contact.push(part.free[p]);
            }
            if let (Phi::Unknown(p), Phi::Unknown(q)) = (part.phi[i], one.phi[i]) {
                assert_eq!(part.free[p], q);
                contact.push(q);
            }
        }
        assert!(contact.len() > 100, "{} contact unknowns", contact.len());
        let mut expected: Vec<usize> = (0..dofs.n_free()).filter(|&k| complete[k]).collect();
        expected.extend(contact);
        expected.sort_unstable();
        expected.dedup();
        assert!(expected.len() < dofs.n_free());
        assert_eq!(part.free, expected);
        for (p, &k) in part.free.iter().enumerate() {
            assert_eq!(part.global[p], one.global[k]);
            assert_eq!(dofs.free_index(part.global[p]), k);
        }
    }
}

#[cfg(test)]
mod transfer_tests {
    use super::*;
    use crate::assembly::secant_moduli;
    use crate::linalg::default_solver;
    use crate::testing::{Fixture, PAPER_72};

    /// The Schur complement of a set taken by solves from a factor analysed with another set
    /// last (some unknowns shared, some new, some dropped) equals the one of a factor
    /// analysed with that set last.
    #[test]
    fn a_schur_complement_by_solves_equals_one_by_analysis() {
        let fixture = Fixture::new(
            PAPER_72,
            &["mesh.nx=24", "mesh.ny=4", "contact.penetration=0.05", "conductivity.ke=0.5"],
        );
        let dofs = DofMap::new(fixture.problem()).unwrap();
        let all = Condensed::new(&dofs, &fixture.surface, (true, false), Guess::Nearest(2000));
        let m = all.len();
        assert!(m > 40, "{m} condensed unknowns");
        let analysed: Vec<usize> = all.free[..2 * m / 3].to_vec();
        let wanted: Vec<usize> = all.free[m / 3..].iter().rev().copied().collect();
        let problem = fixture.problem();
        let schur = |last: &[usize], wanted: &[usize]| {
            let mut system =
                CoupledSystem::with_last(problem, dofs.clone(), last, default_solver()).unwrap();
            let moduli = secant_moduli(problem, system.dofs(), &vec![0.0; dofs.n_total()]).unwrap();
            system.factorize(problem, &moduli, &[]).unwrap();
            SchurSource::new(last).get(&mut system, wanted).unwrap()
        };
        let (by_solves, by_analysis) = (schur(&analysed, &wanted), schur(&wanted, &wanted));
        let size = (0..wanted.len()).map(|k| by_analysis.get(k, k).abs()).fold(0.0, f64::max);
        for i in 0..wanted.len() {
            for j in 0..wanted.len() {
                let error = (by_solves.get(i, j) - by_analysis.get(i, j)).abs();
                assert!(error <= 1e-10 * size, "entry ({i}, {j}): {error:e} of {size:e}");
            }
        }
    }

    /// Solves win when their cost is below a factorisation's: by the flops the analysis
    /// counted (a solve: 4 per factor entry, at a sixteenth of the rate; in a block, each
    /// column after the first a share of that), whatever the times measured; by the mean
    /// times when the backend counts no flops.
    #[test]
    fn growth_by_solves_when_they_cost_less_than_a_factorisation() {
        let timed = SolverStats {
            numeric_seconds: 2.0,
            numeric_count: 2,
            solve_seconds: 0.03,
            solve_count: 3,
            ..SolverStats::default()
        };
        assert!(cheaper_by_solves(99, &timed));
        assert!(!cheaper_by_solves(100, &timed));
        // 1000 entries: a solve alone counts as 64,000 flops, a block of 32 as that times
        // 1 + 31 × BLOCK_COLUMN_SHARE, a block of 2 as that times 1 + BLOCK_COLUMN_SHARE.
        let solve = 64_000.0;
        let block = solve * (1.0 + 31.0 * BLOCK_COLUMN_SHARE);
        let counted = |factor_flops| SolverStats { factor_len: 1000, factor_flops, ..timed };
        assert!(cheaper_by_solves(1, &counted(solve + 1.0)));
        assert!(!cheaper_by_solves(2, &counted(solve + 1.0)));
        assert!(cheaper_by_solves(96, &counted(3.0 * block + 1.0)));
        assert!(!cheaper_by_solves(97, &counted(3.0 * block + 1.0)));
        let two = solve * (1.0 + BLOCK_COLUMN_SHARE);
        assert!(cheaper_by_solves(98, &counted(3.0 * block + two + 1.0)));
        // A block of 32 costs less than 32 solves alone.
        assert!(cheaper_by_solves(32, &counted(32.0 * solve)));
    }
}

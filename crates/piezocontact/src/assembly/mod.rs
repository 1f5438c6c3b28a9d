//! Assembly of the symmetric coupled system of \[P\] (6.2)–(6.3) (model §5):
//!
//! ```text
//! B̌(x_n; x, y) = (k0 tr ε(u) I + 2 g_n ε^D(u), ε(v)) + (Eᵀ∇ϕ, ε(v)) − (β∇ϕ, ∇ξ) + (Eε(u), ∇ξ)
//! (f̌, y)       = ∫Ω f0·v + ∫Γ2 f2·v − ∫Ω q0 ξ + ∫Γb q2 ξ
//! ```
//!
//! with the secant modulus g_n = g(‖ε^D(u_n)‖²) frozen per element at the previous iterate
//! (Section 5). The work is split as it is used:
//! - [`kernel`]: the element matrix of B̌ on one simplex;
//! - [`Assembler`] (this module): the global matrix — the pattern once per run, then every
//!   refill computes the element matrices in parallel and sums them into the pattern, with
//!   the Dirichlet lifting alongside;
//! - [`load`]: the right-hand side f̌;
//! - [`fields`]: strains, secant moduli, internal forces, σ and D, norms.
//!
//! Parallel refills give the same matrix to the last bit whatever the number of threads: the
//! cells are split once into groups of cells that share no node, the groups are summed one
//! after the other, and within a group no two cells write the same entry.

pub mod axisymmetric;
pub mod fields;
pub mod kernel;
pub mod load;

pub use fields::{
    Beyond, ElementFields, Linearisation, MassNorm, cell_gradients, element_fields, internal_force,
    secant_moduli, x_norm_squared,
};
pub use load::load_vector;

use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::{Error, Result};
use crate::linalg::{PatternIndex, SymmetricMatrix, SymmetricPattern};
use crate::mesh::Mesh;
use crate::problem::Problem;
use axisymmetric::cell_matrix;
use kernel::{local_dofs, simplex, tangent_vector};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// Items handled by one parallel task.
const PER_TASK: usize = 1024;

/// A symmetric d × d nodal block, row-major in a 3 × 3 array.
pub type NodalBlock = [[f64; 3]; 3];

/// Assembles B̌ on the free DOFs of a problem, reusing one sparsity pattern.
///
/// Besides the element matrices, the matrix may carry a d × d block on the u DOFs of given
/// nodes: the r M term of Algorithms 2 and 4 on the Γ3 nodes (model §7).
///
/// For a distributed backend ([`crate::linalg::Distributed`]) the assembler holds the rows of
/// the nodes its process owns: the pattern keeps the entries whose row or column belongs to
/// an owned node, and only the cells that touch an owned node are summed, so that the owned
/// rows are complete and the rest of the matrix is absent (the lifting's other rows partial).
/// The process that owns a floating electrode's row assembles every cell touching the
/// electrode (`assembled_nodes`).
#[derive(Debug)]
pub struct Assembler {
    dofs: DofMap,
    /// Where each entry of a cell goes is found anew at every assembly ([`cell_positions`])
    /// rather than kept: a slot per cell entry would cost more memory than the lower
    /// triangle's values.
    pattern: SymmetricPattern,
    /// The cells in groups that share no node (nor, touching a floating electrode, its
    /// unknown), summed one group after the other; then the cells that found no group, in
    /// order on one thread.
    groups: Vec<Vec<usize>>,
    alone: Vec<usize>,
    /// Nodes that carry a nodal block, and the slots of their [`nodal_pairs`].
    block_nodes: Vec<usize>,
    block_slots: Vec<usize>,
    /// Per free unknown: whether its row is complete (its node owned); `None`: all are. Some
    /// for a distributed assembler, whose pattern holds the owned nodes' rows alone: a cell's
    /// entry outside it is then left out, not an error.
    complete: Option<Vec<bool>>,
}

/// A slot of an entry that a distributed assembler's pattern leaves out.
const SKIPPED: usize = usize::MAX;

impl Assembler {
    /// Builds the sparsity pattern (once per run) on the DOFs of `dofs`, with room for nodal
    /// blocks on `block_nodes`; with `owned` (one flag per mesh node), for the rows of the
    /// owned nodes alone.
    pub fn new(
        problem: &Problem,
        dofs: DofMap,
        block_nodes: &[usize],
        owned: Option<&[bool]>,
    ) -> Result<Self> {
        let mesh = &problem.mesh;
        let dim = mesh.dim();
        let assembled = owned.map(|o| assembled_nodes(o, &dofs));
        let pattern = lower_pattern(mesh, &dofs, assembled.as_deref())?;
        let kept = |c: usize| assembled.as_ref().is_none_or(|o| mesh.cell(c).iter().any(|&a| o[a]));
        let partial = owned.is_some();
        let mut block_slots = Vec::new();
        for &node in block_nodes {
            for (_, _, r, c) in nodal_pairs(&dofs, dim, node) {
                let slot = pattern.position(r, c).or(partial.then_some(SKIPPED));
                block_slots.push(slot.ok_or_else(missing(r, c))?);
            }
        }
        let (mut groups, mut alone) = node_disjoint_groups(mesh, &dofs);
        if partial {
            groups.iter_mut().for_each(|g| g.retain(|&c| kept(c)));
            groups.retain(|g| !g.is_empty());
            alone.retain(|&c| kept(c));
        }
        let complete = owned.map(|o| (0..dofs.n_free()).map(|k| o[pattern.group(k)]).collect());
        Ok(Self {
            dofs,
            pattern,
            groups,
            alone,
            block_nodes: block_nodes.to_vec(),
            block_slots,
            complete,
        })
    }

    /// Per free unknown, whether its row of the matrix is complete (`None`: every row is).
    pub fn complete_rows(&self) -> Option<&[bool]> {
        self.complete.as_deref()
    }

    /// The DOF map.
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// The prescribed displacements set to `load_factor` [-] times the case's
    /// ([`DofMap::scale_displacements`]); the next matrix assembled lifts them.
    pub fn scale_displacements(&mut self, factors: crate::problem::Factors) {
        self.dofs.scale_displacements(factors);
    }

    /// Gives up the DOF map.
    pub fn into_dofs(self) -> DofMap {
        self.dofs
    }

    /// The sparsity pattern.
    pub fn pattern(&self) -> &SymmetricPattern {
        &self.pattern
    }

    /// The matrix of B̌(x_n) for per-element secant `moduli` g_e \[stress\], plus the nodal
    /// `blocks` (one per block node, or none at all), and the Dirichlet lifting −K_fc x_c
    /// (free DOFs) to add to the right-hand side.
    pub fn matrix(
        &self,
        problem: &Problem,
        moduli: &[f64],
        blocks: &[NodalBlock],
    ) -> Result<(SymmetricMatrix, Vec<f64>)> {
        self.linearised_matrix(problem, &Linearisation::secant(moduli.to_vec()), blocks)
    }

    /// [`Assembler::matrix`] for Hencky's law linearised at x_n: the secant moduli plus the
    /// rank-one parts of the tangent; the right-hand side gains (K_T − K_sec) x_n (with the
    /// lifting), so that K_T x = f̌ + (K_T − K_sec) x_n is the Newton step of the law.
    pub fn linearised_matrix(
        &self,
        problem: &Problem,
        linearisation: &Linearisation,
        blocks: &[NodalBlock],
    ) -> Result<(SymmetricMatrix, Vec<f64>)> {
        let moduli = &linearisation.moduli;
        if !blocks.is_empty() && blocks.len() != self.block_nodes.len() {
            return Err(Error::Length {
                what: "nodal blocks".into(),
                expected: self.block_nodes.len(),
                got: blocks.len(),
            });
        }
        if moduli.len() != problem.mesh.n_cells() {
            return Err(Error::Length {
                what: "secant moduli".into(),
                expected: problem.mesh.n_cells(),
                got: moduli.len(),
            });
        }
        let dim = problem.mesh.dim();
        let sums: Vec<AtomicU64> =
            (0..self.pattern.nnz() + self.dofs.n_free()).map(|_| AtomicU64::new(0)).collect();
        let add_cells = |cells: &[usize]| {
            cells.iter().try_for_each(|&c| {
                let cell = Cell { c, modulus: moduli[c], tangent: linearisation.tangent_of(c) };
                with_simplex!(dim, add_cell(problem, self, &cell, &sums))
            })
        };
        for group in &self.groups {
            group.par_chunks(PER_TASK).try_for_each(add_cells)?;
        }
        add_cells(&self.alone)?;
        let turned: Vec<NodalBlock> = blocks
            .iter()
            .zip(&self.block_nodes)
            .map(|(block, &node)| turn_block(&self.dofs, node, block))
            .collect();
        let turned = &turned;
        let block_values = self.block_nodes.iter().enumerate().flat_map(|(b, &node)| {
            nodal_pairs(&self.dofs, dim, node)
                .map(move |(i, j, ..)| turned.get(b).map_or(0.0, |k| k[i][j]))
        });
        for (&slot, value) in self.block_slots.iter().zip(block_values) {
            if slot != SKIPPED {
                add(&sums[slot], value);
            }
        }
        let mut values: Vec<f64> =
            sums.into_iter().map(|s| f64::from_bits(s.into_inner())).collect();
        let lifting = values.split_off(self.pattern.nnz()).into_iter().map(|l| -l).collect();
        Ok((self.pattern.matrix(values)?, lifting))
    }

    /// The load f̌ on the free DOFs from its global vector `load` (in mesh components): the
    /// sum of the rows that share an unknown (a floating electrode's ϕ rows), less the
    /// electrode's given charge times `electrode_factor` [-] (the ϕ equations are Gauss's law
    /// with its sign turned).
    pub fn restrict_load(&self, load: &[f64], electrode_factor: f64) -> Vec<f64> {
        let mut free = self.restrict(load);
        for f in self.dofs.floating() {
            let sum: f64 = f.nodes.iter().map(|&a| load[self.dofs.phi(a)]).sum();
            free[f.unknown] = sum - electrode_factor * f.charge;
        }
        free
    }

    /// The entries of a global vector (in mesh components) at the free DOFs, in the nodes'
    /// frames.
    pub fn restrict(&self, global: &[f64]) -> Vec<f64> {
        let turned;
        let global = match self.dofs.has_frames() {
            true => {
                let mut v = global.to_vec();
                self.dofs.to_frames(&mut v);
                turned = v;
                &turned
            }
            false => global,
        };
        let mut free = vec![0.0; self.dofs.n_free()];
        for (dof, v) in global.iter().enumerate() {
            let k = self.dofs.free_index(dof);
            if k != CONSTRAINED {
                free[k] = *v;
            }
        }
        free
    }
}

/// Adds `value` to the f64 held in `sum`. Within a group of cells no other thread touches
/// the same sum, and groups are separated by rayon's joins, so the order of the additions is
/// fixed.
fn add(sum: &AtomicU64, value: f64) {
    let old = f64::from_bits(sum.load(Ordering::Relaxed));
    sum.store((old + value).to_bits(), Ordering::Relaxed);
}

/// Running sums 0, c0, c0 + c1, … of `counts`.
fn offsets(counts: &[usize]) -> Vec<usize> {
    let mut offsets = Vec::with_capacity(counts.len() + 1);
    offsets.push(0);
    for count in counts {
        offsets.push(offsets[offsets.len() - 1] + count);
    }
    offsets
}

/// Runs `f(item, values of the item)` over all items in parallel, the items' values being
/// consecutive slices of `out` delimited by `offsets`.
fn for_ranges<T: Send>(
    offsets: &[usize],
    out: &mut [T],
    f: impl Fn(usize, &mut [T]) -> Result<()> + Sync,
) -> Result<()> {
    let n = offsets.len() - 1;
    let mut tasks = Vec::with_capacity(n.div_ceil(PER_TASK));
    let mut rest = out;
    for first in (0..n).step_by(PER_TASK) {
        let last = (first + PER_TASK).min(n);
        let (head, tail) = rest.split_at_mut(offsets[last] - offsets[first]);
        tasks.push((first..last, head));
        rest = tail;
    }
    tasks.into_par_iter().try_for_each(|(items, slice)| {
        let base = offsets[items.start];
        items
            .into_iter()
            .try_for_each(|k| f(k, &mut slice[offsets[k] - base..offsets[k + 1] - base]))
    })
}

/// The error for an entry that the pattern lacks (a bug, never user input).
fn missing(r: usize, c: usize) -> impl FnOnce() -> Error {
    move || Error::LinearAlgebra(format!("entry ({r}, {c}) is not in the sparsity pattern"))
}

/// For every node, its neighbours (the nodes that share a cell with it, itself included),
/// sorted: `(ptr, list)` with the neighbours of node a in `list[ptr[a]..ptr[a + 1]]`.
pub fn node_neighbours(mesh: &Mesh) -> (Vec<usize>, Vec<usize>) {
    let n = mesh.n_nodes();
    let mut counts = vec![0usize; n];
    for c in 0..mesh.n_cells() {
        mesh.cell(c).iter().for_each(|&a| counts[a] += mesh.cell(c).len());
    }
    let ptr = offsets(&counts);
    let mut list = vec![0usize; ptr[n]];
    let mut next = ptr.clone();
    for c in 0..mesh.n_cells() {
        let cell = mesh.cell(c);
        for &a in cell {
            list[next[a]..next[a] + cell.len()].copy_from_slice(cell);
            next[a] += cell.len();
        }
    }
    let mut kept = vec![0usize; n];
    let mut columns = Vec::with_capacity(n);
    let mut rest = list.as_mut_slice();
    for a in 0..n {
        let (head, tail) = rest.split_at_mut(ptr[a + 1] - ptr[a]);
        columns.push(head);
        rest = tail;
    }
    columns.into_par_iter().zip(kept.par_iter_mut()).for_each(|(neighbours, kept)| {
        neighbours.sort_unstable();
        let mut k = 0;
        for i in 0..neighbours.len() {
            if k == 0 || neighbours[i] != neighbours[k - 1] {
                neighbours[k] = neighbours[i];
                k += 1;
            }
        }
        *kept = k;
    });
    let compact = offsets(&kept);
    let mut sorted = Vec::with_capacity(compact[n]);
    for a in 0..n {
        sorted.extend_from_slice(&list[ptr[a]..ptr[a] + kept[a]]);
    }
    (compact, sorted)
}

/// The nodes whose rows a distributed process assembles: those it `owned`, and every node of
/// each floating electrode whose unknown's row it owns (that of the electrode's first node,
/// the unknown's group in [`lower_pattern`]), so that this row, which spans all of them, is
/// complete. The other rows of those nodes come out partial, and their owners hold them.
fn assembled_nodes(owned: &[bool], dofs: &DofMap) -> Vec<bool> {
    let mut assembled = owned.to_vec();
    for floating in dofs.floating().iter().filter(|f| owned[f.nodes[0]]) {
        floating.nodes.iter().for_each(|&a| assembled[a] = true);
    }
    assembled
}

/// The lower-triangle pattern of B̌ on the free DOFs: free DOFs k ≥ j of the nodes that share a
/// cell with the node of column j — with `owned`, only the pairs of which one node is owned.
/// Free numbers follow global numbers, in which every u comes before every ϕ, so the rows
/// come out sorted.
fn lower_pattern(mesh: &Mesh, dofs: &DofMap, owned: Option<&[bool]>) -> Result<SymmetricPattern> {
    let (ptr, neighbours) = node_neighbours(mesh);
    let (dim, n) = (mesh.dim(), dofs.n_free());
    let mut global_of_free = vec![0usize; n];
    for dof in 0..dofs.n_total() {
        if dofs.free_index(dof) != CONSTRAINED {
            global_of_free[dofs.free_index(dof)] = dof;
        }
    }
    let node_of = |dof: usize| {
        if dof < dim * mesh.n_nodes() { dof / dim } else { dof - dim * mesh.n_nodes() }
    };
    let is_owned = |a: usize| owned.is_none_or(|o| o[a]);
    let rows_at = |a: usize, j: usize| {
        let near =
            neighbours[ptr[a]..ptr[a + 1]].iter().filter(move |&&b| is_owned(a) || is_owned(b));
        let u = near.clone().flat_map(move |&b| (0..dim).map(move |i| dofs.u(b, i)));
        let phi = near.map(|&b| dofs.phi(b));
        u.chain(phi).map(|dof| dofs.free_index(dof)).filter(move |&k| k != CONSTRAINED && k >= j)
    };
    let (col_ptr, row_idx) = match dofs.floating().is_empty() {
        true => columns(n, |j| rows_at(node_of(global_of_free[j]), j))?,
        // A floating electrode's unknown gathers the neighbours of all its nodes, and
        // appears once in the columns of theirs: sorted and without repeats.
        false => columns(n, |j| {
            let floating = dofs.floating().iter().find(|f| f.unknown == j);
            let sources = floating.map_or(vec![node_of(global_of_free[j])], |f| f.nodes.clone());
            let mut rows: Vec<usize> = sources.into_iter().flat_map(|a| rows_at(a, j)).collect();
            rows.sort_unstable();
            rows.dedup();
            rows.into_iter()
        })?,
    };
    let mut nodes: Vec<usize> = global_of_free.iter().map(|&dof| node_of(dof)).collect();
    // A floating electrode's unknown belongs to its first node.
    dofs.floating().iter().for_each(|f| nodes[f.unknown] = f.nodes[0]);
    SymmetricPattern::from_columns(n, col_ptr, row_idx)?.with_groups(nodes)
}

/// The columns (`col_ptr`, `row_idx`) of a pattern of order `n` whose column j holds the rows
/// `rows_of(j)`, in that order (rows narrowed to [`PatternIndex`] unchecked: the pattern
/// refuses an n they miss).
fn columns<I: Iterator<Item = usize>>(
    n: usize,
    rows_of: impl Fn(usize) -> I + Sync,
) -> Result<(Vec<usize>, Vec<PatternIndex>)> {
    let counts: Vec<usize> = (0..n).into_par_iter().map(|j| rows_of(j).count()).collect();
    let col_ptr = offsets(&counts);
    let mut row_idx = vec![0; col_ptr[n]];
    for_ranges(&col_ptr, &mut row_idx, |j, out| {
        out.iter_mut().zip(rows_of(j)).for_each(|(slot, k)| *slot = k as PatternIndex);
        Ok(())
    })?;
    Ok((col_ptr, row_idx))
}

/// Splits the cells into groups in which no two cells share a node, the nodes of a floating
/// electrode counting as one (greedy colouring in cell order); the cells that find none of
/// 128 groups free are returned apart, to be summed alone.
fn node_disjoint_groups(mesh: &Mesh, dofs: &DofMap) -> (Vec<Vec<usize>>, Vec<usize>) {
    const COLOURS: usize = 128;
    let mut used = vec![0u128; mesh.n_nodes()];
    let owner: Vec<usize> = match dofs.floating().is_empty() {
        true => Vec::new(),
        false => (0..mesh.n_nodes()).map(|a| dofs.phi_owner(a)).collect(),
    };
    let key = |a: usize| owner.get(a).copied().unwrap_or(a);
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut crowded = Vec::new();
    for c in 0..mesh.n_cells() {
        let taken = mesh.cell(c).iter().fold(0u128, |m, &a| m | used[key(a)]);
        let colour = taken.trailing_ones() as usize;
        if colour >= COLOURS {
            crowded.push(c);
            continue;
        }
        mesh.cell(c).iter().for_each(|&a| used[key(a)] |= 1 << colour);
        if groups.len() <= colour {
            groups.resize(colour + 1, Vec::new());
        }
        groups[colour].push(c);
    }
    (groups, crowded)
}

/// The position in `pattern`'s values of each pair (p, q) of the element's DOFs `global`
/// whose free row is at or below its free column ([`SKIPPED`] elsewhere, and where the
/// pattern lacks it): for each column, one walk down its stored rows beside the element's
/// rows in increasing order, instead of a search per pair.
fn cell_positions(
    dofs: &DofMap,
    pattern: &SymmetricPattern,
    global: &[usize],
) -> [[usize; kernel::M_MAX]; kernel::M_MAX] {
    let mut table = [[SKIPPED; kernel::M_MAX]; kernel::M_MAX];
    let (mut free, mut order, mut count) = ([CONSTRAINED; kernel::M_MAX], [0; kernel::M_MAX], 0);
    for (p, &g) in global.iter().enumerate() {
        free[p] = dofs.free_index(g);
        if free[p] != CONSTRAINED {
            (order[count], count) = (p, count + 1);
        }
    }
    let rows = &mut order[..count];
    rows.sort_unstable_by_key(|&p| free[p]);
    for &q in rows.iter() {
        let (start, stored) = pattern.column(free[q]);
        let mut at = 0;
        for &p in rows.iter().filter(|&&p| free[p] >= free[q]) {
            while at < stored.len() && (stored[at] as usize) < free[p] {
                at += 1;
            }
            if at < stored.len() && stored[at] as usize == free[p] {
                table[p][q] = start + at;
            }
        }
    }
    table
}

/// What [`add_cell`] adds for one cell: its index, its secant modulus g_e [stress] and the
/// rank-one part of the tangent, if any ([`Linearisation`]).
struct Cell<'a> {
    c: usize,
    modulus: f64,
    tangent: Option<(f64, &'a [[f64; 3]; 3])>,
}

/// Adds the element matrix of a cell to the assembler's pattern (nnz values, then the
/// lifting's n_free): K_pq at its entry ([`cell_positions`]), times the prescribed value of
/// the column where it is constrained (the lifting, row r at slot nnz + r). With a tangent
/// part |K| β a aᵀ (β = 4 g'), adds it to the uu block, and −|K| β t a (t = aᵀ u_e) to the
/// lifting's slots, which the right-hand side takes with the opposite sign.
fn add_cell<const D: usize, const N: usize>(
    problem: &Problem,
    assembler: &Assembler,
    cell: &Cell,
    sums: &[AtomicU64],
) -> Result<()> {
    let (dofs, pattern) = (&assembler.dofs, &assembler.pattern);
    let s = simplex::<D, N>(problem, cell.c)?;
    let mut k = cell_matrix(problem, cell.c, &s, cell.modulus)?;
    let nodes = problem.mesh.cell(cell.c);
    turn_element::<D, N>(dofs, nodes, &mut k);
    let global = local_dofs::<D, N>(dofs, nodes);
    if let Some((beta, deviator)) = cell.tangent {
        let mut a = tangent_vector::<D, N>(&s, deviator);
        turn_vector::<D, N>(dofs, nodes, &mut a);
        let t: f64 = deviator.iter().flatten().map(|v| v * v).sum();
        let lifting_start = sums.len() - dofs.n_free();
        for p in 0..N * D {
            (0..N * D).for_each(|q| k[p][q] += s.measure() * beta * a[p] * a[q]);
            let row = dofs.free_index(global[p]);
            if row != CONSTRAINED {
                add(&sums[lifting_start + row], -s.measure() * beta * t * a[p]);
            }
        }
    }
    let m = N * (D + 1);
    let table = cell_positions(dofs, pattern, &global[..m]);
    for (p, q, r, col) in local_pairs(dofs, global, m) {
        let (slot, value) = if col == CONSTRAINED {
            (pattern.nnz() + r, k[p][q] * dofs.prescribed(global[q]))
        } else {
            (table[p][q], k[p][q])
        };
        match slot {
            SKIPPED if assembler.complete.is_some() => {}
            SKIPPED => return Err(missing(r, col)()),
            slot => add(&sums[slot], value),
        }
    }
    Ok(())
}

/// Turns an element matrix to the frames of its nodes ([`DofMap::frame`]): Tᵀ K T, with T
/// block diagonal (Rᵀ on the u block of a node with a turned frame, 1 elsewhere).
fn turn_element<const D: usize, const N: usize>(
    dofs: &DofMap,
    nodes: &[usize],
    k: &mut kernel::ElementMatrix,
) {
    if !dofs.has_frames() {
        return;
    }
    for (a, rows) in nodes.iter().enumerate().filter_map(|(a, &n)| Some((a, dofs.frame(n)?))) {
        for q in 0..N * (D + 1) {
            let turned: [f64; 3] =
                std::array::from_fn(|i| (0..D).map(|j| rows[i][j] * k[a * D + j][q]).sum());
            (0..D).for_each(|i| k[a * D + i][q] = turned[i]);
        }
        for row in k.iter_mut().take(N * (D + 1)) {
            let turned: [f64; 3] =
                std::array::from_fn(|i| (0..D).map(|j| rows[i][j] * row[a * D + j]).sum());
            (0..D).for_each(|i| row[a * D + i] = turned[i]);
        }
    }
}

/// A nodal block (mesh components) in the frame of `node`: R B Rᵀ.
fn turn_block(dofs: &DofMap, node: usize, block: &NodalBlock) -> NodalBlock {
    let Some(rows) = dofs.frame(node) else { return *block };
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..3).map(|a| (0..3).map(|b| rows[i][a] * block[a][b] * rows[j][b]).sum::<f64>()).sum()
        })
    })
}

/// Turns the u entries of an element vector to the frames of its nodes: Tᵀ a.
fn turn_vector<const D: usize, const N: usize>(
    dofs: &DofMap,
    nodes: &[usize],
    v: &mut [f64; kernel::M_MAX],
) {
    if !dofs.has_frames() {
        return;
    }
    for (a, rows) in nodes.iter().enumerate().filter_map(|(a, &n)| Some((a, dofs.frame(n)?))) {
        let turned: [f64; 3] =
            std::array::from_fn(|i| (0..D).map(|j| rows[i][j] * v[a * D + j]).sum());
        (0..D).for_each(|i| v[a * D + i] = turned[i]);
    }
}

/// The local pairs (p, q) of an element with `m` DOFs `global` whose row is free, with their
/// free row r and free column (or [`CONSTRAINED`]): pairs of free DOFs only in the lower
/// triangle (r ≥ column), constrained columns always (they feed the Dirichlet lifting). The
/// order is fixed, so the pattern and every refill agree.
fn local_pairs(
    dofs: &DofMap,
    global: [usize; kernel::M_MAX],
    m: usize,
) -> impl Iterator<Item = (usize, usize, usize, usize)> + '_ {
    (0..m).flat_map(move |p| {
        let r = dofs.free_index(global[p]);
        (0..m).filter_map(move |q| {
            let col = dofs.free_index(global[q]);
            (r != CONSTRAINED && (col == CONSTRAINED || r >= col)).then_some((p, q, r, col))
        })
    })
}

/// The (i, j, free row, free column) pairs of the u block of `node` with both DOFs free, in
/// the lower triangle.
fn nodal_pairs(
    dofs: &DofMap,
    dim: usize,
    node: usize,
) -> impl Iterator<Item = (usize, usize, usize, usize)> + '_ {
    (0..dim).flat_map(move |i| {
        (0..dim).filter_map(move |j| {
            let (r, c) = (dofs.free_index(dofs.u(node, i)), dofs.free_index(dofs.u(node, j)));
            (r != CONSTRAINED && c != CONSTRAINED && r >= c).then_some((i, j, r, c))
        })
    })
}

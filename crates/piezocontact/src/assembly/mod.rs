//! Assembly of the symmetric coupled system of [P] (6.2)–(6.3) (model §5):
//!
//! ```text
//! B̌(x_n; x, y) = (k0 tr ε(u) I + 2 g_n ε^D(u), ε(v)) + (Eᵀ∇ϕ, ε(v)) − (β∇ϕ, ∇ξ) + (Eε(u), ∇ξ)
//! (f̌, y)       = ∫Ω f0·v + ∫Γ2 f2·v − ∫Ω q0 ξ + ∫Γb q2 ξ
//! ```
//!
//! with the secant modulus g_n = g(‖ε^D(u_n)‖²) frozen per element at the previous iterate
//! (Section 5). The work is split as it is used:
//! - [`kernel`]: the element matrix of B̌ on one simplex;
//! - [`Assembler`] (this module): the global matrix — the pattern and its gather plan once per
//!   run, then every refill computes the element matrices in parallel and sums them into the
//!   pattern, with the Dirichlet lifting alongside;
//! - [`load`]: the right-hand side f̌;
//! - [`fields`]: strains, secant moduli, internal forces, σ and D, norms.
//!
//! Parallel refills give the same matrix to the last bit whatever the number of threads: each
//! element writes its own values, and each matrix entry sums its contributions in element order
//! ([`SymmetricPattern`]).

pub mod fields;
pub mod kernel;
pub mod load;

pub use fields::{
    ElementFields, MassNorm, cell_gradients, element_fields, internal_force, secant_moduli,
    x_norm_squared,
};
pub use load::load_vector;

use crate::dofs::{CONSTRAINED, DofMap};
use crate::error::{Error, Result};
use crate::linalg::{SymmetricMatrix, SymmetricPattern, VECTOR_ENTRY};
use crate::problem::Problem;
use kernel::{element_matrix, local_dofs, simplex};
use rayon::prelude::*;

/// Cells handled by one parallel task.
const CELLS_PER_TASK: usize = 2048;

/// A symmetric d × d nodal block, row-major in a 3 × 3 array.
pub type NodalBlock = [[f64; 3]; 3];

/// Assembles B̌ on the free DOFs of a problem, reusing one sparsity pattern.
///
/// Besides the element matrices, the matrix may carry a d × d block on the u DOFs of given
/// nodes: the r M term of Algorithms 2 and 4 on the Γ3 nodes (model §7).
#[derive(Debug)]
pub struct Assembler {
    dofs: DofMap,
    pattern: SymmetricPattern,
    /// Values of cell c occupy `cell_offsets[c]..cell_offsets[c + 1]`; nodal blocks follow.
    cell_offsets: Vec<usize>,
    /// Nodes that carry a nodal block.
    block_nodes: Vec<usize>,
}

impl Assembler {
    /// Builds the sparsity pattern (once per run) on the DOFs of `dofs`, with room for nodal
    /// blocks on `block_nodes`.
    pub fn new(problem: &Problem, dofs: DofMap, block_nodes: &[usize]) -> Result<Self> {
        let dim = problem.mesh.dim();
        let counts: Vec<usize> = (0..problem.mesh.n_cells())
            .into_par_iter()
            .map(|c| with_simplex!(dim, cell_pair_count(problem, &dofs, c)))
            .collect();
        let mut cell_offsets = Vec::with_capacity(counts.len() + 1);
        cell_offsets.push(0);
        for count in counts {
            cell_offsets.push(cell_offsets[cell_offsets.len() - 1] + count);
        }
        let mut positions = vec![(0, 0); cell_offsets[cell_offsets.len() - 1]];
        for_cells(&cell_offsets, &mut positions, |c, out| {
            with_simplex!(dim, cell_positions_into(problem, &dofs, c, out));
            Ok(())
        })?;
        for &node in block_nodes {
            positions.extend(nodal_pairs(&dofs, dim, node).map(|(_, _, r, c)| (r, c)));
        }
        let pattern = SymmetricPattern::new(dofs.n_free(), &positions)?;
        Ok(Self { dofs, pattern, cell_offsets, block_nodes: block_nodes.to_vec() })
    }

    /// The DOF map.
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// Gives up the DOF map.
    pub fn into_dofs(self) -> DofMap {
        self.dofs
    }

    /// The sparsity pattern.
    pub fn pattern(&self) -> &SymmetricPattern {
        &self.pattern
    }

    /// The matrix of B̌(x_n) for per-element secant moduli `g` [stress], plus the nodal
    /// `blocks` (one per block node, or none at all), and the Dirichlet lifting −K_fc x_c
    /// (free DOFs) to add to the right-hand side.
    pub fn matrix(
        &self,
        problem: &Problem,
        g: &[f64],
        blocks: &[NodalBlock],
    ) -> Result<(SymmetricMatrix, Vec<f64>)> {
        if !blocks.is_empty() && blocks.len() != self.block_nodes.len() {
            return Err(Error::Length {
                what: "nodal blocks".into(),
                expected: self.block_nodes.len(),
                got: blocks.len(),
            });
        }
        if g.len() != problem.mesh.n_cells() {
            return Err(Error::Length {
                what: "secant moduli".into(),
                expected: problem.mesh.n_cells(),
                got: g.len(),
            });
        }
        let dim = problem.mesh.dim();
        let mut values = vec![0.0; self.pattern.entries()];
        let n_cell_values = self.cell_offsets[self.cell_offsets.len() - 1];
        let (cell_values, block_values) = values.split_at_mut(n_cell_values);
        for_cells(&self.cell_offsets, cell_values, |c, out| {
            with_simplex!(dim, cell_values_into(problem, &self.dofs, g[c], c, out))
        })?;
        let block_pairs = self.block_nodes.iter().enumerate().flat_map(|(b, &node)| {
            nodal_pairs(&self.dofs, dim, node)
                .map(move |(i, j, ..)| blocks.get(b).map_or(0.0, |k| k[i][j]))
        });
        block_values.iter_mut().zip(block_pairs).for_each(|(v, k)| *v = k);
        let (matrix, mut lifting) = self.pattern.assemble(&values)?;
        lifting.iter_mut().for_each(|l| *l = -*l);
        Ok((matrix, lifting))
    }

    /// The entries of a global vector at the free DOFs.
    pub fn restrict(&self, global: &[f64]) -> Vec<f64> {
        let mut free = vec![0.0; self.dofs.n_free()];
        for (g, v) in global.iter().enumerate() {
            let k = self.dofs.free_index(g);
            if k != CONSTRAINED {
                free[k] = *v;
            }
        }
        free
    }
}

/// Runs `f(cell, values of the cell)` over all cells in parallel, the cells' values being
/// consecutive slices of `out` delimited by `offsets`.
fn for_cells<T: Send>(
    offsets: &[usize],
    out: &mut [T],
    f: impl Fn(usize, &mut [T]) -> Result<()> + Sync,
) -> Result<()> {
    let n_cells = offsets.len() - 1;
    let mut tasks = Vec::with_capacity(n_cells.div_ceil(CELLS_PER_TASK));
    let mut rest = out;
    for first in (0..n_cells).step_by(CELLS_PER_TASK) {
        let last = (first + CELLS_PER_TASK).min(n_cells);
        let (head, tail) = rest.split_at_mut(offsets[last] - offsets[first]);
        tasks.push((first..last, head));
        rest = tail;
    }
    tasks.into_par_iter().try_for_each(|(cells, slice)| {
        let base = offsets[cells.start];
        cells
            .into_iter()
            .try_for_each(|c| f(c, &mut slice[offsets[c] - base..offsets[c + 1] - base]))
    })
}

/// The element matrix of cell `c` at the positions of [`local_pairs`]: K_pq, times the
/// prescribed value of the column where it is constrained (the lifting).
fn cell_values_into<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    g: f64,
    c: usize,
    out: &mut [f64],
) -> Result<()> {
    let k = element_matrix(&problem.material, &simplex::<D, N>(problem, c)?, g);
    let global = local_dofs::<D, N>(dofs, problem.mesh.cell(c));
    for (value, (p, q, _, col)) in out.iter_mut().zip(local_pairs(dofs, global, N * (D + 1))) {
        *value = if col == CONSTRAINED { k[p][q] * dofs.prescribed(global[q]) } else { k[p][q] };
    }
    Ok(())
}

/// The number of [`local_pairs`] of cell `c`.
fn cell_pair_count<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    c: usize,
) -> usize {
    local_pairs(dofs, local_dofs::<D, N>(dofs, problem.mesh.cell(c)), N * (D + 1)).count()
}

/// The positions of the [`local_pairs`] of cell `c`: (row, column), or (row, VECTOR_ENTRY)
/// for a constrained column.
fn cell_positions_into<const D: usize, const N: usize>(
    problem: &Problem,
    dofs: &DofMap,
    c: usize,
    out: &mut [(usize, usize)],
) {
    let global = local_dofs::<D, N>(dofs, problem.mesh.cell(c));
    for (slot, (_, _, r, col)) in out.iter_mut().zip(local_pairs(dofs, global, N * (D + 1))) {
        *slot = (r, if col == CONSTRAINED { VECTOR_ENTRY } else { col });
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

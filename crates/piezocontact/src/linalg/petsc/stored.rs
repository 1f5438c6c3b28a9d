//! The distributed matrix as the backend stores it: one AIJ matrix, or — on the iterative
//! route with its field split — PETSc's MATNEST of the four field blocks (K_uu, K_uϕ, K_ϕu,
//! K_ϕϕ), so that the split takes its blocks by reference instead of copying them (about
//! 0.6 KB per unknown in 3D, docs/distributed.md). Either way it is written and read by the
//! rows of the whole matrix in PETSc's numbering; [`Split`] turns them into the blocks'.

use super::ffi::{Matrix, PetscInt, Vector};
use crate::error::Result;

/// The two fields' numbering: each field's rows of the whole matrix, numbered process by
/// process in the whole matrix's order, are the rows of its blocks.
#[derive(Debug)]
pub struct Split {
    /// The field (0: u and the held rows, 1: ϕ) of each row of the whole matrix.
    field: Vec<u8>,
    /// Each row's index among its field's rows.
    index: Vec<PetscInt>,
    /// The whole matrix's row of each index of each field.
    whole: [Vec<PetscInt>; 2],
}

impl Split {
    /// The split with the field of each row of the whole matrix.
    pub fn new(field: Vec<u8>) -> Self {
        let mut whole: [Vec<PetscInt>; 2] = [Vec::new(), Vec::new()];
        let index = field
            .iter()
            .enumerate()
            .map(|(p, &f)| {
                let list = &mut whole[f as usize];
                list.push(p as PetscInt);
                (list.len() - 1) as PetscInt
            })
            .collect();
        Self { field, index, whole }
    }

    /// The field of the whole matrix's row (or column) `p`.
    pub fn field(&self, p: usize) -> usize {
        self.field[p] as usize
    }

    /// The number of rows of field `f` over all processes.
    fn len(&self, f: usize) -> usize {
        self.whole[f].len()
    }
}

/// The preallocation of the whole matrix's owned rows: per row, the entries in the owned
/// columns (`diagonal`) and outside (`off`), each counted by the columns' field.
#[derive(Debug)]
pub struct Preallocation {
    pub diagonal: [Vec<PetscInt>; 2],
    pub off: [Vec<PetscInt>; 2],
}

impl Preallocation {
    /// Both fields' counts added: the preallocation of the one AIJ matrix.
    fn whole(&self) -> (Vec<PetscInt>, Vec<PetscInt>) {
        let add = |[a, b]: &[Vec<PetscInt>; 2]| a.iter().zip(b).map(|(a, b)| a + b).collect();
        (add(&self.diagonal), add(&self.off))
    }
}

/// The four blocks, the MATNEST over them, and the split.
#[derive(Debug)]
pub struct Blocks {
    nest: Matrix,
    blocks: [[Matrix; 2]; 2],
    split: Split,
    /// Each field's (columns, values) of the row being written.
    scratch: [(Vec<PetscInt>, Vec<f64>); 2],
}

impl Blocks {
    /// Puts the (whole matrix's index, value) pairs `at`, `values` into the scratch by their
    /// field, as indices of that field's blocks; the field and index of `line` (the row or
    /// column they lie on).
    fn sort_by_field(
        &mut self,
        line: PetscInt,
        at: &[PetscInt],
        values: &[f64],
    ) -> (usize, PetscInt) {
        let Self { split, scratch, .. } = self;
        scratch.iter_mut().for_each(|(a, v)| (a.clear(), v.clear()).1);
        for (&p, &v) in at.iter().zip(values) {
            let (indices, values) = &mut scratch[split.field(p as usize)];
            indices.push(split.index[p as usize]);
            values.push(v);
        }
        (split.field(line as usize), split.index[line as usize])
    }
}

/// The distributed matrix: [`Stored::Whole`] one AIJ matrix, [`Stored::Blocks`] the MATNEST.
#[derive(Debug)]
pub enum Stored {
    Whole(Matrix),
    Blocks(Box<Blocks>),
}

impl Stored {
    /// One AIJ matrix of `total` rows, `start..end` this process's.
    pub fn whole(
        (start, end): (usize, usize),
        total: usize,
        counts: &Preallocation,
    ) -> Result<Self> {
        let (diagonal, off) = counts.whole();
        Ok(Self::Whole(Matrix::new(end - start, total, &diagonal, &off)?))
    }

    /// The MATNEST of the blocks of `split` for this process's rows `start..end` of the
    /// whole matrix, field 0's diagonal block with the block size `block` (its rows a node's
    /// `block` together).
    pub fn blocks(
        (start, end): (usize, usize),
        split: Split,
        counts: &Preallocation,
        block: usize,
    ) -> Result<Self> {
        let owned: [Vec<PetscInt>; 2] = [0, 1].map(|f| {
            (start..end).filter(|&p| split.field(p) == f).map(|p| p as PetscInt).collect()
        });
        let sizes = [0, 1].map(|f| (owned[f].len(), split.len(f)));
        let make = |f: usize, g: usize| {
            let of_rows = |counts: &[PetscInt]| -> Vec<PetscInt> {
                owned[f].iter().map(|&p| counts[p as usize - start]).collect()
            };
            let (diagonal, off) = (of_rows(&counts.diagonal[g]), of_rows(&counts.off[g]));
            let block = if (f, g) == (0, 0) { block } else { 1 };
            Matrix::rectangular([sizes[f], sizes[g]], (&diagonal, &off), block)
        };
        let blocks = [[make(0, 0)?, make(0, 1)?], [make(1, 0)?, make(1, 1)?]];
        let nest = Matrix::nest(
            [&owned[0], &owned[1]],
            [[&blocks[0][0], &blocks[0][1]], [&blocks[1][0], &blocks[1][1]]],
        )?;
        let scratch = [(Vec::new(), Vec::new()), (Vec::new(), Vec::new())];
        Ok(Self::Blocks(Box::new(Blocks { nest, blocks, split, scratch })))
    }

    /// The matrix as an operator: for products, Krylov solvers and factorisations.
    pub fn operator(&self) -> &Matrix {
        match self {
            Self::Whole(matrix) => matrix,
            Self::Blocks(blocks) => &blocks.nest,
        }
    }

    /// A distributed vector of the matrix's row layout.
    pub fn vector(&self) -> Result<Vector> {
        self.operator().vector()
    }

    /// Puts `values` at (row, cols) of an owned row (the whole matrix's numbering).
    pub fn set_row(&mut self, row: PetscInt, cols: &[PetscInt], values: &[f64]) -> Result<()> {
        let blocks = match self {
            Self::Whole(matrix) => return matrix.set_row(row, cols, values),
            Self::Blocks(blocks) => blocks,
        };
        let (f, r) = blocks.sort_by_field(row, cols, values);
        let Blocks { blocks, scratch, .. } = &mut **blocks;
        for (g, (columns, values)) in scratch.iter().enumerate().filter(|(_, s)| !s.0.is_empty()) {
            blocks[f][g].set_row(r, columns, values)?;
        }
        Ok(())
    }

    /// Puts `values` at (rows, col) of owned rows (the whole matrix's numbering).
    pub fn set_column(&mut self, rows: &[PetscInt], col: PetscInt, values: &[f64]) -> Result<()> {
        let blocks = match self {
            Self::Whole(matrix) => return matrix.set_column(rows, col, values),
            Self::Blocks(blocks) => blocks,
        };
        let (g, c) = blocks.sort_by_field(col, rows, values);
        let Blocks { blocks, scratch, .. } = &mut **blocks;
        for (f, (at, values)) in scratch.iter().enumerate().filter(|(_, s)| !s.0.is_empty()) {
            blocks[f][g].set_column(at, c, values)?;
        }
        Ok(())
    }

    /// The stored (column, value) pairs of an owned row (the whole matrix's numbering).
    pub fn row(&self, row: PetscInt) -> Result<Vec<(usize, f64)>> {
        let Blocks { blocks, split, .. } = match self {
            Self::Whole(matrix) => return matrix.row(row),
            Self::Blocks(blocks) => &**blocks,
        };
        let (f, r) = (split.field(row as usize), split.index[row as usize]);
        let mut out = Vec::new();
        for (g, block) in blocks[f].iter().enumerate() {
            let whole = &split.whole[g];
            out.extend(block.row(r)?.into_iter().map(|(c, v)| (whole[c] as usize, v)));
        }
        Ok(out)
    }

    /// Final assembly after the values are set (the MATNEST's assembles its blocks); marks
    /// the matrix symmetric if it is.
    pub fn assemble(&mut self, symmetric: bool) -> Result<()> {
        match self {
            Self::Whole(matrix) => matrix.assemble(symmetric),
            Self::Blocks(blocks) => blocks.nest.assemble(symmetric),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows 0, 2, 3 of field 0 and 1, 4 of field 1: each field's rows numbered in the whole
    /// matrix's order, and back.
    #[test]
    fn each_field_numbers_its_rows_in_the_whole_matrix_s_order() {
        let split = Split::new(vec![0, 1, 0, 0, 1]);
        assert_eq!(split.index, vec![0, 0, 1, 2, 1]);
        assert_eq!(split.whole, [vec![0, 2, 3], vec![1, 4]]);
        assert_eq!((split.len(0), split.len(1), split.field(4)), (3, 2, 1));
        let counts =
            Preallocation { diagonal: [vec![2, 1], vec![3, 0]], off: [vec![1, 0], vec![0, 4]] };
        assert_eq!(counts.whole(), (vec![5, 1], vec![1, 4]));
    }
}

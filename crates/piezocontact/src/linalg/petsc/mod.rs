//! [`PetscSolver`]: PETSc's distributed AIJ matrix and MUMPS's LDLᵀ (symmetric indefinite,
//! `sym = 2`) behind the [`LinearSolver`] seam, with the [`SchurComplement`] capability from
//! MUMPS's Schur complement; built with the cargo feature `petsc` (docs/distributed.md).
//!
//! Every process runs the same program on the same mesh. Through the [`Distributed`]
//! capability the backend splits the mesh nodes between the processes (METIS's k-way
//! partition), each process assembles the rows of its nodes, and the backend hands them to
//! PETSc — numbered process by process, node by node — which distributes the factor over the
//! processes. Vectors cross the seam whole: a solve scatters the owned rows of the right-hand
//! side and gathers the solution back to every process.
//!
//! As [`super::LdltSolver`], the matrix is scaled symmetrically by its diagonal,
//! `D A D` with `D = diag(|a_ii|^{-1/2})`, so that the u and ϕ blocks meet on equal terms in
//! MUMPS's pivoting. MUMPS's inertia (INFOG(12), the negative pivots) is checked against the
//! quasi-definite matrix's: one per ϕ row (on one process only: the
//! private `PetscSolver::check_inertia` says why).
//!
//! With a Schur set, MUMPS leaves the Schur block out of the factor and returns S dense on
//! rank 0, which broadcasts it; a solve is then the interior with the Schur unknowns at zero
//! (MUMPS's ICNTL(26) = 0), so a whole solve is two of them around a dense solve with S:
//! y = K_ii⁻¹ b_i, x_c = S⁻¹ (b_c − K_ci y), x_i = K_ii⁻¹ (b_i − K_ic x_c).
//!
//! On the iterative route ([`PetscSolver::iterative`]) the same distributed matrix is solved
//! by PETSc's GMRES with a field split over the u and ϕ rows and algebraic multigrid on each
//! (docs/distributed.md): its ϕ rows negated (both diagonal blocks then positive definite),
//! each field scaled by one constant instead of row by row (the rigid-body modes of the
//! elastic field, its multigrid's near null space, stay those of the unscaled matrix). With
//! the field split the matrix is stored as its four field blocks (PETSc's MATNEST: the split
//! takes its blocks by reference instead of copying them), written and read by the rows of
//! the whole matrix (the private module `stored`).

mod ffi;
mod lag;
mod scaling;
mod stored;

pub use ffi::{abort, gather, initialize, option, rank_and_size, sum_over_processes};

use super::dense::DenseMatrix;
use super::rows::{Patched, RowMatrix};
use super::seam::{
    Distributed, LinearRoute, LinearSolver, SchurComplement, SolverStats, UnsymmetricSolve,
};
use super::sparse::{PatternIndex, SymmetricMatrix, SymmetricPattern};
use super::vectors::check_length;
use crate::error::{Error, Result};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use ffi::{Factor, Field, Gather, Krylov, KrylovSolve, PetscInt, Vector};
use lag::Lag;
use scaling::{Scaled, Scaling};
use std::time::Instant;
use stored::{Preallocation, Split, Stored};

/// The rows of the matrix this process owns. PETSc numbers
/// the unknowns process by process and node by node (a node's u and ϕ together, in the order
/// of their components), so that each process's block of PETSc rows is the unknowns of its
/// nodes. On the iterative route a node with some but not all of its elastic components free
/// also gets a [`HELD`] row for each constrained one: an identity row, with 0 on the right and
/// in the solution, so that every node with elastic rows has `dim` of them, as the multigrid's
/// block size and the rigid-body modes want.
#[derive(Debug)]
struct Rows {
    /// Order of the seam's matrix.
    n: usize,
    /// Order of PETSc's matrix: `n` and the held rows.
    total: usize,
    /// This process's PETSc rows: `start..end`.
    start: usize,
    end: usize,
    /// The unknowns among them (the others are held rows).
    owned: usize,
    /// The unknown at each of this process's PETSc rows, `start..end` ([`HELD`] at a held
    /// row).
    order: Vec<usize>,
    /// The PETSc row of each unknown (PETSc's 32-bit indices: half the bytes of a `usize`).
    petsc: Vec<PetscInt>,
    /// The mesh node of each owned PETSc row.
    nodes: Vec<usize>,
}

/// The unknown of a held row (a constrained elastic component kept as an identity row).
const HELD: usize = usize::MAX;

impl Rows {
    /// PETSc's numbering of the unknowns of `pattern` (whose groups are the mesh nodes) with
    /// `partition` (the process of each node, from [`Distributed::owned_nodes`]; needed on
    /// more than one process) and this process's block of it; with `held` (the dimension and
    /// the component of each unknown, `dim` for ϕ), the held rows too.
    fn new(
        pattern: &SymmetricPattern,
        partition: Option<&[usize]>,
        held: Option<(usize, &[u8])>,
    ) -> Result<Self> {
        let n = pattern.n();
        let (rank, size) = rank_and_size();
        let process = |node: usize| partition.map_or(Some(0), |p| p.get(node).copied());
        if size > 1 && (0..n).any(|k| process(pattern.group(k)).is_none()) {
            return Err(Error::LinearAlgebra(
                "PETSc backend: on several processes, owned_nodes must partition the mesh before the analysis".into(),
            ));
        }
        let process = |node: usize| process(node).unwrap_or(0);
        let component = |k: usize| held.map_or(0, |(_, c)| c[k] as usize);
        // (process, node, component, unknown) of each PETSc row, in PETSc's order.
        let mut keys: Vec<[usize; 4]> = (0..n)
            .map(|k| [process(pattern.group(k)), pattern.group(k), component(k), k])
            .collect();
        if let Some((dim, components)) = held {
            let nodes = held_components(pattern, dim, components);
            keys.extend(nodes.into_iter().map(|(node, i)| [process(node), node, i, HELD]));
        }
        keys.sort_unstable();
        let total = keys.len();
        ffi::index(total)?;
        let mut petsc = vec![0; n];
        let unknowns = keys.iter().enumerate().filter(|(_, key)| key[3] != HELD);
        unknowns.for_each(|(p, key)| petsc[key[3]] = p as PetscInt);
        let start = keys.partition_point(|key| key[0] < rank);
        let end = keys.partition_point(|key| key[0] <= rank);
        let order = keys[start..end].iter().map(|key| key[3]).collect();
        let nodes = keys[start..end].iter().map(|key| key[1]).collect();
        let owned = keys[start..end].iter().filter(|key| key[3] != HELD).count();
        Ok(Self { n, total, start, end, owned, order, petsc, nodes })
    }

    /// Whether unknown i's row is this process's.
    fn owns(&self, i: usize) -> bool {
        (self.start..self.end).contains(&self.row(i))
    }

    /// Unknown i's PETSc row.
    fn row(&self, i: usize) -> usize {
        self.petsc[i] as usize
    }

    /// The unknown at this process's PETSc row p ([`HELD`] at a held row).
    fn unknown(&self, p: usize) -> usize {
        self.order[p - self.start]
    }

    /// PETSc's preallocation for the seam's matrix of pattern `symbolic` (its lower triangle):
    /// per owned row, entries in the owned columns and outside, by the field (`field` of a
    /// PETSc row: 0 or 1) of their columns; none in the rows of the unknowns (or [`HELD`])
    /// that `only` leaves out, 1 on a held row's diagonal (field 0).
    fn preallocation(
        &self,
        symbolic: SymbolicSparseColMatRef<'_, PatternIndex>,
        only: impl Fn(usize) -> bool,
        field: impl Fn(usize) -> usize,
    ) -> Preallocation {
        let local = self.end - self.start;
        let [mut diagonal, mut off] = [(); 2].map(|()| [vec![0; local], vec![0; local]]);
        let mut count = |row: usize, column: usize| {
            if self.owns(row) && only(row) {
                let (k, f) = (self.row(row) - self.start, field(self.row(column)));
                match self.owns(column) {
                    true => diagonal[f][k] += 1,
                    false => off[f][k] += 1,
                }
            }
        };
        for j in 0..self.n {
            for i in symbolic.row_idx()[symbolic.col_range(j)].iter().map(|&i| i as usize) {
                count(i, j);
                if i != j {
                    count(j, i);
                }
            }
        }
        for p in (self.start..self.end).filter(|&p| self.unknown(p) == HELD && only(HELD)) {
            diagonal[0][p - self.start] = 1;
        }
        Preallocation { diagonal, off }
    }

    /// The split of PETSc's rows into u (with the held rows) and ϕ (pivot sign −1 in
    /// `signs`).
    fn split(&self, signs: &[i8]) -> Split {
        let mut field = vec![0; self.total];
        (0..self.n).filter(|&k| signs[k] < 0).for_each(|k| field[self.row(k)] = 1);
        Split::new(field)
    }

    /// Copies the owned rows of `whole` (the seam's numbering) into `local` (PETSc's), 0 at
    /// the held rows.
    fn scatter(&self, whole: &[f64], local: &mut [f64]) {
        local.iter_mut().zip(&self.order).for_each(|(l, &k)| *l = whole.get(k).map_or(0.0, |w| *w));
    }

    /// This process's PETSc rows that hold the unknowns of pivot sign `sign` (+1 for u, with
    /// the held rows; −1 for ϕ).
    fn field(&self, signs: &[i8], sign: i8) -> Vec<usize> {
        let sign_of = |p: usize| signs.get(self.unknown(p)).copied().unwrap_or(1);
        (self.start..self.end).filter(|&p| sign_of(p) == sign).collect()
    }

    /// Copies the distributed `v` whole into `whole` (the seam's numbering) on every process.
    fn gather(&self, (v, gather): (&Vector, &mut Gathers), whole: &mut [f64]) -> Result<()> {
        let mut run = match gather.kept.take() {
            Some(run) => run,
            None => Gather::new(v)?,
        };
        let gathered = run.run(v, |all| {
            whole.iter_mut().zip(&self.petsc).for_each(|(w, &p)| *w = all[p as usize]);
        });
        if gather.keep {
            gather.kept = Some(run);
        }
        gathered
    }

    /// The unknowns of a vector given as `part`, in its order: all of them, or those whose
    /// rows this process owns, increasing.
    fn unknowns(&self, part: Part) -> impl Iterator<Item = usize> + '_ {
        (0..self.n).filter(move |&k| part == Part::Whole || self.owns(k))
    }

    /// f(k, entry) for each entry of a vector given as `part`, k its unknown.
    fn each(&self, part: Part, values: &mut [f64], f: impl Fn(usize, &mut f64)) {
        self.unknowns(part).zip(values).for_each(|(k, v)| f(k, v));
    }

    /// Copies a vector given as `part` (the seam's numbering) into `local` (this process's
    /// PETSc rows), 0 at the held rows.
    fn put(&self, part: Part, values: &[f64], local: &mut [f64]) {
        match part {
            Part::Whole => self.scatter(values, local),
            Part::Owned => {
                local.fill(0.0);
                let at = |k: usize| self.row(k) - self.start;
                self.unknowns(part).zip(values).for_each(|(k, v)| local[at(k)] = *v);
            }
        }
    }

    /// Reads the distributed `x` into `values`, a vector given as `part`: whole (gathered on
    /// every process by `gather`), or this process's rows.
    fn take(
        &self,
        part: Part,
        (x, gather): (&mut Vector, &mut Gathers),
        values: &mut [f64],
    ) -> Result<()> {
        match part {
            Part::Whole => self.gather((x, gather), values),
            Part::Owned => x.with_local(|local| {
                let at = |k: usize| self.row(k) - self.start;
                self.unknowns(part).zip(values.iter_mut()).for_each(|(k, v)| *v = local[at(k)]);
            }),
        }
    }
}

/// How a vector of the unknowns crosses the seam.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Part {
    /// Every unknown, on every process.
    Whole,
    /// The unknowns whose rows this process owns, increasing ([`UnsymmetricSolve`]).
    Owned,
}

/// How the backend gathers distributed vectors whole onto every process: PETSc's scatter
/// holds a vector of every unknown on every process, so on the iterative route, where whole
/// vectors are rare (the solve without contact forces, the assessment), one is made for each
/// gather instead of kept between them.
#[derive(Debug)]
struct Gathers {
    kept: Option<Gather>,
    /// Whether a gather is kept for the next one (the direct route, whose every solve is whole).
    keep: bool,
}

/// A row of the distributed matrix kept aside: PETSc's row, its columns and values.
type SavedRow = (PetscInt, Vec<PetscInt>, Vec<f64>);

/// The PETSc objects of one analysis.
#[derive(Debug)]
struct Objects {
    /// The factorised matrix (during a solve with a patched matrix, the preconditioning one:
    /// [`UnsymmetricSolve`]).
    matrix: Stored,
    factor: Option<Factor>,
    krylov: Option<Krylov>,
    /// Whether the Krylov solver's preconditioner was made from scratch for the matrix's
    /// values as they are: false once values are written after it, for the setup they call
    /// for keeps the first setup's interpolations (GAMG's default), and a solve that does not
    /// converge with it is solved again with a preconditioner made anew.
    from_scratch: bool,
    b: Vector,
    x: Vector,
    gather: Gathers,
}

impl Objects {
    /// Final assembly of the matrix after its values are written.
    fn assemble(&mut self, symmetric: bool) -> Result<()> {
        self.from_scratch = false;
        self.matrix.assemble(symmetric)
    }
}

/// Writes this process's rows of the unknowns that `only` takes (never a held one) into
/// `target` as the backend holds a matrix (`scaled`): unknown i's row from `row(i, entries)`,
/// which pushes its (unknown, value) pairs.
fn write_rows(
    target: &mut Stored,
    (rows, only): (&Rows, impl Fn(usize) -> bool),
    scaled: Scaled<'_>,
    mut row: impl FnMut(usize, &mut Vec<(usize, f64)>),
) -> Result<()> {
    let (mut entries, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    for p in rows.start..rows.end {
        let i = rows.unknown(p);
        if i == HELD || !only(i) {
            continue;
        }
        let s = scaled.row(i);
        entries.clear();
        row(i, &mut entries);
        cols.clear();
        vals.clear();
        for &(j, v) in &entries {
            cols.push(rows.petsc[j]);
            vals.push(v * s * scaled.column(j));
        }
        target.set_row(p as PetscInt, &cols, &vals)?;
    }
    Ok(())
}

/// Writes the owned rows (and [`HELD`] ones) of the seam's matrix (`lower`: its lower
/// triangle) into `target`, scaled as [`write_rows`] does, column by
/// column of the lower triangle (column j's entries are row j's right of its diagonal and,
/// below it, an entry of each row i > j); a held row 1 on its diagonal (the scaled elastic
/// diagonal is 1 on average: [`Scaling::Fields`]).
fn write_lower(
    target: &mut Stored,
    rows: &Rows,
    scaled: Scaled<'_>,
    lower: SparseColMatRef<'_, PatternIndex, f64>,
) -> Result<()> {
    let (symbolic, values) = (lower.symbolic(), lower.val());
    let takes = |i: usize| rows.owns(i);
    let petsc = |i: usize| rows.petsc[i];
    let (mut at, mut vals) = (Vec::new(), Vec::new());
    for j in 0..rows.n {
        let range = symbolic.col_range(j);
        let (below, column) = (&symbolic.row_idx()[range.clone()], &values[range]);
        if takes(j) {
            at.clear();
            vals.clear();
            for (i, &v) in below.iter().map(|&i| i as usize).zip(column) {
                at.push(petsc(i));
                vals.push(v * scaled.row(j) * scaled.column(i));
            }
            target.set_row(petsc(j), &at, &vals)?;
        }
        at.clear();
        vals.clear();
        let others = below.iter().map(|&i| i as usize).zip(column);
        for (i, &v) in others.filter(|&(i, _)| i != j && takes(i)) {
            at.push(petsc(i));
            vals.push(v * scaled.row(i) * scaled.column(j));
        }
        if !at.is_empty() {
            target.set_column(&at, petsc(j), &vals)?;
        }
    }
    for p in (rows.start..rows.end).filter(|&p| rows.unknown(p) == HELD) {
        target.set_row(p as PetscInt, &[p as PetscInt], &[1.0])?;
    }
    Ok(())
}

/// MUMPS's LDLᵀ of the distributed matrix (see the module's documentation).
#[derive(Debug, Default)]
pub struct PetscSolver {
    rows: Option<Rows>,
    distributed: Option<Objects>,
    /// +1 for u rows, −1 for ϕ rows.
    signs: Vec<i8>,
    /// The unknowns kept for the Schur complement (empty: none).
    last: Vec<usize>,
    /// D of the last factorised matrix.
    scaling: Scaling,
    /// S of the scaled matrix (on every process) and its inverse, with a Schur set.
    schur: Option<(DenseMatrix, DenseMatrix)>,
    stats: SolverStats,
    /// The process of each mesh node, from [`Distributed::owned_nodes`].
    partition: Option<Vec<usize>>,
    /// The iterative route ([`PetscSolver::iterative`]): the Krylov solver's settings;
    /// `None`: MUMPS.
    iterative: Option<Iterative>,
    /// The mesh nodes' dimension and coordinates and the component of each unknown, from
    /// [`Distributed::node_layout`].
    layout: Option<Layout>,
    /// The Krylov iterations of each solve on the iterative route, in order.
    krylov_iterations: Vec<usize>,
    /// The most Krylov iterations of the next solve alone ([`UnsymmetricSolve::cap_next_solve`]).
    cap: Option<usize>,
    /// The operator's correction since the last factorisation ([`UnsymmetricSolve::correct`]).
    correction: Option<Correction>,
    /// The Krylov method's and the preconditioner's names, read at the last setup: they stay
    /// known when [`LinearSolver::release_work`] has freed the solver.
    kinds: Option<[String; 2]>,
    /// Whether a Newton step's solve keeps the preconditioner of an earlier step's.
    lag: Lag,
}

/// Row i of `patch` as (unknown, value) pairs.
fn row_entries(patch: &RowMatrix, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
    let (columns, values) = patch.row(i);
    columns.iter().copied().zip(values.iter().copied())
}

/// The operator's correction ([`UnsymmetricSolve::correct`]): its rows, the matrix of the
/// layout that holds them as the factorised matrix is held, and the operator, PETSc's
/// composite of the factorised matrix and that one.
#[derive(Debug)]
struct Correction {
    rows: RowMatrix,
    /// Held for the composite (which references it too).
    _matrix: Stored,
    operator: ffi::Matrix,
}

/// Whether unknown i (or [`HELD`]) has a row in `patch`: a held row never has.
fn patched_rows(patch: &RowMatrix) -> impl Fn(usize) -> bool + '_ {
    move |i| i != HELD && patch.has_row(i)
}

/// The error of a solve before the matrix is filled.
fn unfilled() -> Error {
    Error::LinearAlgebra("PETSc backend: solve before factorize".into())
}

/// The mesh nodes' dimension and coordinates and the component of each unknown.
type Layout = (usize, Vec<f64>, Vec<u8>);

/// The iterative route's settings (defaults that PETSc's options override).
#[derive(Clone, Copy, Debug, Default)]
struct Iterative {
    /// The relative tolerance on the residual of the scaled system.
    rtol: f64,
    /// The most iterations of one solve.
    max_iterations: usize,
}

/// The Krylov solver's relative tolerance by default: the direct route's answers to about
/// 1e−8 of their size on the block of model §13's measurements.
pub const KRYLOV_RTOL: f64 = 1e-10;

/// The most Krylov iterations of one solve by default.
pub const KRYLOV_MAX_ITERATIONS: usize = 2000;

impl PetscSolver {
    /// The backend on every process of the run, starting PETSc (and MPI) if needed.
    pub fn new() -> Result<Self> {
        initialize("")?;
        Ok(Self::default())
    }

    /// The iterative route on every process of the run: GMRES preconditioned by a field
    /// split over u and ϕ with algebraic multigrid on each (module documentation), to the
    /// relative tolerance `rtol` in at most `max_iterations` per solve; no Schur complement.
    pub fn iterative(rtol: f64, max_iterations: usize) -> Result<Self> {
        initialize("")?;
        let lag = Lag::from_options()?;
        Ok(Self { iterative: Some(Iterative { rtol, max_iterations }), lag, ..Self::default() })
    }

    /// The unknowns whose rows this process owns, after an analysis.
    pub fn owned_unknowns(&self) -> Vec<usize> {
        let owned = self.rows.as_ref().map(|r| &r.order);
        owned.into_iter().flatten().copied().filter(|&k| k != HELD).collect()
    }

    /// The distributed matrix's owned rows as PETSc stores them, unscaled (and on the
    /// iterative route the ϕ rows' negation undone): (row, column, value) of the seam's
    /// unknowns, for the check that it is the seam's matrix.
    pub fn owned_entries(&self) -> Result<Vec<(usize, usize, f64)>> {
        let (Some(rows), Some(d)) = (&self.rows, &self.distributed) else {
            return Ok(Vec::new());
        };
        let mut unknown = vec![HELD; rows.total];
        (0..rows.n).for_each(|k| unknown[rows.row(k)] = k);
        let (scaled, mut out) = (self.scaled(), Vec::new());
        for p in (rows.start..rows.end).filter(|&p| rows.unknown(p) != HELD) {
            let i = rows.unknown(p);
            for (q, v) in d.matrix.row(p as PetscInt)? {
                let j = unknown[q];
                out.push((i, j, v / (scaled.row(i) * scaled.column(j))));
            }
        }
        Ok(out)
    }

    /// Whether the distributed matrix is stored as its field blocks (PETSc's MATNEST, which
    /// the field split reads without copies), not as one AIJ matrix.
    pub fn stores_field_blocks(&self) -> bool {
        self.distributed.as_ref().is_some_and(|d| matches!(d.matrix, Stored::Blocks(_)))
    }

    fn analyze_rows(
        &mut self,
        pattern: &SymmetricPattern,
        signs: &[i8],
        last: &[usize],
    ) -> Result<()> {
        check_length("pivot signs", pattern.n(), signs.len())?;
        if let Some(&bad) = last.iter().find(|&&i| i >= pattern.n()) {
            return Err(Error::LinearAlgebra(format!("Schur unknown {bad} of {}", pattern.n())));
        }
        let t = Instant::now();
        self.distributed = None;
        self.schur = None;
        let held = match (&self.iterative, &self.layout) {
            (Some(_), Some((dim, _, components))) if components.len() == pattern.n() => {
                Some((*dim, &components[..]))
            }
            _ => None,
        };
        self.rows = Some(Rows::new(pattern, self.partition.as_deref(), held)?);
        self.signs = signs.to_vec();
        self.last = last.to_vec();
        self.stats.symbolic_seconds += t.elapsed().as_secs_f64();
        self.stats.ordering = "mumps";
        Ok(())
    }

    /// The distributed matrix with the scaled values of `matrix`, made at the first
    /// factorisation after an analysis and refilled afterwards.
    fn fill(&mut self, matrix: &SymmetricMatrix) -> Result<()> {
        let rows = self.rows.as_ref().ok_or_else(|| {
            Error::LinearAlgebra("PETSc backend: factorize before analyze".into())
        })?;
        check_length("matrix order", rows.n, matrix.n())?;
        if self.distributed.is_none() {
            let matrix = self.stored(rows, matrix.lower().symbolic())?;
            let (b, x) = (matrix.vector()?, matrix.vector()?);
            let gather = Gathers { kept: None, keep: self.iterative.is_none() };
            let (factor, krylov, from_scratch) = (None, None, false);
            self.distributed = Some(Objects { matrix, factor, krylov, from_scratch, b, x, gather });
        }
        self.scaling = match self.iterative {
            Some(_) => self.field_scaling(&matrix.diagonal())?,
            None => self.unknown_scaling(&matrix.diagonal())?,
        };
        let (Some(rows), Some(d)) = (&self.rows, self.distributed.as_mut()) else {
            return Err(unfilled());
        };
        let scaled = Scaled {
            scaling: &self.scaling,
            signs: &self.signs,
            iterative: self.iterative.is_some(),
        };
        write_lower(&mut d.matrix, rows, scaled, matrix.lower().as_ref())?;
        d.assemble(self.iterative.is_none())
    }

    /// The direct route's D from `diagonal` (K's, right on this process's rows), gathered
    /// whole: D must be the same on every process.
    fn unknown_scaling(&mut self, diagonal: &[f64]) -> Result<Scaling> {
        let (Some(rows), Some(d)) = (&self.rows, self.distributed.as_mut()) else {
            return Err(unfilled());
        };
        d.b.with_local(|b| rows.scatter(diagonal, b))?;
        let mut whole = vec![0.0; rows.n];
        rows.gather((&d.b, &mut d.gather), &mut whole)?;
        if let Some(i) = whole.iter().position(|d| *d == 0.0 || !d.is_finite()) {
            return Err(Error::SingularSystem { detail: format!("zero diagonal entry {i}") });
        }
        Ok(Scaling::Unknowns(whole.iter().map(|d| 1.0 / d.abs().sqrt()).collect()))
    }

    /// The iterative route's D from `diagonal` (K's, right on this process's rows): each
    /// field's sum of |a_ii| over the owned rows, summed over the processes; a zero or
    /// non-finite entry on any process is an error on every process.
    fn field_scaling(&self, diagonal: &[f64]) -> Result<Scaling> {
        let rows = self.rows.as_ref().ok_or_else(unfilled)?;
        // u's sum and count, ϕ's, and the last unfit entry + 1 (0: none).
        let (mut sums, mut unfit) = ([0.0; 4], 0.0f64);
        for &i in rows.order.iter().filter(|&&i| i != HELD) {
            let (a, f) = (diagonal[i], usize::from(self.signs[i] < 0));
            if a == 0.0 || !a.is_finite() {
                unfit = unfit.max(i as f64 + 1.0);
            }
            sums[f] += a.abs();
            sums[2 + f] += 1.0;
        }
        if let Some(i) = (self.max(unfit)? as usize).checked_sub(1) {
            return Err(Error::SingularSystem { detail: format!("zero diagonal entry {i}") });
        }
        self.sum_each(&mut sums)?;
        Ok(Scaling::fields([sums[0], sums[1]], [sums[2], sums[3]]))
    }

    /// How a matrix is written as the distributed one is.
    fn scaled(&self) -> Scaled<'_> {
        Scaled { scaling: &self.scaling, signs: &self.signs, iterative: self.iterative.is_some() }
    }

    /// The distributed matrix of `rows`, preallocated for `symbolic` (the seam's matrix's lower
    /// triangle): on the iterative route with the field split (the default, or `-pc_type
    /// fieldsplit`) PETSc's MATNEST of the u and ϕ blocks, else one AIJ matrix.
    fn stored(
        &self,
        rows: &Rows,
        symbolic: SymbolicSparseColMatRef<'_, PatternIndex>,
    ) -> Result<Stored> {
        let range = (rows.start, rows.end);
        let split = self.iterative.is_some()
            && ffi::option("-pc_type")?.is_none_or(|kind| kind == "fieldsplit");
        if !split {
            let counts = rows.preallocation(symbolic, |_| true, |_| 0);
            return Stored::whole(range, rows.total, &counts);
        }
        let split = rows.split(&self.signs);
        let counts = rows.preallocation(symbolic, |_| true, |p| split.field(p));
        let u = rows.field(&self.signs, 1);
        let block = rigid_modes(self.layout.as_ref(), rows, &u).map_or(1, |(dim, _)| dim);
        Stored::blocks(range, split, &counts, block)
    }

    /// The owned rows of the distributed matrix that `patch` will overwrite, as they are
    /// (PETSc's row, columns and values): what [`PetscSolver::restore_rows`] writes back.
    fn save_rows(&self, patch: &RowMatrix) -> Result<Vec<SavedRow>> {
        let (Some(rows), Some(d)) = (&self.rows, &self.distributed) else {
            return Err(unfilled());
        };
        let patched = patched_rows(patch);
        let saved = (rows.start..rows.end).filter(|&p| patched(rows.unknown(p))).map(|p| {
            let row = d.matrix.row(p as PetscInt)?;
            let columns = row.iter().map(|&(q, _)| q as PetscInt).collect();
            Ok((p as PetscInt, columns, row.iter().map(|&(_, v)| v).collect()))
        });
        saved.collect()
    }

    /// Writes `saved` rows back over the distributed matrix and assembles it.
    fn restore_rows(&mut self, saved: &[SavedRow]) -> Result<()> {
        let d = self.distributed.as_mut().ok_or_else(unfilled)?;
        for (row, columns, values) in saved {
            d.matrix.set_row(*row, columns, values)?;
        }
        d.assemble(false)
    }

    /// Writes the rows of `patch` (the seam's numbering, both triangles) over the owned rows
    /// of the distributed matrix, scaled as [`PetscSolver::fill`] does, and assembles it.
    fn write_patch(&mut self, patch: &RowMatrix) -> Result<()> {
        let (Some(rows), Some(d)) = (&self.rows, self.distributed.as_mut()) else {
            return Err(unfilled());
        };
        let iterative = self.iterative.is_some();
        let scaled = Scaled { scaling: &self.scaling, signs: &self.signs, iterative };
        write_rows(&mut d.matrix, (rows, patched_rows(patch)), scaled, |i, row| {
            row.extend(row_entries(patch, i));
        })?;
        d.assemble(false)
    }

    /// J − P, scaled as the distributed matrix: a matrix of the layout with entries only in
    /// the patched rows (the two patches share their pattern: [`Patched::new`]) and, with a
    /// correction, the correction's rows outside them (J's rows hold it already).
    fn difference(&self, patched: &Patched) -> Result<Stored> {
        let (jacobian, preconditioner) = (patched.jacobian(), patched.preconditioner());
        let in_patch = patched_rows(preconditioner);
        let correction = self.correction.as_ref().map(|c| &c.rows);
        let corrected = |i: usize| correction.filter(|c| patched_rows(c)(i) && !in_patch(i));
        let only = |i: usize| in_patch(i) || corrected(i).is_some();
        self.rows_matrix(patched.pattern(), only, |i, row| {
            if let Some(correction) = corrected(i) {
                return row.extend(row_entries(correction, i));
            }
            let (j, (columns, p)) = (jacobian.row(i).1, preconditioner.row(i));
            row.extend(columns.iter().copied().zip(j.iter().zip(p).map(|(j, p)| j - p)));
        })
    }

    /// A matrix of the layout with this process's rows of the unknowns that `only` takes
    /// alone, preallocated from `pattern` and written by `row` scaled and signed as the
    /// factorised matrix ([`write_rows`]), assembled.
    fn rows_matrix(
        &self,
        pattern: &SymmetricPattern,
        only: impl Fn(usize) -> bool,
        row: impl FnMut(usize, &mut Vec<(usize, f64)>),
    ) -> Result<Stored> {
        let rows = self.rows.as_ref().ok_or_else(unfilled)?;
        let counts = rows.preallocation(pattern.symbolic(), &only, |_| 0);
        let mut matrix = Stored::whole((rows.start, rows.end), rows.total, &counts)?;
        write_rows(&mut matrix, (rows, &only), self.scaled(), row)?;
        matrix.assemble(false)?;
        Ok(matrix)
    }

    /// The Krylov solver of the filled matrix, made after the first fill of an analysis (or
    /// after [`LinearSolver::release_work`]), and its preconditioner set up for the current
    /// values: from scratch when the solver is made here.
    fn set_up_krylov(&mut self) -> Result<()> {
        let (Some(rows), Some(d), Some(iterative)) =
            (&self.rows, self.distributed.as_mut(), &self.iterative)
        else {
            return Err(Error::LinearAlgebra("PETSc backend: set up before the fill".into()));
        };
        let made = d.krylov.is_none();
        if made {
            let (u, phi) = (rows.field(&self.signs, 1), rows.field(&self.signs, -1));
            let rigid = rigid_modes(self.layout.as_ref(), rows, &u);
            let petsc = |rows: Vec<usize>| rows.into_iter().map(|p| p as PetscInt).collect();
            let fields = [
                Field { name: c"u", rows: petsc(u), rigid },
                Field { name: c"phi", rows: petsc(phi), rigid: None },
            ];
            let (rtol, most) = (iterative.rtol, iterative.max_iterations);
            d.krylov = Some(Krylov::new(d.matrix.operator(), &fields, rtol, most)?);
        }
        let krylov = d.krylov.as_mut().expect("made above");
        krylov.set_up(d.matrix.operator())?;
        d.from_scratch = made;
        self.lag.reset();
        self.kinds = Some(match krylov.kinds() {
            Ok(kinds) => kinds,
            Err(e) => [(); 2].map(|()| format!("unknown ({e})")),
        });
        Ok(())
    }

    /// One Krylov solve of the scaled system (ϕ rows negated) — with the factorised matrix, or
    /// with `general` = (an operator, the relative residual), preconditioned as for the
    /// distributed matrix's current values or, where [`Lag`] says so, as for an earlier
    /// Newton step's —: `rhs` in and the solution out, both given as `part`. A solve that
    /// does not converge with a preconditioner other than one made from scratch for the
    /// current values (a kept one, or one whose setup kept the first setup's interpolations)
    /// is solved again with one made so, unless it was capped (a check, whose budget is its
    /// cap: [`UnsymmetricSolve::cap_next_solve`]); a solve that does not converge then is an
    /// error with its numbers and the options to change.
    fn krylov_solve(
        &mut self,
        (rhs, part): (&mut [f64], Part),
        general: Option<(&ffi::Matrix, f64)>,
    ) -> Result<()> {
        ffi::return_free_memory();
        if self.distributed.as_ref().is_some_and(|d| d.krylov.is_none()) {
            self.set_up_krylov()?;
        }
        let rows = self.rows.as_ref().expect("analysed");
        let scaled = self.scaled();
        rows.each(part, rhs, |k, b| *b *= scaled.sign(k));
        let d = self.distributed.as_mut().expect("set up");
        d.b.with_local(|b| rows.put(part, rhs, b))?;
        let keep = general.is_some() && self.lag.keep();
        let most = self.cap.take();
        let mut solve = self.attempt(general, keep, most)?;
        let (mut kept, mut spent) = (keep, 0);
        let from_scratch = self.distributed.as_ref().is_some_and(|d| d.from_scratch);
        if solve.reason <= 0 && !from_scratch && most.is_none() {
            // The lag and a failure's message read this attempt, the list of iterations both.
            spent = solve.iterations;
            self.distributed.as_mut().expect("set up").krylov = None;
            self.set_up_krylov()?;
            solve = self.attempt(general, false, most)?;
            kept = false;
        }
        match general {
            Some((_, rtol)) => self.lag.record(kept, solve.iterations, rtol),
            None => self.lag.reset(),
        }
        self.krylov_iterations.push(spent + solve.iterations);
        let d = self.distributed.as_mut().expect("set up");
        if solve.reason <= 0 {
            return Err(not_converged(d.krylov.as_ref().expect("set up"), &solve));
        }
        let rows = self.rows.as_ref().expect("analysed");
        rows.take(part, (&mut d.x, &mut d.gather), rhs)
    }

    /// One attempt of [`PetscSolver::krylov_solve`] from the distributed right-hand side,
    /// with the preconditioner of the last setup (`keep`) or one set up for the current
    /// values, in at most `most` iterations (`None`: the solver's own).
    fn attempt(
        &mut self,
        general: Option<(&ffi::Matrix, f64)>,
        keep: bool,
        most: Option<usize>,
    ) -> Result<KrylovSolve> {
        let d = self.distributed.as_mut().expect("set up");
        let krylov = d.krylov.as_mut().expect("set up");
        let own = d.matrix.operator();
        let (operator, rtol) = match general {
            Some(general) => general,
            None => (self.correction.as_ref().map_or(own, |c| &c.operator), krylov.tolerances()?.0),
        };
        krylov.reuse_preconditioner(keep)?;
        krylov.solve_operator((operator, own), (rtol, most), &d.b, &mut d.x)
    }

    /// `values`, given as `part`, times D (the scaling).
    fn scale(&self, part: Part, values: &mut [f64]) {
        let rows = self.rows.as_ref().expect("analysed");
        let scaled = self.scaled();
        rows.each(part, values, |k, v| *v *= scaled.column(k));
    }

    /// MUMPS's analysis (at the first factorisation after [`LinearSolver::analyze`]) and
    /// numeric factorisation, with the inertia checked; the analysis's time [s].
    fn factor(&mut self) -> Result<f64> {
        let d = self.distributed.as_mut().expect("filled");
        let mut analysis = 0.0;
        if d.factor.is_none() {
            let t = Instant::now();
            let schur: Vec<PetscInt> = match rank_and_size().0 {
                0 => {
                    let rows = self.rows.as_ref().expect("analysed");
                    self.last.iter().map(|&i| rows.petsc[i]).collect()
                }
                _ => Vec::new(),
            };
            let schur = (!self.last.is_empty()).then_some(&schur[..]);
            let factor = Factor::analyse(d.matrix.operator(), schur)?;
            // INFOG(17): the memory MUMPS's analysis estimates for the factorisation, summed
            // over the processes [MB].
            self.stats.factor_bytes = f64::from(factor.infog(17)?) * 1e6;
            d.factor = Some(factor);
            analysis = t.elapsed().as_secs_f64();
            self.stats.symbolic_seconds += analysis;
        }
        let factor = d.factor.as_mut().expect("analysed");
        factor.factorize(d.matrix.operator(), !self.last.is_empty())?;
        // INFOG(29): entries of the factor (negative: millions of entries).
        let entries = factor.infog(29)?;
        self.stats.factor_len = if entries < 0 {
            entries.unsigned_abs() as usize * 1_000_000
        } else {
            entries as usize
        };
        if rank_and_size().1 == 1 {
            let negative = factor.infog(12)? as usize;
            self.check_inertia(negative)?;
        }
        Ok(analysis)
    }

    /// MUMPS's count of negative pivots against the quasi-definite matrix's: one per ϕ row
    /// outside the Schur set. On more than one process MUMPS factorises the root of its tree
    /// with ScaLAPACK, whose pivots it does not count, and the check is not made.
    fn check_inertia(&self, negative: usize) -> Result<()> {
        let mut schur = vec![false; self.signs.len()];
        self.last.iter().for_each(|&c| schur[c] = true);
        let expected = (0..self.signs.len()).filter(|&i| self.signs[i] < 0 && !schur[i]).count();
        if negative == expected {
            return Ok(());
        }
        Err(Error::SingularSystem {
            detail: format!(
                "MUMPS found {negative} negative pivots where the quasi-definite matrix has {expected} (one per free ϕ unknown)"
            ),
        })
    }

    /// S of the scaled matrix from MUMPS, broadcast from rank 0, and its inverse.
    fn read_schur(&mut self) -> Result<()> {
        let m = self.last.len();
        let factor = self.distributed.as_ref().and_then(|d| d.factor.as_ref()).expect("factorised");
        let mut values = factor.schur_complement()?;
        values.resize(m * m, 0.0);
        ffi::broadcast(&mut values)?;
        let mut s = DenseMatrix::zeros(m);
        for j in 0..m {
            s.col_mut(j).copy_from_slice(&values[j * m..(j + 1) * m]);
        }
        s.symmetrize();
        let inverse = s.inverse()?;
        self.schur = Some((s, inverse));
        Ok(())
    }

    /// One MUMPS solve of the scaled system: `rhs` whole in, the whole solution out (with a
    /// Schur set, the interior with the Schur unknowns at zero).
    fn mumps_solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        let rows = self.rows.as_ref().expect("analysed");
        let d = self.distributed.as_mut().expect("factorised");
        d.b.with_local(|b| rows.scatter(rhs, b))?;
        d.factor.as_ref().expect("factorised").solve(&d.b, &mut d.x)?;
        rows.gather((&d.x, &mut d.gather), rhs)?;
        self.last.iter().for_each(|&c| rhs[c] = 0.0);
        Ok(())
    }

    /// y = A x of the scaled matrix (with the correction, if any), x and y given as `part`.
    fn multiply(&mut self, (x, part): (&[f64], Part)) -> Result<Vec<f64>> {
        let rows = self.rows.as_ref().expect("analysed");
        let d = self.distributed.as_mut().expect("filled");
        d.b.with_local(|b| rows.put(part, x, b))?;
        let operator = self.correction.as_ref().map_or(d.matrix.operator(), |c| &c.operator);
        operator.mult(&d.b, &mut d.x)?;
        let mut y = vec![0.0; x.len()];
        rows.take(part, (&mut d.x, &mut d.gather), &mut y)?;
        Ok(y)
    }

    /// The whole solve with a Schur set (the module's documentation): two interior solves
    /// around a dense solve with S, in the scaled system.
    fn solve_with_schur(&mut self, b: &mut [f64]) -> Result<()> {
        let mut y = b.to_vec();
        self.mumps_solve(&mut y)?;
        let k_y = self.multiply((&y, Part::Whole))?;
        // b − K y on the Schur rows, each from the process that owns it (b is read on the
        // owned rows alone).
        let rows = self.rows.as_ref().expect("analysed");
        let own = |c: usize| if rows.owns(c) { b[c] - k_y[c] } else { 0.0 };
        let mut reduced: Vec<f64> = self.last.iter().map(|&c| own(c)).collect();
        ffi::sum_each_over_processes(&mut reduced)?;
        let (_, inverse) = self.schur.as_ref().expect("read at factorisation");
        let x_c = inverse.mul(&reduced);
        let mut e = vec![0.0; b.len()];
        self.last.iter().zip(&x_c).for_each(|(&c, &v)| e[c] = v);
        let k_e = self.multiply((&e, Part::Whole))?;
        b.iter_mut().zip(&k_e).for_each(|(b, k)| *b -= k);
        self.mumps_solve(b)?;
        self.last.iter().zip(&x_c).for_each(|(&c, &v)| b[c] = v);
        Ok(())
    }
}

impl LinearSolver for PetscSolver {
    fn name(&self) -> &str {
        match self.iterative {
            Some(_) => "PETSc Krylov (GMRES, field split u/ϕ, GAMG)",
            None => "PETSc + MUMPS LDLᵀ",
        }
    }

    fn analyze(&mut self, pattern: &SymmetricPattern, signs: &[i8]) -> Result<()> {
        self.analyze_rows(pattern, signs, &[])
    }

    fn factorize(&mut self, matrix: &SymmetricMatrix) -> Result<()> {
        let t = Instant::now();
        self.correction = None;
        self.fill(matrix)?;
        if self.iterative.is_some() {
            self.set_up_krylov()?;
            self.stats.numeric_seconds += t.elapsed().as_secs_f64();
            self.stats.numeric_count += 1;
            return Ok(());
        }
        let analysis = self.factor()?;
        if !self.last.is_empty() {
            self.read_schur()?;
        }
        self.stats.numeric_seconds += t.elapsed().as_secs_f64() - analysis;
        self.stats.numeric_count += 1;
        Ok(())
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        let t = Instant::now();
        let n = self.rows.as_ref().map_or(0, |r| r.n);
        check_length("right-hand side", n, rhs.len())?;
        let factorised = match &self.distributed {
            Some(d) => self.iterative.is_some() || d.factor.is_some(),
            None => false,
        };
        if !factorised {
            return Err(Error::LinearAlgebra("PETSc backend: solve before factorize".into()));
        }
        self.scale(Part::Whole, rhs);
        if self.iterative.is_some() {
            self.krylov_solve((rhs, Part::Whole), None)?;
        } else if self.last.is_empty() {
            self.mumps_solve(rhs)?;
        } else {
            self.solve_with_schur(rhs)?;
        }
        self.scale(Part::Whole, rhs);
        self.stats.solve_seconds += t.elapsed().as_secs_f64();
        self.stats.solve_count += 1;
        Ok(())
    }

    fn stats(&self) -> SolverStats {
        self.stats
    }

    fn route(&self) -> LinearRoute {
        if self.iterative.is_none() {
            return LinearRoute::default();
        }
        // Before the first factorisation there is no solver to name; an unreadable name says
        // why rather than pass for the direct route's "none".
        let [method, preconditioner] = self
            .kinds
            .clone()
            .unwrap_or_else(|| [(); 2].map(|()| "not set up (no factorisation yet)".to_string()));
        LinearRoute {
            kind: "iterative",
            krylov: Some(method),
            preconditioner: Some(preconditioner),
            krylov_iterations: self.krylov_iterations.clone(),
        }
    }

    fn schur(&mut self) -> Option<&mut dyn SchurComplement> {
        match self.iterative {
            Some(_) => None,
            None => Some(self),
        }
    }

    fn distributed(&mut self) -> Option<&mut dyn Distributed> {
        Some(self)
    }

    fn unsymmetric(&mut self) -> Option<&mut dyn UnsymmetricSolve> {
        match self.iterative {
            Some(_) => Some(self),
            None => None,
        }
    }

    /// On the iterative route, the Krylov solver goes (GMRES's vectors, each of the size of
    /// the unknowns, and GAMG's hierarchy); the next solve makes it again for the matrix's
    /// values then.
    fn release_work(&mut self) -> Result<()> {
        if let Some(d) = self.distributed.as_mut() {
            d.krylov = None;
        }
        Ok(())
    }
}

/// On the iterative route: P written over the distributed matrix's patched rows (as the
/// factorised matrix is written: scaled, ϕ rows negated), the preconditioner (field split,
/// GAMG) set up for it, and J = P + (J − P) solved by the Krylov solver — J − P a matrix of
/// the patched rows alone, J the sum of the two held as PETSc's composite matrix —; the
/// factorised matrix's rows, read before P overwrote them, written back after. No other copy
/// of the matrix is made.
impl UnsymmetricSolve for PetscSolver {
    fn solve_unsymmetric(&mut self, patched: Patched, rhs: &mut [f64], rtol: f64) -> Result<()> {
        let t = Instant::now();
        let (n, owned) = self.rows.as_ref().map_or((0, 0), |r| (r.n, r.owned));
        check_length("right-hand side (this process's rows)", owned, rhs.len())?;
        check_length("Jacobian's patch order", n, patched.jacobian().n())?;
        if self.distributed.is_none() {
            return Err(unfilled());
        }
        let difference = self.difference(&patched)?;
        let saved = self.save_rows(patched.preconditioner())?;
        self.write_patch(patched.preconditioner())?;
        let own = self.distributed.as_ref().ok_or_else(unfilled)?.matrix.operator();
        let operator = ffi::Matrix::sum(&[own, difference.operator()])?;
        self.scale(Part::Owned, rhs);
        let solved = self.krylov_solve((rhs, Part::Owned), Some((&operator, rtol)));
        // K's rows again, whether or not the solve converged.
        self.restore_rows(&saved)?;
        solved?;
        self.scale(Part::Owned, rhs);
        self.stats.solve_seconds += t.elapsed().as_secs_f64();
        self.stats.solve_count += 1;
        Ok(())
    }

    /// K x from the distributed matrix, which holds S D K D (D the scaling, S −1 on the ϕ
    /// rows): K x = D⁻¹ S (S D K D) D⁻¹ x.
    fn product(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        let rows = self.rows.as_ref().ok_or_else(unfilled)?;
        check_length("x (this process's rows)", rows.owned, x.len())?;
        if self.distributed.is_none() {
            return Err(unfilled());
        }
        let mut scaled = x.to_vec();
        let written = self.scaled();
        rows.each(Part::Owned, &mut scaled, |k, v| *v /= written.column(k));
        let mut product = self.multiply((&scaled, Part::Owned))?;
        let (rows, written) = (self.rows.as_ref().ok_or_else(unfilled)?, self.scaled());
        rows.each(Part::Owned, &mut product, |k, y| *y /= written.row(k));
        Ok(product)
    }

    fn cap_next_solve(&mut self, iterations: usize) {
        self.cap = Some(iterations);
    }

    /// The correction's rows written into a matrix of the layout, scaled and signed as the
    /// factorised matrix is (its preallocation from the factorised matrix's pattern), and the
    /// composite of the two made once for every solve and product until the next
    /// factorisation.
    fn correct(&mut self, pattern: &SymmetricPattern, correction: RowMatrix) -> Result<()> {
        let (Some(rows), Some(d)) = (&self.rows, &self.distributed) else {
            return Err(unfilled());
        };
        check_length("correction order", rows.n, correction.n())?;
        let matrix = self.rows_matrix(pattern, patched_rows(&correction), |i, row| {
            row.extend(row_entries(&correction, i));
        })?;
        let operator = ffi::Matrix::sum(&[d.matrix.operator(), matrix.operator()])?;
        self.correction = Some(Correction { rows: correction, _matrix: matrix, operator });
        Ok(())
    }
}

impl Distributed for PetscSolver {
    /// METIS's k-way partition of the node graph into one part per process.
    fn owned_nodes(
        &mut self,
        weights: &[usize],
        adjacency: (&[usize], &[usize]),
    ) -> Result<Option<Vec<bool>>> {
        let (rank, size) = rank_and_size();
        if size == 1 {
            return Ok(None);
        }
        let partition = super::ordering::partition(adjacency, weights, size)?;
        let owned = partition.iter().map(|&p| p == rank).collect();
        self.partition = Some(partition);
        Ok(Some(owned))
    }

    fn sum_each(&self, values: &mut [f64]) -> Result<()> {
        ffi::sum_each_over_processes(values)
    }

    fn max(&self, value: f64) -> Result<f64> {
        ffi::max_over_processes(value)
    }

    fn node_layout(&mut self, dim: usize, coordinates: &[f64], components: &[u8]) {
        self.layout = Some((dim, coordinates.to_vec(), components.to_vec()));
    }
}

impl SchurComplement for PetscSolver {
    fn analyze_with_last(
        &mut self,
        pattern: &SymmetricPattern,
        signs: &[i8],
        last: &[usize],
    ) -> Result<()> {
        self.analyze_rows(pattern, signs, last)
    }

    fn schur_complement(&self) -> Result<DenseMatrix> {
        let (s, _) = self.schur.as_ref().ok_or_else(|| {
            Error::LinearAlgebra("PETSc backend: Schur complement before factorize".into())
        })?;
        let m = self.last.len();
        let mut out = DenseMatrix::zeros(m);
        let scaled = self.scaled();
        for (a, &i) in self.last.iter().enumerate() {
            for (b, &j) in self.last.iter().enumerate() {
                out.set(a, b, s.get(a, b) / (scaled.column(i) * scaled.column(j)));
            }
        }
        Ok(out)
    }
}

/// The (node, component) of each constrained elastic component of a node with some but not
/// all of its `dim` components among the unknowns (`components`: each unknown's, `dim` for
/// ϕ).
fn held_components(
    pattern: &SymmetricPattern,
    dim: usize,
    components: &[u8],
) -> Vec<(usize, usize)> {
    let nodes = (0..components.len()).map(|k| pattern.group(k) + 1).max().unwrap_or(0);
    let mut free = vec![0u8; nodes];
    for (k, &i) in components.iter().enumerate().filter(|(_, i)| (**i as usize) < dim) {
        free[pattern.group(k)] |= 1 << i;
    }
    let all = (1u8 << dim) - 1;
    let partial = free.into_iter().enumerate().filter(|&(_, mask)| mask != 0 && mask != all);
    partial
        .flat_map(|(node, mask)| {
            (0..dim).filter(move |i| mask & (1 << i) == 0).map(move |i| (node, i))
        })
        .collect()
}

/// The coordinates of the nodes of the owned elastic rows `u` (PETSc's rows, a node's rows
/// together), `dim` per node, where every node among them has `dim` of them (the held rows
/// complete a node on rollers); else `None` (no layout given): then the rigid-body modes
/// would not be those of the rows, and the multigrid goes without them. (A node in a turned
/// frame gets modes in the mesh's axes: a poorer preconditioner, the same answer.)
fn rigid(rows: &Rows, u: &[usize], dim: usize, coordinates: &[f64]) -> Option<Vec<f64>> {
    let mut out = Vec::with_capacity(u.len());
    for chunk in u.chunks(dim) {
        let node = rows.nodes[chunk[0] - rows.start];
        if chunk.len() != dim || chunk.iter().any(|&p| rows.nodes[p - rows.start] != node) {
            return None;
        }
        out.extend_from_slice(&coordinates[dim * node..dim * (node + 1)]);
    }
    Some(out)
}

/// The rigid-body modes of the elastic rows `u` (this process's, PETSc's numbering) from the
/// nodes' `layout` ([`Distributed::node_layout`]): the dimension and the nodes' coordinates
/// (see [`rigid`]).
fn rigid_modes(layout: Option<&Layout>, rows: &Rows, u: &[usize]) -> Option<(usize, Vec<f64>)> {
    let (dim, coordinates, _) = layout?;
    Some((*dim, rigid(rows, u, *dim, coordinates)?))
}

/// The error of a Krylov solve that stopped short of its tolerance (the solver's own, the
/// options applied).
fn not_converged(krylov: &Krylov, solve: &KrylovSolve) -> Error {
    let [method, preconditioner] = krylov
        .kinds()
        .unwrap_or_else(|_| ["the Krylov method".into(), "its preconditioner".into()]);
    let (rtol, most) = (solve.rtol, solve.most);
    Error::LinearAlgebra(format!(
        "the Krylov solve ({method}, preconditioner {preconditioner}) stopped after {} iterations with PETSc's reason {} and a residual of {:.3e} (relative tolerance {:e}, at most {} iterations): give it more iterations or another tolerance with --petsc-options \"-ksp_max_it N -ksp_rtol R\", another preconditioner (-fieldsplit_u_pc_type, -fieldsplit_phi_pc_type), or use solver.linear = \"direct\"",
        solve.iterations, solve.reason, solve.residual, rtol, most
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three nodes in 2D: node 0 free (u_x, u_y, ϕ), node 1 on a roller (u_y and ϕ), node 2
    /// clamped with ϕ free. The roller's u_x gets a held row between its node's rows, node 2
    /// none (it has no elastic row); the elastic field then comes two rows per node.
    #[test]
    fn a_node_on_a_roller_gets_a_held_row_for_its_constrained_component() {
        let n = 6;
        let positions: Vec<(usize, usize)> =
            (0..n).flat_map(|j| (j..n).map(move |i| (i, j))).collect();
        let pattern = SymmetricPattern::from_positions(n, &positions).unwrap();
        let pattern = pattern.with_groups(vec![0, 0, 1, 2, 0, 1]).unwrap();
        let components = [0, 1, 1, 2, 2, 2];
        let signs = [1, 1, 1, -1, -1, -1];
        let rows = Rows::new(&pattern, None, Some((2, &components))).unwrap();
        assert_eq!((rows.n, rows.total), (6, 7));
        assert_eq!(rows.order, vec![0, 1, 4, HELD, 2, 5, 3]);
        assert_eq!(rows.nodes, vec![0, 0, 0, 1, 1, 1, 2]);
        // The held row an identity row; every other row full: the 6 × 6 pattern's 21 stored
        // entries give 6 a row; all on this process.
        let counts = rows.preallocation(pattern.symbolic(), |_| true, |_| 0);
        assert_eq!(counts.diagonal[0], vec![6, 6, 6, 1, 6, 6, 6]);
        assert_eq!(counts.off, [vec![0; 7], vec![0; 7]]);
        let counts = rows.preallocation(pattern.symbolic(), |i| i == 4, |_| 0);
        assert_eq!(counts.diagonal[0], vec![0, 0, 6, 0, 0, 0, 0], "the rows `only` takes alone");
        // By the columns' field: each full row has 3 u columns and 3 ϕ ones, the held row its
        // diagonal alone.
        let split = rows.split(&signs);
        let counts = rows.preallocation(pattern.symbolic(), |_| true, |p| split.field(p));
        assert_eq!(counts.diagonal, [vec![3, 3, 3, 1, 3, 3, 3], vec![3, 3, 3, 0, 3, 3, 3]]);
        assert_eq!((0..7).map(|p| split.field(p)).collect::<Vec<_>>(), vec![0, 0, 1, 0, 0, 1, 1]);
        let u = rows.field(&signs, 1);
        assert_eq!(u, vec![0, 1, 3, 4]);
        // One point per node of the field: nodes 0 and 1.
        let coordinates = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0];
        assert_eq!(rigid(&rows, &u, 2, &coordinates), Some(vec![0.0, 0.0, 1.0, 0.0]));
        let mut local = vec![f64::NAN; 7];
        rows.scatter(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], &mut local);
        assert_eq!(local, vec![1.0, 2.0, 5.0, 0.0, 3.0, 6.0, 4.0]);
        // The direct route has no held rows, and the rigid modes are refused for the roller.
        let direct = Rows::new(&pattern, None, None).unwrap();
        assert_eq!((direct.total, direct.order.clone()), (6, vec![0, 1, 4, 2, 5, 3]));
        assert_eq!(rigid(&direct, &direct.field(&signs, 1), 2, &coordinates), None);
    }
}

//! The C API of PETSc 3.18 (with MUMPS) and the few MPI calls the backend makes, wrapped in
//! safe types. Every `unsafe` call of the PETSc backend is in this file.
//!
//! The declarations follow the headers of Debian's `libpetsc-real3.18-dev`: `PetscInt` is a
//! 32-bit int, `PetscScalar` a real double, `PetscErrorCode` an int; MPI is Open MPI, whose
//! handles are pointers (`MPI_DOUBLE` is the address of `ompi_mpi_double`). The build script
//! checks the first three in `petscconf.h` and refuses another configuration.
//!
//! Errors: PETSc's error handler is ours, [`return_error`], which returns the error without
//! printing it; each non-zero code becomes [`Error::LinearAlgebra`] with PETSc's own text and
//! message.

#![allow(unsafe_code)]

use crate::error::{Error, Result};
use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::ptr::null_mut;
use std::sync::OnceLock;

/// PETSc's index type (32-bit in the configuration the build script accepts).
pub type PetscInt = i32;
type Code = c_int;
type Handle = *mut c_void;

/// An Open MPI communicator, datatype or operation.
type MpiHandle = *mut c_void;

#[repr(C)]
struct Opaque {
    _private: [u8; 0],
}

type ErrorHandler = unsafe extern "C" fn(
    MpiHandle,
    c_int,
    *const c_char,
    *const c_char,
    Code,
    c_int,
    *const c_char,
    *mut c_void,
) -> Code;

#[link(name = "mpi")]
unsafe extern "C" {
    static ompi_mpi_double: Opaque;
    static ompi_mpi_op_sum: Opaque;
    static ompi_mpi_op_max: Opaque;
    fn MPI_Comm_rank(comm: MpiHandle, rank: *mut c_int) -> c_int;
    fn MPI_Comm_size(comm: MpiHandle, size: *mut c_int) -> c_int;
    fn MPI_Bcast(buf: *mut c_void, n: c_int, ty: MpiHandle, root: c_int, comm: MpiHandle) -> c_int;
    fn MPI_Allreduce(
        send: *const c_void,
        recv: *mut c_void,
        n: c_int,
        ty: MpiHandle,
        op: MpiHandle,
        comm: MpiHandle,
    ) -> c_int;
    fn MPI_Gather(
        send: *const c_void,
        n_send: c_int,
        send_ty: MpiHandle,
        recv: *mut c_void,
        n_recv: c_int,
        recv_ty: MpiHandle,
        root: c_int,
        comm: MpiHandle,
    ) -> c_int;
    fn MPI_Abort(comm: MpiHandle, code: c_int) -> c_int;
}

unsafe extern "C" {
    static PETSC_COMM_WORLD: MpiHandle;
    fn PetscInitializeNoArguments() -> Code;
    fn PetscFinalize() -> Code;
    fn PetscOptionsInsertString(options: Handle, text: *const c_char) -> Code;
    fn PetscLogDefaultBegin() -> Code;
    fn PetscMemorySetGetMaximumUsage() -> Code;
    fn PetscPushErrorHandler(handler: ErrorHandler, ctx: *mut c_void) -> Code;
    fn PetscErrorMessage(code: c_int, text: *mut *const c_char, more: *mut *mut c_char) -> Code;
    fn atexit(f: extern "C" fn()) -> c_int;
}

// Matrices and their factors.
unsafe extern "C" {
    fn MatCreate(comm: MpiHandle, mat: *mut Handle) -> Code;
    fn MatSetSizes(mat: Handle, m: PetscInt, n: PetscInt, big_m: PetscInt, big_n: PetscInt)
    -> Code;
    fn MatSetBlockSize(mat: Handle, bs: PetscInt) -> Code;
    fn MatSetType(mat: Handle, kind: *const c_char) -> Code;
    fn MatSeqAIJSetPreallocation(mat: Handle, nz: PetscInt, nnz: *const PetscInt) -> Code;
    fn MatMPIAIJSetPreallocation(
        mat: Handle,
        d_nz: PetscInt,
        d_nnz: *const PetscInt,
        o_nz: PetscInt,
        o_nnz: *const PetscInt,
    ) -> Code;
    fn MatCreateNest(
        comm: MpiHandle,
        nr: PetscInt,
        is_row: *const Handle,
        nc: PetscInt,
        is_col: *const Handle,
        blocks: *const Handle,
        mat: *mut Handle,
    ) -> Code;
    fn MatNestSetVecType(mat: Handle, kind: *const c_char) -> Code;
    fn MatSetOption(mat: Handle, option: c_int, flag: c_int) -> Code;
    fn MatSetValues(
        mat: Handle,
        m: PetscInt,
        rows: *const PetscInt,
        n: PetscInt,
        cols: *const PetscInt,
        values: *const f64,
        mode: c_int,
    ) -> Code;
    fn MatAssemblyBegin(mat: Handle, kind: c_int) -> Code;
    fn MatAssemblyEnd(mat: Handle, kind: c_int) -> Code;
    fn MatGetRow(
        mat: Handle,
        row: PetscInt,
        n: *mut PetscInt,
        cols: *mut *const PetscInt,
        values: *mut *const f64,
    ) -> Code;
    fn MatRestoreRow(
        mat: Handle,
        row: PetscInt,
        n: *mut PetscInt,
        cols: *mut *const PetscInt,
        values: *mut *const f64,
    ) -> Code;
    fn MatMult(mat: Handle, x: Handle, y: Handle) -> Code;
    fn MatCreateVecs(mat: Handle, right: *mut Handle, left: *mut Handle) -> Code;
    fn MatDestroy(mat: *mut Handle) -> Code;
    fn MatCreateComposite(
        comm: MpiHandle,
        n: PetscInt,
        mats: *const Handle,
        mat: *mut Handle,
    ) -> Code;
    fn MatGetFactor(mat: Handle, kind: *const c_char, ftype: c_int, factor: *mut Handle) -> Code;
    fn MatFactorSetSchurIS(factor: Handle, is: Handle) -> Code;
    fn MatCholeskyFactorSymbolic(
        factor: Handle,
        mat: Handle,
        perm: Handle,
        info: *const c_void,
    ) -> Code;
    fn MatCholeskyFactorNumeric(factor: Handle, mat: Handle, info: *const c_void) -> Code;
    fn MatFactorCreateSchurComplement(factor: Handle, s: *mut Handle, status: *mut c_int) -> Code;
    fn MatGetSize(mat: Handle, m: *mut PetscInt, n: *mut PetscInt) -> Code;
    fn MatDenseGetArrayRead(mat: Handle, values: *mut *const f64) -> Code;
    fn MatDenseRestoreArrayRead(mat: Handle, values: *mut *const f64) -> Code;
    fn MatMumpsSetIcntl(factor: Handle, icntl: PetscInt, value: PetscInt) -> Code;
    fn MatMumpsGetInfog(factor: Handle, icntl: PetscInt, value: *mut PetscInt) -> Code;
    fn MatSolve(factor: Handle, b: Handle, x: Handle) -> Code;
}

// Vectors, their scatters and index sets.
unsafe extern "C" {
    fn VecGetArray(v: Handle, values: *mut *mut f64) -> Code;
    fn VecRestoreArray(v: Handle, values: *mut *mut f64) -> Code;
    fn VecGetLocalSize(v: Handle, n: *mut PetscInt) -> Code;
    fn VecScatterCreateToAll(v: Handle, ctx: *mut Handle, all: *mut Handle) -> Code;
    fn VecScatterBegin(ctx: Handle, x: Handle, y: Handle, mode: c_int, dir: c_int) -> Code;
    fn VecScatterEnd(ctx: Handle, x: Handle, y: Handle, mode: c_int, dir: c_int) -> Code;
    fn VecScatterDestroy(ctx: *mut Handle) -> Code;
    fn VecDestroy(v: *mut Handle) -> Code;
    fn ISCreateGeneral(
        comm: MpiHandle,
        n: PetscInt,
        idx: *const PetscInt,
        mode: c_int,
        is: *mut Handle,
    ) -> Code;
    fn ISDestroy(is: *mut Handle) -> Code;
}

// Krylov solvers, preconditioners and the options database.
unsafe extern "C" {
    fn KSPCreate(comm: MpiHandle, ksp: *mut Handle) -> Code;
    fn KSPSetOperators(ksp: Handle, a: Handle, p: Handle) -> Code;
    fn KSPSetType(ksp: Handle, kind: *const c_char) -> Code;
    fn KSPGetPC(ksp: Handle, pc: *mut Handle) -> Code;
    fn KSPSetPCSide(ksp: Handle, side: c_int) -> Code;
    fn KSPGMRESSetRestart(ksp: Handle, restart: PetscInt) -> Code;
    fn KSPSetTolerances(ksp: Handle, rtol: f64, atol: f64, dtol: f64, its: PetscInt) -> Code;
    fn KSPSetFromOptions(ksp: Handle) -> Code;
    fn KSPSetUp(ksp: Handle) -> Code;
    fn KSPSolve(ksp: Handle, b: Handle, x: Handle) -> Code;
    fn KSPGetIterationNumber(ksp: Handle, its: *mut PetscInt) -> Code;
    fn KSPGetConvergedReason(ksp: Handle, reason: *mut c_int) -> Code;
    fn KSPGetResidualNorm(ksp: Handle, norm: *mut f64) -> Code;
    fn KSPGetType(ksp: Handle, kind: *mut *const c_char) -> Code;
    fn KSPGetTolerances(
        ksp: Handle,
        rtol: *mut f64,
        atol: *mut f64,
        dtol: *mut f64,
        its: *mut PetscInt,
    ) -> Code;
    fn KSPDestroy(ksp: *mut Handle) -> Code;
    fn KSPSetReusePreconditioner(ksp: Handle, reuse: c_int) -> Code;
    fn PCFieldSplitGetSubKSP(pc: Handle, n: *mut PetscInt, sub: *mut *mut Handle) -> Code;
    /// PETSc's free (what its PetscFree macro calls).
    static PetscTrFree:
        unsafe extern "C" fn(*mut c_void, c_int, *const c_char, *const c_char) -> Code;
    fn PCSetType(pc: Handle, kind: *const c_char) -> Code;
    fn VecCreateMPI(comm: MpiHandle, local: PetscInt, n: PetscInt, v: *mut Handle) -> Code;
    fn VecSetBlockSize(v: Handle, bs: PetscInt) -> Code;
    fn ISSetBlockSize(is: Handle, bs: PetscInt) -> Code;
    fn MatNullSpaceCreateRigidBody(coordinates: Handle, space: *mut Handle) -> Code;
    fn MatNullSpaceDestroy(space: *mut Handle) -> Code;
    fn PetscObjectCompose(object: Handle, name: *const c_char, other: Handle) -> Code;
    fn PCGetType(pc: Handle, kind: *mut *const c_char) -> Code;
    fn PCFieldSplitSetIS(pc: Handle, name: *const c_char, is: Handle) -> Code;
    fn PetscOptionsHasName(
        options: Handle,
        prefix: *const c_char,
        name: *const c_char,
        set: *mut c_int,
    ) -> Code;
    fn PetscOptionsSetValue(options: Handle, name: *const c_char, value: *const c_char) -> Code;
    fn PetscOptionsGetString(
        options: Handle,
        prefix: *const c_char,
        name: *const c_char,
        value: *mut c_char,
        len: usize,
        set: *mut c_int,
    ) -> Code;
}

const PETSC_TRUE: c_int = 1;
const INSERT_VALUES: c_int = 1;
const MAT_FINAL_ASSEMBLY: c_int = 0;
const MAT_SYMMETRIC: c_int = 1;
const MAT_NEW_NONZERO_ALLOCATION_ERR: c_int = 19;
const MAT_FACTOR_CHOLESKY: c_int = 2;
const PETSC_COPY_VALUES: c_int = 0;
const SCATTER_FORWARD: c_int = 0;
const PC_RIGHT: c_int = 1;
/// GMRES's restart: 30 (PETSc's default) stagnated on the 3D block without contact.
const GMRES_RESTART: PetscInt = 100;
/// PETSC_DEFAULT as a real argument: keep PETSc's value.
const PETSC_DEFAULT: f64 = -2.0;

/// The library's error for a PETSc error code, with PETSc's text and message.
fn check(code: Code, what: &str) -> Result<()> {
    if code == 0 {
        return Ok(());
    }
    let (mut text, mut specific): (*const c_char, *mut c_char) = (std::ptr::null(), null_mut());
    // SAFETY: PetscErrorMessage writes two pointers to static strings (or null) owned by PETSc.
    unsafe { PetscErrorMessage(code, &mut text, &mut specific) };
    let read = |p: *const c_char| {
        // SAFETY: a non-null pointer from PetscErrorMessage is a NUL-terminated string.
        (!p.is_null()).then(|| unsafe { CStr::from_ptr(p) }.to_string_lossy().trim().to_string())
    };
    let message = [read(text), read(specific)].into_iter().flatten().collect::<Vec<_>>();
    Err(Error::LinearAlgebra(format!("PETSc, {what}: {} (error {code})", message.join(": "))))
}

/// An MPI error code as the library's error.
fn check_mpi(code: c_int, what: &str) -> Result<()> {
    match code {
        0 => Ok(()),
        _ => Err(Error::LinearAlgebra(format!("MPI, {what}: error {code}"))),
    }
}

/// PETSc's initialisation: `Ok` once PETSc runs, or the error that stopped it (kept, so that
/// every later call reports it).
static SESSION: OnceLock<std::result::Result<(), String>> = OnceLock::new();

/// Starts PETSc (and MPI) once per process, with `options` (PETSc's command-line syntax,
/// e.g. "-mat_mumps_icntl_14 50") in its options database; PETSc finalises when the process
/// exits. Later calls return at once; their options are ignored.
pub fn initialize(options: &str) -> Result<()> {
    let result = SESSION.get_or_init(|| start(options).map_err(|e| e.to_string()));
    result.clone().map_err(Error::LinearAlgebra)
}

fn start(options: &str) -> Result<()> {
    let options = CString::new(options)
        .map_err(|_| Error::Input("--petsc-options: a NUL character in the options".into()))?;
    // SAFETY: called once per process (guarded by SESSION), before any other PETSc call.
    check(unsafe { PetscInitializeNoArguments() }, "PetscInitialize")?;
    // SAFETY: PETSc is initialised; the handler is PETSc's own; `finalize` has C linkage.
    unsafe {
        check(PetscPushErrorHandler(return_error, null_mut()), "error handler")?;
        check(PetscOptionsInsertString(null_mut(), options.as_ptr()), "options")?;
        atexit(finalize);
    }
    start_log()
}

/// Starts what PETSc's reports at exit read when the options ask for them (-log_view: the
/// performance log; -memory_view: the tracking of the largest resident set, without which
/// PetscFinalize fails before it finalises MPI): PETSc starts them only for options present
/// at its initialisation, and ours are inserted after.
fn start_log() -> Result<()> {
    if has_option("-log_view")? {
        // SAFETY: PETSc is initialised and no event has been logged yet.
        check(unsafe { PetscLogDefaultBegin() }, "PetscLogDefaultBegin")?;
    }
    if has_option("-memory_view")? {
        // SAFETY: PETSc is initialised.
        check(unsafe { PetscMemorySetGetMaximumUsage() }, "PetscMemorySetGetMaximumUsage")?;
    }
    Ok(())
}

/// PETSc's error handler: returns the error code to the caller, which reads PETSc's message
/// with `PetscErrorMessage` ([`check`]), instead of printing a traceback.
unsafe extern "C" fn return_error(
    _comm: MpiHandle,
    _line: c_int,
    _func: *const c_char,
    _file: *const c_char,
    code: Code,
    _kind: c_int,
    _message: *const c_char,
    _ctx: *mut c_void,
) -> Code {
    code
}

extern "C" fn finalize() {
    // SAFETY: registered by `start` after a successful initialisation, run once at exit.
    unsafe { PetscFinalize() };
}

/// PETSC_COMM_WORLD; PETSc must be initialised.
fn world() -> MpiHandle {
    // SAFETY: a global of PETSc, set by PetscInitialize and constant afterwards.
    unsafe { PETSC_COMM_WORLD }
}

/// Whether PETSc has been started in this process.
fn is_initialized() -> bool {
    matches!(SESSION.get(), Some(Ok(())))
}

/// This process's rank and the number of processes (0 and 1 before PETSc is started).
pub fn rank_and_size() -> (usize, usize) {
    if !is_initialized() {
        return (0, 1);
    }
    let (mut rank, mut size) = (0, 1);
    // SAFETY: PETSc (hence MPI) is initialised; the outputs are plain ints.
    unsafe {
        MPI_Comm_rank(world(), &mut rank);
        MPI_Comm_size(world(), &mut size);
    }
    (rank as usize, size as usize)
}

/// Broadcasts `values` from rank 0 to every process (the same length everywhere).
pub fn broadcast(values: &mut [f64]) -> Result<()> {
    let n = c_int::try_from(values.len())
        .map_err(|_| Error::LinearAlgebra("a broadcast of more than 2³¹ values".into()))?;
    // SAFETY: `values` is a valid buffer of n doubles on every process.
    let code = unsafe {
        MPI_Bcast(values.as_mut_ptr().cast(), n, (&raw const ompi_mpi_double) as _, 0, world())
    };
    check_mpi(code, "broadcast")
}

/// The sum of `value` over the processes.
pub fn sum_over_processes(value: f64) -> Result<f64> {
    let mut out = [value];
    sum_each_over_processes(&mut out)?;
    Ok(out[0])
}

/// Each entry of `values` (the same length everywhere) summed over the processes, in place.
pub fn sum_each_over_processes(values: &mut [f64]) -> Result<()> {
    reduce_each((&raw const ompi_mpi_op_sum) as MpiHandle, values)
}

/// The largest `value` over the processes.
pub fn max_over_processes(value: f64) -> Result<f64> {
    let mut out = [value];
    reduce_each((&raw const ompi_mpi_op_max) as MpiHandle, &mut out)?;
    Ok(out[0])
}

/// Each entry of `values` (the same length everywhere) reduced over the processes by the
/// operation `op`, in place.
fn reduce_each(op: MpiHandle, values: &mut [f64]) -> Result<()> {
    let n = c_int::try_from(values.len())
        .map_err(|_| Error::LinearAlgebra("a reduction of more than 2³¹ values".into()))?;
    let send = values.to_vec();
    // SAFETY: n doubles in and out on every process, in distinct buffers.
    let code = unsafe {
        MPI_Allreduce(
            send.as_ptr().cast(),
            values.as_mut_ptr().cast(),
            n,
            (&raw const ompi_mpi_double) as _,
            op,
            world(),
        )
    };
    check_mpi(code, "reduction")
}

/// `value` of every process, on rank 0 (empty on the others).
pub fn gather(value: f64) -> Result<Vec<f64>> {
    let (rank, size) = rank_and_size();
    let mut all = vec![0.0; if rank == 0 { size } else { 0 }];
    let ty = (&raw const ompi_mpi_double) as MpiHandle;
    // SAFETY: one double sent by each process, `size` received on rank 0 only.
    let code = unsafe {
        MPI_Gather((&raw const value).cast(), 1, ty, all.as_mut_ptr().cast(), 1, ty, 0, world())
    };
    check_mpi(code, "gather").map(|_| all)
}

/// Returns the heap's free pages to the system (glibc's `malloc_trim`; nothing elsewhere), so
/// that memory freed since — a Newton step's patches and vectors, an earlier setup's — does
/// not stay in the resident set while the next Krylov solve sets up its preconditioner: on
/// two processes at 1.37M unknowns the larger one's peak fell from 2,992–3,082 MB (four runs)
/// to 2,971–2,979 (three), in the same time; the one process's stayed at 3,314 MB.
pub fn return_free_memory() {
    #[cfg(target_env = "gnu")]
    {
        unsafe extern "C" {
            fn malloc_trim(pad: usize) -> c_int;
        }
        // SAFETY: glibc's malloc_trim only releases free memory of its own arenas.
        unsafe { malloc_trim(0) };
    }
}

/// Ends every process of the run with `code` (after an error on this one).
pub fn abort(code: i32) -> ! {
    // SAFETY: MPI is initialised; MPI_Abort does not return.
    unsafe { MPI_Abort(world(), code) };
    std::process::exit(code)
}

/// A distributed sparse matrix (MPIAIJ, or SeqAIJ on one process).
#[derive(Debug)]
pub struct Matrix(Handle);

// SAFETY: PETSc objects are used by one thread at a time (the backend is behind `&mut`).
unsafe impl Send for Matrix {}

impl Matrix {
    /// An n × n AIJ matrix whose `local` rows are this process's, preallocated with
    /// `diagonal[k]` entries of owned row k in the owned columns and `off[k]` outside.
    pub fn new(local: usize, n: usize, diagonal: &[PetscInt], off: &[PetscInt]) -> Result<Self> {
        Self::rectangular([(local, n), (local, n)], (diagonal, off), 1)
    }

    /// An AIJ matrix of `sizes` = [(local, global) rows, (local, global) columns], this
    /// process's rows and columns `local` of them, preallocated as [`Matrix::new`], with the
    /// block size `block` (rows and columns; the local sizes its multiples).
    pub fn rectangular(
        sizes: [(usize, usize); 2],
        (diagonal, off): (&[PetscInt], &[PetscInt]),
        block: usize,
    ) -> Result<Self> {
        let [(m, big_m), (n, big_n)] = sizes;
        let [m, big_m, n, big_n, block] = [m, big_m, n, big_n, block].map(index);
        let (m, big_m, n, big_n, block) = (m?, big_m?, n?, big_n?, block?);
        let mut mat = null_mut();
        // SAFETY: the preallocation arrays have one entry per local row; each call applies to
        // the matrix just made (the preallocation of the other type is a no-op).
        unsafe {
            check(MatCreate(world(), &mut mat), "MatCreate")?;
            let this = Self(mat);
            check(MatSetSizes(mat, m, n, big_m, big_n), "MatSetSizes")?;
            check(MatSetBlockSize(mat, block), "MatSetBlockSize")?;
            check(MatSetType(mat, c"aij".as_ptr()), "MatSetType")?;
            let code = MatSeqAIJSetPreallocation(mat, 0, diagonal.as_ptr());
            check(code, "MatSeqAIJSetPreallocation")?;
            let code = MatMPIAIJSetPreallocation(mat, 0, diagonal.as_ptr(), 0, off.as_ptr());
            check(code, "MatMPIAIJSetPreallocation")?;
            check(MatSetOption(mat, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption")?;
            Ok(this)
        }
    }

    /// PETSc's MATNEST of the four blocks `blocks[f][g]` (rows of field f, columns of field
    /// g), field f's rows being this process's rows `fields[f]` of the whole matrix; it keeps
    /// its own references to the blocks, which stay writable through theirs. Its vectors are
    /// standard ones (not nested), as every vector of the backend is.
    pub fn nest(fields: [&[PetscInt]; 2], blocks: [[&Matrix; 2]; 2]) -> Result<Self> {
        let mut sets = [null_mut(); 2];
        let mut made = Ok(());
        for (set, rows) in sets.iter_mut().zip(fields) {
            let n = index(rows.len())?;
            // SAFETY: `rows` has n entries, copied.
            let code =
                unsafe { ISCreateGeneral(world(), n, rows.as_ptr(), PETSC_COPY_VALUES, set) };
            made = made.and(check(code, "ISCreateGeneral"));
        }
        let handles = blocks.map(|row| row.map(|b| b.0));
        let mut mat = null_mut();
        // SAFETY: two index sets, a 2 × 2 row-major array of assembled-or-preallocated blocks
        // of their sizes; the nest references the sets and blocks, so ours are released.
        unsafe {
            if made.is_ok() {
                let code = MatCreateNest(
                    world(),
                    2,
                    sets.as_ptr(),
                    2,
                    sets.as_ptr(),
                    handles.as_ptr().cast(),
                    &mut mat,
                );
                made = check(code, "MatCreateNest");
            }
            sets.iter_mut().filter(|s| !s.is_null()).for_each(|s| {
                ISDestroy(s);
            });
            made?;
            let this = Self(mat);
            check(MatNestSetVecType(mat, c"standard".as_ptr()), "MatNestSetVecType")?;
            Ok(this)
        }
    }

    /// Puts `values` at (row, cols) of an owned row.
    pub fn set_row(&mut self, row: PetscInt, cols: &[PetscInt], values: &[f64]) -> Result<()> {
        assert_eq!(cols.len(), values.len());
        let n = cols.len() as PetscInt;
        // SAFETY: `cols` and `values` have n entries.
        let code = unsafe {
            MatSetValues(self.0, 1, &row, n, cols.as_ptr(), values.as_ptr(), INSERT_VALUES)
        };
        check(code, "MatSetValues")
    }

    /// Puts `values` at (rows, col) of owned rows: a column's entries in those rows.
    pub fn set_column(&mut self, rows: &[PetscInt], col: PetscInt, values: &[f64]) -> Result<()> {
        assert_eq!(rows.len(), values.len());
        let m = rows.len() as PetscInt;
        // SAFETY: `rows` and `values` have m entries (an m × 1 block, row by row).
        let code = unsafe {
            MatSetValues(self.0, m, rows.as_ptr(), 1, &col, values.as_ptr(), INSERT_VALUES)
        };
        check(code, "MatSetValues")
    }

    /// Final assembly after the values are set; marks the matrix symmetric if it is.
    pub fn assemble(&mut self, symmetric: bool) -> Result<()> {
        // SAFETY: a valid matrix; collective on every process.
        unsafe {
            check(MatAssemblyBegin(self.0, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin")?;
            check(MatAssemblyEnd(self.0, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd")?;
            check(MatSetOption(self.0, MAT_SYMMETRIC, c_int::from(symmetric)), "MatSetOption")
        }
    }

    /// The stored (column, value) pairs of an owned row.
    pub fn row(&self, row: PetscInt) -> Result<Vec<(usize, f64)>> {
        let (mut n, mut cols, mut values) = (0, std::ptr::null(), std::ptr::null());
        // SAFETY: MatGetRow gives n columns and values valid until MatRestoreRow.
        unsafe {
            check(MatGetRow(self.0, row, &mut n, &mut cols, &mut values), "MatGetRow")?;
            let out = (0..n as usize).map(|k| (*cols.add(k) as usize, *values.add(k))).collect();
            check(MatRestoreRow(self.0, row, &mut n, &mut cols, &mut values), "MatRestoreRow")?;
            Ok(out)
        }
    }

    /// y = A x.
    pub fn mult(&self, x: &Vector, y: &mut Vector) -> Result<()> {
        // SAFETY: vectors made by `vectors` of this matrix.
        check(unsafe { MatMult(self.0, x.0, y.0) }, "MatMult")
    }

    /// The sum of `parts` (of one layout) as an operator: PETSc's composite matrix, which
    /// multiplies by each and adds, and holds its own references to them.
    pub fn sum(parts: &[&Matrix]) -> Result<Self> {
        let handles: Vec<Handle> = parts.iter().map(|m| m.0).collect();
        let (n, mut mat) = (index(handles.len())?, null_mut());
        // SAFETY: valid assembled matrices of one layout; collective.
        let code = unsafe { MatCreateComposite(world(), n, handles.as_ptr(), &mut mat) };
        check(code, "MatCreateComposite")?;
        Ok(Self(mat))
    }

    /// A distributed vector with this matrix's row layout.
    pub fn vector(&self) -> Result<Vector> {
        let mut v = null_mut();
        // SAFETY: a valid assembled matrix.
        check(unsafe { MatCreateVecs(self.0, &mut v, null_mut()) }, "MatCreateVecs")?;
        Ok(Vector(v))
    }
}

impl Drop for Matrix {
    fn drop(&mut self) {
        // SAFETY: the handle was made by PETSc and is destroyed once.
        unsafe { MatDestroy(&mut self.0) };
    }
}

/// A MUMPS LDLᵀ factorisation (`sym = 2`) of a [`Matrix`], with an optional Schur set.
#[derive(Debug)]
pub struct Factor(Handle);

// SAFETY: as for Matrix.
unsafe impl Send for Factor {}

impl Factor {
    /// MUMPS's symbolic analysis of `matrix`, with a Schur set when `schur` is given (on
    /// every process: PETSc's calls are collective): its unknowns on rank 0, an empty slice
    /// on the others.
    pub fn analyse(matrix: &Matrix, schur: Option<&[PetscInt]>) -> Result<Self> {
        let mut factor = null_mut();
        // SAFETY: a valid assembled matrix; the IS copies the indices.
        unsafe {
            let mumps = c"mumps";
            check(
                MatGetFactor(matrix.0, mumps.as_ptr(), MAT_FACTOR_CHOLESKY, &mut factor),
                "MatGetFactor (is PETSc built with MUMPS?)",
            )?;
            let this = Self(factor);
            if let Some(schur) = schur {
                let mut is = null_mut();
                let n = schur.len() as PetscInt;
                let code = ISCreateGeneral(world(), n, schur.as_ptr(), PETSC_COPY_VALUES, &mut is);
                check(code, "ISCreateGeneral")?;
                let code = MatFactorSetSchurIS(factor, is);
                ISDestroy(&mut is);
                check(code, "MatFactorSetSchurIS")?;
            }
            let code = MatCholeskyFactorSymbolic(factor, matrix.0, null_mut(), std::ptr::null());
            check(code, "MUMPS analysis")?;
            this.check_mumps("analysis")?;
            Ok(this)
        }
    }

    /// Numeric factorisation of `matrix` (the analysed pattern, new values). With a Schur
    /// set, solves are then of the interior rows (ICNTL(26) = 0, which PETSc's analysis and
    /// factorisation reset); on several processes S is asked for centralised on process 0
    /// at every factorisation (ICNTL(19) = 1): PETSc asks for it so at the analysis, but
    /// after each factorisation turns its copy to columns and sets ICNTL(19) = 2, which MUMPS
    /// reads at the next one as another layout — S came back with its off-diagonal entries
    /// zero (PETSc 3.18, MUMPS 5.5.1).
    pub fn factorize(&mut self, matrix: &Matrix, schur: bool) -> Result<()> {
        // SAFETY: a factor analysed with this matrix's pattern.
        unsafe {
            if schur && rank_and_size().1 > 1 {
                check(MatMumpsSetIcntl(self.0, 19, 1), "MatMumpsSetIcntl")?;
            }
            check(
                MatCholeskyFactorNumeric(self.0, matrix.0, std::ptr::null()),
                "MUMPS factorisation",
            )?;
            self.check_mumps("factorisation")?;
            if schur {
                check(MatMumpsSetIcntl(self.0, 26, 0), "MatMumpsSetIcntl")?;
            }
        }
        Ok(())
    }

    /// MUMPS's own error after a phase: PETSc records it in the factor without returning an
    /// error code, so INFOG(1) < 0 is read here (the same on every process).
    fn check_mumps(&self, phase: &str) -> Result<()> {
        let (code, detail) = (self.infog(1)?, self.infog(2)?);
        if code >= 0 {
            return Ok(());
        }
        let why = match code {
            -8 | -9 | -11 | -14 | -15 | -17 | -20 => {
                "its working memory is too small: raise it with --petsc-options \"-mat_mumps_icntl_14 60\" (percent of the analysis's estimate; default 20)"
            }
            -10 => {
                "the matrix is numerically singular: check that the body is clamped (Γ1) and grounded (Γa)"
            }
            -13 => {
                "an allocation failed: the factor does not fit in memory; use more processes or a coarser mesh"
            }
            -19 => "the memory cap -mat_mumps_icntl_23 is too small for the factor",
            -38 => {
                "its parallel analysis (-mat_mumps_icntl_28 2) needs PT-Scotch or ParMETIS, which this MUMPS lacks: leave -mat_mumps_icntl_28 out"
            }
            -39 => {
                "its options do not go together (MUMPS does not combine the parallel analysis, -mat_mumps_icntl_28 2, with the Schur set of the exact solver): leave -mat_mumps_icntl_28 out"
            }
            _ => "see MUMPS's manual, section \"Error diagnostics\"",
        };
        let message =
            format!("MUMPS {phase} failed with INFOG(1) = {code}, INFOG(2) = {detail}: {why}");
        Err(if code == -10 {
            Error::SingularSystem { detail: message }
        } else {
            Error::LinearAlgebra(message)
        })
    }

    /// MUMPS's INFOG(k) (global information, the same on every process).
    pub fn infog(&self, k: PetscInt) -> Result<PetscInt> {
        let mut value = 0;
        // SAFETY: a valid MUMPS factor.
        check(unsafe { MatMumpsGetInfog(self.0, k, &mut value) }, "MatMumpsGetInfog")?;
        Ok(value)
    }

    /// The dense Schur complement (column-major, m × m) on rank 0; empty elsewhere.
    pub fn schur_complement(&self) -> Result<Vec<f64>> {
        let (mut s, mut status) = (null_mut(), 0);
        // SAFETY: a factor with a Schur set, numerically factorised; S is a copy we destroy.
        unsafe {
            check(MatFactorCreateSchurComplement(self.0, &mut s, &mut status), "Schur complement")?;
            let s = Matrix(s);
            if rank_and_size().0 != 0 {
                return Ok(Vec::new());
            }
            let (mut m, mut n) = (0, 0);
            check(MatGetSize(s.0, &mut m, &mut n), "MatGetSize")?;
            let mut values = std::ptr::null();
            check(MatDenseGetArrayRead(s.0, &mut values), "MatDenseGetArrayRead")?;
            let out = std::slice::from_raw_parts(values, (m * n) as usize).to_vec();
            check(MatDenseRestoreArrayRead(s.0, &mut values), "MatDenseRestoreArrayRead")?;
            Ok(out)
        }
    }

    /// x = A⁻¹ b (with a Schur set: the interior rows, the Schur unknowns at zero).
    pub fn solve(&self, b: &Vector, x: &mut Vector) -> Result<()> {
        // SAFETY: vectors of the factorised matrix's layout.
        check(unsafe { MatSolve(self.0, b.0, x.0) }, "MUMPS solve")
    }
}

impl Drop for Factor {
    fn drop(&mut self) {
        // SAFETY: made by MatGetFactor, destroyed once.
        unsafe { MatDestroy(&mut self.0) };
    }
}

/// What one Krylov solve did.
#[derive(Clone, Copy, Debug)]
pub struct KrylovSolve {
    /// The iterations it took.
    pub iterations: usize,
    /// PETSc's KSPConvergedReason: positive when it converged, negative when it stopped
    /// without.
    pub reason: i32,
    /// The norm of the residual at the end, as the method measures it.
    pub residual: f64,
    /// The relative tolerance it was asked for.
    pub rtol: f64,
    /// The most iterations it was allowed.
    pub most: usize,
}

/// One field of a field split: its name, this process's rows of it (PETSc's numbering) and,
/// for an elastic field whose rows come `dim` per node, the nodes' coordinates (`dim` per
/// node, in the rows' order) for its rigid-body modes.
#[derive(Debug)]
pub struct Field {
    pub name: &'static CStr,
    pub rows: Vec<PetscInt>,
    pub rigid: Option<(usize, Vec<f64>)>,
}

/// Composes the rigid-body modes of the nodes at `coordinates` onto the index set `is` as its
/// near null space ("nearnullspace", which the field split hands to the field's multigrid),
/// with the block size `dim`.
///
/// # Safety
/// `is` is a valid index set of `coordinates.len()` local rows.
unsafe fn near_null_space(is: Handle, dim: usize, coordinates: &[f64]) -> Result<()> {
    let (bs, n) = (index(dim)?, index(coordinates.len())?);
    let (mut v, mut space) = (null_mut(), null_mut());
    // SAFETY: the vector has the local size of `coordinates`; the space keeps its own
    // reference to the vector and the index set to the space.
    unsafe {
        check(ISSetBlockSize(is, bs), "ISSetBlockSize")?;
        check(VecCreateMPI(world(), n, -1, &mut v), "VecCreateMPI")?;
        let mut v = Vector(v);
        check(VecSetBlockSize(v.0, bs), "VecSetBlockSize")?;
        v.with_local(|local| local.copy_from_slice(coordinates))?;
        check(MatNullSpaceCreateRigidBody(v.0, &mut space), "MatNullSpaceCreateRigidBody")?;
        let code = PetscObjectCompose(is, c"nearnullspace".as_ptr(), space);
        MatNullSpaceDestroy(&mut space);
        check(code, "PetscObjectCompose")
    }
}

/// A Krylov solver of a [`Matrix`] (PETSc's KSP) with a field-split preconditioner over the
/// named fields.
#[derive(Debug)]
pub struct Krylov {
    ksp: Handle,
    /// The fields' names.
    fields: Vec<&'static CStr>,
    /// Whether the solves keep the preconditioner of the last setup
    /// ([`Krylov::reuse_preconditioner`]).
    reusing: bool,
}

// SAFETY: as for Matrix.
unsafe impl Send for Krylov {}

impl Krylov {
    /// GMRES(100), preconditioned on the right (so that it measures the true residual), to the
    /// relative tolerance `rtol` in at most `max_iterations`, preconditioned by PCFIELDSPLIT
    /// over `fields` (each a name and this process's rows of it, in PETSc's numbering) with
    /// algebraic multigrid (GAMG) on each field, whose Galerkin products on more than one
    /// process free their intermediate structures once made (`-mat_product_clear`: there
    /// they outweigh the products and stand at the peak; a later setup makes them again).
    /// Every choice is a default that the options database overrides: -ksp_type, -ksp_rtol,
    /// -pc_type, -pc_fieldsplit_type, -fieldsplit_NAME_pc_type, -mat_product_clear, ...
    pub fn new(
        matrix: &Matrix,
        fields: &[Field],
        rtol: f64,
        max_iterations: usize,
    ) -> Result<Self> {
        for field in fields {
            let name = field.name.to_string_lossy();
            default_option(&format!("-fieldsplit_{name}_pc_type"), "gamg")?;
        }
        if rank_and_size().1 > 1 {
            default_option("-mat_product_clear", "true")?;
        }
        let max_iterations = index(max_iterations)?;
        let mut ksp = null_mut();
        // SAFETY: a valid assembled matrix; the index sets copy their indices, and the
        // field split keeps its own reference to each.
        unsafe {
            check(KSPCreate(world(), &mut ksp), "KSPCreate")?;
            let this =
                Self { ksp, fields: fields.iter().map(|f| f.name).collect(), reusing: false };
            check(KSPSetOperators(ksp, matrix.0, matrix.0), "KSPSetOperators")?;
            check(KSPSetType(ksp, c"gmres".as_ptr()), "KSPSetType")?;
            check(KSPSetPCSide(ksp, PC_RIGHT), "KSPSetPCSide")?;
            check(KSPGMRESSetRestart(ksp, GMRES_RESTART), "KSPGMRESSetRestart")?;
            let code = KSPSetTolerances(ksp, rtol, PETSC_DEFAULT, PETSC_DEFAULT, max_iterations);
            check(code, "KSPSetTolerances")?;
            let mut pc = null_mut();
            check(KSPGetPC(ksp, &mut pc), "KSPGetPC")?;
            check(PCSetType(pc, c"fieldsplit".as_ptr()), "PCSetType")?;
            for field in fields {
                let (mut is, n) = (null_mut(), index(field.rows.len())?);
                let rows = field.rows.as_ptr();
                check(ISCreateGeneral(world(), n, rows, PETSC_COPY_VALUES, &mut is), "IS")?;
                let code = match &field.rigid {
                    Some((dim, coordinates)) => near_null_space(is, *dim, coordinates),
                    None => Ok(()),
                }
                .and_then(|()| check(PCFieldSplitSetIS(pc, field.name.as_ptr(), is), "split"));
                ISDestroy(&mut is);
                code?;
            }
            check(KSPSetFromOptions(ksp), "KSPSetFromOptions")?;
            Ok(this)
        }
    }

    /// Sets the preconditioner up for the matrix's current values (GAMG's hierarchy).
    pub fn set_up(&mut self, matrix: &Matrix) -> Result<()> {
        self.reuse_preconditioner(false)?;
        // SAFETY: the matrix this solver was made with, refilled; collective.
        unsafe {
            check(KSPSetOperators(self.ksp, matrix.0, matrix.0), "KSPSetOperators")?;
            check(KSPSetUp(self.ksp), "KSPSetUp (the preconditioner's setup)")
        }
    }

    /// Whether the next solves keep the preconditioner of the last setup though the matrix's
    /// values change (`KSPSetReusePreconditioner`), or set it up again for them as by default:
    /// a field split's sub-solvers too, whose operators — the blocks of the matrix — change
    /// with it. Keeping it needs a setup made (a solve or [`Krylov::set_up`]).
    pub fn reuse_preconditioner(&mut self, keep: bool) -> Result<()> {
        if keep == self.reusing {
            return Ok(());
        }
        let (mut pc, mut kind) = (null_mut(), std::ptr::null());
        // SAFETY: a valid solver, set up when `keep` is first asked (the field split's
        // sub-solvers exist then); PETSc allocates the array of sub-solvers, freed here.
        unsafe {
            check(KSPSetReusePreconditioner(self.ksp, c_int::from(keep)), "reuse")?;
            check(KSPGetPC(self.ksp, &mut pc), "KSPGetPC")?;
            check(PCGetType(pc, &mut kind), "PCGetType")?;
            if CStr::from_ptr(kind) == c"fieldsplit" {
                let (mut n, mut sub) = (0, null_mut());
                check(PCFieldSplitGetSubKSP(pc, &mut n, &mut sub), "PCFieldSplitGetSubKSP")?;
                let set = (0..n.max(0) as usize).try_for_each(|k| {
                    check(KSPSetReusePreconditioner(*sub.add(k), c_int::from(keep)), "reuse")
                });
                PetscTrFree(sub.cast(), line!() as c_int, c"reuse".as_ptr(), c"ffi.rs".as_ptr());
                set?;
            }
        }
        self.reusing = keep;
        Ok(())
    }

    /// x = A⁻¹ b to the tolerance, from x = 0; what the solve did, converged or not.
    pub fn solve(&self, b: &Vector, x: &mut Vector) -> Result<KrylovSolve> {
        let (mut iterations, mut reason, mut residual) = (0, 0, 0.0);
        // SAFETY: vectors of the matrix's layout; the outputs are plain numbers.
        unsafe {
            check(KSPSolve(self.ksp, b.0, x.0), "KSPSolve")?;
            check(KSPGetIterationNumber(self.ksp, &mut iterations), "KSPGetIterationNumber")?;
            check(KSPGetConvergedReason(self.ksp, &mut reason), "KSPGetConvergedReason")?;
            check(KSPGetResidualNorm(self.ksp, &mut residual), "KSPGetResidualNorm")?;
        }
        let (rtol, most) = self.tolerances()?;
        Ok(KrylovSolve { iterations: iterations.max(0) as usize, reason, residual, rtol, most })
    }

    /// x = A⁻¹ b from x = 0 with A = `operator` (of the layout of the solver's own matrix
    /// `own`), preconditioned as for `own`'s current values, to the relative residual `rtol`
    /// in at most `most` iterations (`None`: the solver's own); the solver's operators and
    /// tolerances are its own again afterwards.
    pub fn solve_operator(
        &self,
        (operator, own): (&Matrix, &Matrix),
        (rtol, most): (f64, Option<usize>),
        b: &Vector,
        x: &mut Vector,
    ) -> Result<KrylovSolve> {
        let (own_rtol, own_most) = self.tolerances()?;
        let set = |a: &Matrix, p: &Matrix, rtol: f64, most: usize| {
            let most = index(most)?;
            // SAFETY: valid matrices of the solver's layout.
            unsafe {
                check(KSPSetOperators(self.ksp, a.0, p.0), "KSPSetOperators")?;
                let code = KSPSetTolerances(self.ksp, rtol, PETSC_DEFAULT, PETSC_DEFAULT, most);
                check(code, "KSPSetTolerances")
            }
        };
        set(operator, own, rtol, most.unwrap_or(own_most))?;
        let solve = self.solve(b, x);
        set(own, own, own_rtol, own_most)?;
        solve
    }

    /// The relative tolerance and the most iterations of a solve, as the options left them.
    pub fn tolerances(&self) -> Result<(f64, usize)> {
        let (mut rtol, mut atol, mut dtol, mut its) = (0.0, 0.0, 0.0, 0);
        // SAFETY: a valid solver; the outputs are plain numbers.
        let code = unsafe { KSPGetTolerances(self.ksp, &mut rtol, &mut atol, &mut dtol, &mut its) };
        check(code, "KSPGetTolerances")?;
        Ok((rtol, its.max(0) as usize))
    }

    /// The Krylov method's and the preconditioner's names, as the options left them; a field
    /// split's with each field's preconditioner ("fieldsplit (u: gamg, phi: gamg)").
    pub fn kinds(&self) -> Result<[String; 2]> {
        let (mut krylov, mut pc, mut preconditioner) =
            (std::ptr::null(), null_mut(), std::ptr::null());
        // SAFETY: the names are static strings owned by PETSc.
        let [krylov, preconditioner] = unsafe {
            check(KSPGetType(self.ksp, &mut krylov), "KSPGetType")?;
            check(KSPGetPC(self.ksp, &mut pc), "KSPGetPC")?;
            check(PCGetType(pc, &mut preconditioner), "PCGetType")?;
            [krylov, preconditioner].map(|p| CStr::from_ptr(p).to_string_lossy().into_owned())
        };
        if preconditioner != "fieldsplit" {
            return Ok([krylov, preconditioner]);
        }
        let split = self.fields.iter().map(|name| {
            let name = name.to_string_lossy();
            let kind = option(&format!("-fieldsplit_{name}_pc_type"))?;
            Ok(format!("{name}: {}", kind.as_deref().unwrap_or("PETSc's default")))
        });
        let split = split.collect::<Result<Vec<_>>>()?.join(", ");
        Ok([krylov, format!("{preconditioner} ({split})")])
    }
}

impl Drop for Krylov {
    fn drop(&mut self) {
        // SAFETY: made by KSPCreate, destroyed once.
        unsafe { KSPDestroy(&mut self.ksp) };
    }
}

/// Puts `name value` into PETSc's options database unless the run's options set `name`.
fn default_option(name: &str, value: &str) -> Result<()> {
    if has_option(name)? {
        return Ok(());
    }
    let (name, value) = (CString::new(name), CString::new(value));
    let (Ok(name), Ok(value)) = (name, value) else {
        return Err(Error::LinearAlgebra("a PETSc option with a NUL character".into()));
    };
    // SAFETY: NUL-terminated strings; the global options database.
    check(unsafe { PetscOptionsSetValue(null_mut(), name.as_ptr(), value.as_ptr()) }, "options")
}

/// Whether `name` is in PETSc's options database.
fn has_option(name: &str) -> Result<bool> {
    let name = CString::new(name)
        .map_err(|_| Error::LinearAlgebra("a PETSc option with a NUL character".into()))?;
    let mut set = 0;
    // SAFETY: a NUL-terminated name; the global options database.
    let code =
        unsafe { PetscOptionsHasName(null_mut(), std::ptr::null(), name.as_ptr(), &mut set) };
    check(code, "options")?;
    Ok(set != 0)
}

/// The value of `name` in PETSc's options database (`None` where it is not set).
pub fn option(name: &str) -> Result<Option<String>> {
    let name = CString::new(name)
        .map_err(|_| Error::LinearAlgebra("a PETSc option with a NUL character".into()))?;
    let (mut value, mut set) = ([0 as c_char; 256], 0);
    // SAFETY: a NUL-terminated name; PETSc writes at most `value.len()` bytes, NUL-terminated.
    unsafe {
        let code = PetscOptionsGetString(
            null_mut(),
            std::ptr::null(),
            name.as_ptr(),
            value.as_mut_ptr(),
            value.len(),
            &mut set,
        );
        check(code, "PetscOptionsGetString")?;
        Ok((set != 0).then(|| CStr::from_ptr(value.as_ptr()).to_string_lossy().into_owned()))
    }
}

/// A distributed vector.
#[derive(Debug)]
pub struct Vector(Handle);

// SAFETY: as for Matrix.
unsafe impl Send for Vector {}

impl Vector {
    /// Runs `f` on this process's entries.
    pub fn with_local<T>(&mut self, f: impl FnOnce(&mut [f64]) -> T) -> Result<T> {
        let (mut n, mut values) = (0, null_mut());
        // SAFETY: the array has the local size and is valid until VecRestoreArray.
        unsafe {
            check(VecGetLocalSize(self.0, &mut n), "VecGetLocalSize")?;
            check(VecGetArray(self.0, &mut values), "VecGetArray")?;
            let out = f(std::slice::from_raw_parts_mut(values, n as usize));
            check(VecRestoreArray(self.0, &mut values), "VecRestoreArray")?;
            Ok(out)
        }
    }
}

impl Drop for Vector {
    fn drop(&mut self) {
        // SAFETY: made by PETSc, destroyed once.
        unsafe { VecDestroy(&mut self.0) };
    }
}

/// Gathers a distributed vector whole onto every process.
#[derive(Debug)]
pub struct Gather {
    context: Handle,
    all: Vector,
}

// SAFETY: as for Matrix.
unsafe impl Send for Gather {}

impl Gather {
    /// The gather of vectors laid out as `like`.
    pub fn new(like: &Vector) -> Result<Self> {
        let (mut context, mut all) = (null_mut(), null_mut());
        // SAFETY: a valid vector; PETSc makes the scatter and the sequential vector.
        let code = unsafe { VecScatterCreateToAll(like.0, &mut context, &mut all) };
        check(code, "VecScatterCreateToAll")?;
        Ok(Self { context, all: Vector(all) })
    }

    /// `read` of the whole of `v` on every process.
    pub fn run(&mut self, v: &Vector, read: impl FnOnce(&[f64])) -> Result<()> {
        // SAFETY: `v` has the layout the scatter was made for.
        unsafe {
            let (x, y) = (v.0, self.all.0);
            check(VecScatterBegin(self.context, x, y, INSERT_VALUES, SCATTER_FORWARD), "scatter")?;
            check(VecScatterEnd(self.context, x, y, INSERT_VALUES, SCATTER_FORWARD), "scatter")?;
        }
        self.all.with_local(|all| read(all))
    }
}

impl Drop for Gather {
    fn drop(&mut self) {
        // SAFETY: made by VecScatterCreateToAll, destroyed once.
        unsafe { VecScatterDestroy(&mut self.context) };
    }
}

/// `n` as a PETSc index, or the error that PETSc's 32-bit indices cannot hold it.
pub fn index(n: usize) -> Result<PetscInt> {
    PetscInt::try_from(n).map_err(|_| {
        Error::Input(format!(
            "{n} unknowns are more than PETSc's 32-bit indices hold (2³¹ − 1); use a PETSc built with --with-64-bit-indices"
        ))
    })
}

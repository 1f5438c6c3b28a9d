//! The coupled electro-elastic system without contact: assemble B̌(x_n) and f̌ (SPEC §5),
//! factor once, solve. [`CoupledSystem`] keeps the pattern, the symbolic analysis and the
//! current factorisation so that the contact algorithms reuse them (SPEC §7).

use crate::assembly::{Assembler, NodalBlock, secant_moduli};
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::linalg::{LdltSolver, SymmetricMatrix};
use crate::material::Material;
use crate::problem::Problem;
use std::time::Instant;

/// Wall-clock seconds spent in each phase.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timings {
    /// Pattern construction, element matrices, loads [s].
    pub assembly: f64,
    /// Symbolic analysis (ordering, elimination tree) [s].
    pub symbolic: f64,
    /// All numeric factorisations [s].
    pub numeric: f64,
    /// Number of numeric factorisations.
    pub numeric_count: usize,
    /// All triangular solves [s].
    pub solve: f64,
    /// Number of solves.
    pub solve_count: usize,
}

/// Assembler, factorisation and load vector of one problem.
#[derive(Debug)]
pub struct CoupledSystem {
    assembler: Assembler,
    solver: LdltSolver,
    matrix: Option<SymmetricMatrix>,
    /// f̌ on the free DOFs: assembled once, it does not depend on x_n.
    load: Vec<f64>,
    /// f̌ plus the Dirichlet lifting of the current matrix, on the free DOFs.
    rhs: Vec<f64>,
    timings: Timings,
}

impl CoupledSystem {
    /// Numbers DOFs, builds the pattern (with room for nodal blocks on `block_nodes`) and
    /// runs the symbolic analysis.
    pub fn new(problem: &Problem, block_nodes: &[usize]) -> Result<Self> {
        let t = Instant::now();
        let assembler = Assembler::new(problem, block_nodes)?;
        let load = assembler.restrict(&assembler.load_vector(problem));
        let assembly = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let solver = LdltSolver::analyze(assembler.pattern(), assembler.dofs().signs())?;
        let timings =
            Timings { assembly, symbolic: t.elapsed().as_secs_f64(), ..Timings::default() };
        Ok(Self { assembler, solver, matrix: None, load, rhs: Vec::new(), timings })
    }

    /// Assembles B̌ with the secant moduli `g` (one per element) plus the nodal `blocks`, and
    /// factorises.
    pub fn factorize(&mut self, problem: &Problem, g: &[f64], blocks: &[NodalBlock]) -> Result<()> {
        let t = Instant::now();
        let (matrix, lifting) = self.assembler.matrix(problem, g, blocks)?;
        self.rhs = self.load.iter().zip(&lifting).map(|(f, l)| f + l).collect();
        self.timings.assembly += t.elapsed().as_secs_f64();
        let t = Instant::now();
        self.solver.factorize(&matrix)?;
        self.timings.numeric += t.elapsed().as_secs_f64();
        self.timings.numeric_count = self.solver.numeric_factorizations();
        self.matrix = Some(matrix);
        Ok(())
    }

    /// Solves with the current factorisation for the current right-hand side plus `extra`
    /// (free DOFs), returning the global vector x = (u, ϕ) with prescribed values in place.
    pub fn solve(&mut self, extra: Option<&[f64]>) -> Result<Vec<f64>> {
        let mut x = self.rhs.clone();
        if let Some(extra) = extra {
            x.iter_mut().zip(extra).for_each(|(b, e)| *b += e);
        }
        let t = Instant::now();
        self.solver.solve_in_place(&mut x)?;
        self.timings.solve += t.elapsed().as_secs_f64();
        self.timings.solve_count = self.solver.solves();
        if let Some(k) = x.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFinite { what: format!("solution component {k}") });
        }
        Ok(self.assembler.dofs().expand(&x))
    }

    /// The assembler (DOF map, pattern).
    pub fn assembler(&self) -> &Assembler {
        &self.assembler
    }

    /// The DOF map.
    pub fn dofs(&self) -> &DofMap {
        self.assembler.dofs()
    }

    /// The last factorised matrix.
    pub fn matrix(&self) -> Option<&SymmetricMatrix> {
        self.matrix.as_ref()
    }

    /// The right-hand side f̌ + lifting on the free DOFs.
    pub fn rhs(&self) -> &[f64] {
        &self.rhs
    }

    /// Number of stored values of the LDLᵀ factor.
    pub fn factor_len(&self) -> usize {
        self.solver.factor_len()
    }

    /// Timings so far.
    pub fn timings(&self) -> Timings {
        self.timings
    }
}

/// Result of a solve without contact.
#[derive(Clone, Debug)]
pub struct StaticSolution {
    /// x = (u, ϕ) on all DOFs, global numbering (u_i at node a: a·d + i; ϕ: n·d + a).
    pub x: Vec<f64>,
    /// Number of free DOFs (the order of the system).
    pub free_dofs: usize,
    /// Relative residual ‖B̌x − f̌‖ / ‖f̌‖ of the linear system on the free DOFs.
    pub relative_residual: f64,
    /// Time spent.
    pub timings: Timings,
}

/// Solves the coupled problem without contact, with B̌(x_0) at x_0 = 0 (g = g(0) = µ1: the
/// linear problem; the Hencky secant update comes with the contact algorithms).
pub fn solve_without_contact(problem: &Problem) -> Result<StaticSolution> {
    let mut system = CoupledSystem::new(problem, &[])?;
    let zero = vec![0.0; system.dofs().n_total()];
    let g = secant_moduli(problem, system.dofs(), &zero)?;
    system.factorize(problem, &g, &[])?;
    let x = system.solve(None)?;
    let free = system.assembler().restrict(&x);
    let matrix = system.matrix().ok_or_else(|| Error::LinearAlgebra("no matrix".into()))?;
    let ax = matrix.mul(&free);
    let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let r: Vec<f64> = ax.iter().zip(system.rhs()).map(|(a, b)| a - b).collect();
    let relative_residual = norm(&r) / norm(system.rhs()).max(f64::MIN_POSITIVE);
    Ok(StaticSolution {
        x,
        free_dofs: system.dofs().n_free(),
        relative_residual,
        timings: system.timings(),
    })
}

/// Element fields of a solution, padded to 3D for output.
#[derive(Clone, Debug, Default)]
pub struct ElementFields {
    /// σ per element, 3 × 3 row-major [stress], with the true law g(‖ε^D(u)‖²).
    pub sigma: Vec<[f64; 9]>,
    /// D per element [charge/length^(d−1)].
    pub electric_displacement: Vec<[f64; 3]>,
}

/// σ and D on every element of the solution x (global vector).
pub fn element_fields(problem: &Problem, dofs: &DofMap, x: &[f64]) -> Result<ElementFields> {
    let mut fields = ElementFields::default();
    for c in 0..problem.mesh.n_cells() {
        let (s, d) = match problem.mesh.dim() {
            2 => fields_on::<2, 3>(problem, &problem.material, dofs, x, c)?,
            _ => fields_on::<3, 4>(problem, &problem.material, dofs, x, c)?,
        };
        fields.sigma.push(s);
        fields.electric_displacement.push(d);
    }
    Ok(fields)
}

fn fields_on<const D: usize, const N: usize>(
    problem: &Problem,
    material: &Material,
    dofs: &DofMap,
    x: &[f64],
    c: usize,
) -> Result<([f64; 9], [f64; 3])> {
    let (eps, grad_phi) = crate::assembly::cell_gradients::<D, N>(problem, dofs, x, c)?;
    let sigma = material.true_stress(&eps, &grad_phi);
    let d = material.displacement_field(&eps, &grad_phi);
    let mut s9 = [0.0; 9];
    let mut d3 = [0.0; 3];
    for i in 0..D {
        d3[i] = d[i];
        for j in 0..D {
            s9[3 * i + j] = sigma[i][j];
        }
    }
    Ok((s9, d3))
}

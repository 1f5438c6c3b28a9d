//! `piezocontact bench`: assembly, symbolic, numeric and solve times of the coupled system —
//! on the paper's rectangle (Example 7.1 data) at several sizes, or on any Gmsh mesh — beside
//! faer's bare numeric LDLᵀ and solve of the same matrix in the same run (the floor), and
//! optionally faer's sparse LU.
//!
//! On a Gmsh mesh every boundary part is clamped and grounded and the paper's PZT-5A is used:
//! the matrix has the structure of every run on that mesh.

use anyhow::{Result, anyhow, bail};
use piezocontact::assembly::secant_moduli;
use piezocontact::case::Case;
use piezocontact::dofs::DofMap;
use piezocontact::linalg::bare_ldlt_seconds;
use piezocontact::problem::Problem;
use piezocontact::solver::CoupledSystem;
use std::path::Path;

const PAPER_CASE: &str = include_str!("../../../cases/paper-7.1.toml");

/// The material of the paper's case, for meshes from files.
const MATERIAL: &str = "[material]
young = 58.7102
poisson = 0.3912
e32 = -5.4
e33 = 15.8
e24 = 12.3
eps0 = 8.885e-3
beta22_rel = 916
beta33_rel = 830
";

/// What to benchmark.
pub enum Target<'a> {
    /// The paper's rectangle at sizes "NXxNY".
    Sizes(&'a [String]),
    /// A Gmsh mesh.
    Mesh(&'a Path),
}

/// Runs the benchmark and prints one line per mesh; `lu` adds faer's sparse LU.
pub fn run(target: &Target, lu: bool) -> Result<()> {
    println!(
        "{:>16} {:>9} {:>10} {:>11} {:>11} {:>11} {:>9} {:>15} {:>13} {:>16} {:>20} {:>10} {:>10}",
        "mesh",
        "DOFs",
        "pattern_s",
        "assembly_s",
        "symbolic_s",
        "numeric_s",
        "solve_s",
        "faer_numeric_s",
        "faer_solve_s",
        "assembly/numeric",
        "(numeric+solve)/faer",
        "nnz(A)",
        "len(L)"
    );
    match target {
        Target::Sizes(sizes) => {
            for size in *sizes {
                let (nx, ny) = size
                    .split_once('x')
                    .and_then(|(a, b)| Some((a.parse::<usize>().ok()?, b.parse::<usize>().ok()?)))
                    .ok_or_else(|| anyhow!("--sizes: '{size}' is not NXxNY, e.g. 384x64"))?;
                if nx == 0 || ny == 0 {
                    bail!("--sizes: '{size}' needs at least one cell each way");
                }
                let case = Case::from_text(
                    Path::new("cases/paper-7.1.toml"),
                    PAPER_CASE,
                    &[format!("mesh.nx={nx}"), format!("mesh.ny={ny}")],
                )?;
                measure(size, &case.problem()?, lu)?;
            }
        }
        Target::Mesh(path) => {
            let case = mesh_case(path)?;
            let name = path.file_name().map_or("mesh".into(), |n| n.to_string_lossy());
            measure(&name, &case.problem()?, lu)?;
        }
    }
    println!(
        "pattern_s: DOF map, sparsity pattern and gather plan (once per run); assembly_s: f̌ and \
         one refill of B̌ (every factorisation); both parallel over {} threads. numeric_s, \
         solve_s: piezocontact's LDLᵀ (with diagonal scaling and pivot checks); faer_*: faer's \
         bare LDLᵀ of the same matrix in the same run",
        rayon::current_num_threads()
    );
    Ok(())
}

/// A case around a Gmsh mesh: every boundary part clamped and grounded.
fn mesh_case(path: &Path) -> Result<Case> {
    let bytes = std::fs::read(path).map_err(|e| anyhow!("cannot read {}: {e}", path.display()))?;
    let mesh =
        piezocontact::mesh::gmsh::read(&bytes).map_err(|e| anyhow!("{}: {e}", path.display()))?;
    let parts: Vec<String> = mesh.parts().iter().map(|p| format!("{:?}", p.name)).collect();
    if parts.is_empty() {
        bail!(
            "{}: the mesh has no boundary parts (physical groups of dimension d − 1)",
            path.display()
        );
    }
    let parts = parts.join(", ");
    let file = std::fs::canonicalize(path).map_err(|e| anyhow!("{}: {e}", path.display()))?;
    let text = format!(
        "[mesh]\nfile = {:?}\n{MATERIAL}[boundary]\nclamped = [{parts}]\ngrounded = [{parts}]\n",
        file.display().to_string()
    );
    Ok(Case::from_text(Path::new("bench.toml"), &text, &[])?)
}

/// Assembles, analyses, factorises and solves once, then times faer's bare factorisation.
fn measure(name: &str, problem: &Problem, lu: bool) -> Result<()> {
    let t = std::time::Instant::now();
    let dofs = DofMap::new(problem)?;
    let dof_map = t.elapsed().as_secs_f64();
    let mut system = CoupledSystem::new(problem, dofs, &[])?;
    let zero = vec![0.0; system.dofs().n_total()];
    let g = secant_moduli(problem, system.dofs(), &zero)?;
    system.factorize(problem, &g, &[])?;
    system.solve(None)?;
    let timings = system.timings();
    let (pattern, assembly) = (dof_map + timings.pattern, timings.assembly);
    let matrix = system.matrix().ok_or_else(|| anyhow!("no matrix"))?;
    let [faer_numeric, faer_solve] = bare_ldlt_seconds(matrix, system.rhs())?;
    println!(
        "{:>16} {:>9} {:>10.4} {:>11.4} {:>11.4} {:>11.4} {:>9.4} {:>15.4} {:>13.4} {:>16.3} {:>20.3} {:>10} {:>10}",
        name,
        system.dofs().n_free(),
        pattern,
        assembly,
        timings.symbolic,
        timings.numeric,
        timings.solve,
        faer_numeric,
        faer_solve,
        assembly / timings.numeric,
        (timings.numeric + timings.solve) / (faer_numeric + faer_solve),
        matrix.lower_entries().count(),
        system.factor_len()
    );
    if lu {
        let [s, n, v] = matrix.time_lu(system.rhs())?;
        println!(
            "{:>16} {:>9} {:>10} {:>11} {:>11.4} {:>11.4} {:>9.4}   (faer sparse LU)",
            "", "", "", "", s, n, v
        );
    }
    Ok(())
}

//! `piezocontact bench`: assembly, symbolic, numeric and solve times on the paper's
//! rectangle (Example 7.1 data) at several mesh sizes; optionally faer's LU for comparison.

use crate::case::Case;
use anyhow::{Result, anyhow, bail};
use piezocontact::assembly::secant_moduli;
use piezocontact::solver::CoupledSystem;
use std::path::Path;

const PAPER_CASE: &str = include_str!("../../../cases/paper-7.1.toml");

/// Runs the benchmark for sizes "NXxNY".
pub fn run(sizes: &[String], lu: bool) -> Result<()> {
    println!(
        "{:>10} {:>9} {:>12} {:>12} {:>12} {:>12} {:>12} {:>12}",
        "mesh", "DOFs", "assembly_s", "symbolic_s", "numeric_s", "solve_s", "nnz(A)", "len(L)"
    );
    for size in sizes {
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
        let problem = case.problem()?;
        let mut system = CoupledSystem::new(&problem, &[])?;
        let zero = vec![0.0; system.dofs().n_total()];
        let g = secant_moduli(&problem, system.dofs(), &zero)?;
        system.factorize(&problem, &g, &[])?;
        system.solve(None)?;
        let timings = system.timings();
        let matrix = system.matrix().ok_or_else(|| anyhow!("no matrix"))?;
        let nnz = matrix.lower_entries().count();
        println!(
            "{:>10} {:>9} {:>12.4} {:>12.4} {:>12.4} {:>12.4} {:>12} {:>12}",
            size,
            system.dofs().n_free(),
            timings.assembly,
            timings.symbolic,
            timings.numeric,
            timings.solve,
            nnz,
            system.factor_len()
        );
        if lu {
            let [s, n, v] = matrix.time_lu(system.rhs())?;
            println!(
                "{:>10} {:>9} {:>12} {:>12.4} {:>12.4} {:>12.4}   (faer sparse LU)",
                "", "", "", s, n, v
            );
        }
    }
    Ok(())
}

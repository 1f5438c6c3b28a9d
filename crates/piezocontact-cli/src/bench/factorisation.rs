//! `piezocontact bench`: assembly, symbolic, numeric and solve times of the coupled system —
//! on the paper's rectangle (Example 7.1 data) at several sizes, or on any Gmsh mesh — for
//! each ordering (AMD, nested dissection) and thread count, beside faer's bare numeric LDLᵀ
//! and solve of the same matrix with the same analysis in the same run (the floor), and
//! optionally faer's sparse LU.
//!
//! On a Gmsh mesh every boundary part is clamped and grounded and the paper's PZT-5A is used:
//! the matrix has the structure of every run on that mesh.

use super::{PAPER_CASE, factorised_once, mesh_case, paper_case, parse_size};
use crate::say;
use anyhow::{Result, anyhow, bail};
use piezocontact::algorithm::condensed::SOLVE_BLOCK;
use piezocontact::linalg::{LdltSolver, LinearSolver, Ordering};
use piezocontact::problem::Problem;
use std::path::Path;

/// The default sizes of the factorisation benchmark.
pub const SIZES: [&str; 3] = ["96x16", "384x64", "1536x256"];

/// What to benchmark.
pub enum Target<'a> {
    /// The paper's rectangle at sizes "NXxNY".
    Sizes(&'a [String]),
    /// A Gmsh mesh.
    Mesh(&'a Path),
}

/// The orderings and thread counts of the factorisation benchmark.
pub struct Variants {
    /// The orderings, each measured on every thread count.
    pub orderings: Vec<Ordering>,
    /// The thread counts.
    pub threads: Vec<usize>,
}

/// The name of an ordering in the benchmark's rows.
fn ordering_name(ordering: &Ordering) -> &'static str {
    match ordering {
        Ordering::Auto => "auto",
        Ordering::Amd => "amd",
        Ordering::NestedDissection => "nd",
        Ordering::Custom(_) => "custom",
    }
}

/// Parses `--ordering amd,nd,auto`.
pub fn parse_ordering(name: &str) -> Result<Ordering> {
    match name.trim() {
        "amd" => Ok(Ordering::Amd),
        "nd" => Ok(Ordering::NestedDissection),
        "auto" => Ok(Ordering::Auto),
        other => bail!("--ordering: '{other}' is not one of amd, nd, auto"),
    }
}

/// One measured row: (numeric seconds, factor bytes) for the ratios.
type Row = (f64, f64);

/// Runs the benchmark and prints one line per mesh, ordering and thread count; `lu` adds
/// faer's sparse LU. With AMD and nested dissection both measured, prints the ratios of
/// nested dissection on the most threads to AMD on one thread.
pub fn run(target: &Target, variants: &Variants, lu: bool) -> Result<()> {
    let problems: Vec<(String, Problem)> = match target {
        Target::Sizes(sizes) => sizes
            .iter()
            .map(|size| {
                let (nx, ny) = parse_size(size)?;
                Ok((size.clone(), paper_case(PAPER_CASE, nx, ny, &[])?.problem()?))
            })
            .collect::<Result<_>>()?,
        Target::Mesh(path) => {
            let name = path.file_name().map_or("mesh".into(), |n| n.to_string_lossy());
            vec![(name.to_string(), mesh_case(path)?.problem()?)]
        }
    };
    say!(
        "{:>16} {:>5} {:>7} {:>9} {:>10} {:>11} {:>11} {:>11} {:>9} {:>10} {:>15} {:>13} {:>16} {:>20} {:>10} {:>11} {:>10}",
        "mesh",
        "order",
        "threads",
        "DOFs",
        "pattern_s",
        "assembly_s",
        "symbolic_s",
        "numeric_s",
        "solve_s",
        "solve32_s",
        "faer_numeric_s",
        "faer_solve_s",
        "assembly/numeric",
        "(numeric+solve)/faer",
        "nnz(A)",
        "len(L)",
        "factor_MB"
    );
    for (name, problem) in &problems {
        let mut rows = Vec::new();
        for ordering in &variants.orderings {
            for &threads in &variants.threads {
                let row = measure(name, problem, ordering, threads, lu)?;
                rows.push((ordering_name(ordering), threads, row));
            }
        }
        ratios(&rows);
    }
    say!(
        "pattern_s: DOF map, sparsity pattern and gather plan (once per run); assembly_s: f̌ and \
         one refill of B̌ (every factorisation); both parallel over {} threads. symbolic_s: the \
         ordering, the elimination tree and the factor's storage; numeric_s, solve_s: \
         piezocontact's LDLᵀ (with diagonal scaling and pivot checks) on `threads` threads; \
         solve32_s: 32 right-hand sides solved at once (one blocked sweep each way); faer_*: \
         faer's bare LDLᵀ of the same matrix with the same ordering and threads; factor_MB: \
         the factor, its workspace and the scaled matrix, as predicted after the symbolic \
         analysis",
        rayon::current_num_threads()
    );
    Ok(())
}

/// Nested dissection on the most threads against AMD on one thread, when both were measured.
fn ratios(rows: &[(&str, usize, Row)]) {
    let find = |order: &str, most: bool| {
        let matching = rows.iter().filter(|(o, ..)| *o == order);
        if most { matching.max_by_key(|r| r.1) } else { matching.min_by_key(|r| r.1) }
    };
    if let (Some(amd), Some(nd)) = (find("amd", false), find("nd", true)) {
        let ((t_amd, b_amd), (t_nd, b_nd)) = (amd.2, nd.2);
        say!(
            "  nd on {} threads / amd on {} thread(s): numeric {:.3}× ({:.3} s / {:.3} s), factor bytes {:.3}× ({:.1} MB / {:.1} MB)",
            nd.1,
            amd.1,
            t_nd / t_amd,
            t_nd,
            t_amd,
            b_nd / b_amd,
            b_nd / 1e6,
            b_amd / 1e6
        );
    }
}

/// Assembles, analyses, factorises and solves once with `ordering` on `threads` threads, and
/// the [`SOLVE_BLOCK`] right-hand sides that a growth of the condensation solves at once
/// (`solve32_s`), then times faer's bare factorisation with the same analysis; prints the
/// row.
fn measure(
    name: &str,
    problem: &Problem,
    ordering: &Ordering,
    threads: usize,
    lu: bool,
) -> Result<Row> {
    let solver = || LdltSolver::with_ordering(ordering.clone()).on_threads(threads);
    let (mut system, dof_map) = factorised_once(problem, Box::new(solver()))?;
    let timings = system.timings();
    let stats = timings.solver;
    let mut block: Vec<f64> = system.rhs().repeat(SOLVE_BLOCK);
    system.solve_free(&mut block)?;
    let solve_block = system.solver_stats().solve_seconds - stats.solve_seconds;
    let (pattern, assembly) = (dof_map + timings.pattern, timings.assembly);
    let matrix = system.matrix().ok_or_else(|| anyhow!("no matrix"))?;
    let mut bare = solver();
    bare.analyze(system.assembler().pattern(), &system.dofs().signs())?;
    let [faer_numeric, faer_solve] = bare.bare_seconds(matrix, system.rhs())?;
    say!(
        "{:>16} {:>5} {:>7} {:>9} {:>10.4} {:>11.4} {:>11.4} {:>11.4} {:>9.4} {:>10.4} {:>15.4} {:>13.4} {:>16.3} {:>20.3} {:>10} {:>11} {:>10.1}",
        name,
        stats.ordering,
        threads,
        system.dofs().n_free(),
        pattern,
        assembly,
        stats.symbolic_seconds,
        stats.numeric_seconds,
        stats.solve_seconds,
        solve_block,
        faer_numeric,
        faer_solve,
        assembly / stats.numeric_seconds,
        (stats.numeric_seconds + stats.solve_seconds) / (faer_numeric + faer_solve),
        matrix.lower_entries().count(),
        stats.factor_len,
        stats.factor_bytes / 1e6
    );
    if lu {
        let [s, n, v] = matrix.time_lu(system.rhs())?;
        say!(
            "{:>16} {:>5} {:>7} {:>9} {:>10} {:>11} {:>11.4} {:>11.4} {:>9.4}   (faer sparse LU)",
            "",
            "",
            "",
            "",
            "",
            "",
            s,
            n,
            v
        );
    }
    Ok((stats.numeric_seconds, stats.factor_bytes))
}

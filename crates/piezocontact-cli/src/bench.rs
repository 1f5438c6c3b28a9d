//! `piezocontact bench`: assembly, symbolic, numeric and solve times of the coupled system —
//! on the paper's rectangle (Example 7.1 data) at several sizes, or on any Gmsh mesh — for
//! each ordering (AMD, nested dissection) and thread count, beside faer's bare numeric LDLᵀ
//! and solve of the same matrix with the same analysis in the same run (the floor), and
//! optionally faer's sparse LU.
//!
//! On a Gmsh mesh every boundary part is clamped and grounded and the paper's PZT-5A is used:
//! the matrix has the structure of every run on that mesh.

use crate::say;
use anyhow::{Result, anyhow, bail};
use piezocontact::algorithm::condensed::SOLVE_BLOCK;
use piezocontact::algorithm::solve_contact_with;
use piezocontact::assembly::secant_moduli;
use piezocontact::case::{Built, Case};
use piezocontact::dofs::DofMap;
use piezocontact::linalg::{LdltSolver, LinearSolver, Ordering, default_solver};
use piezocontact::path::PathRun;
use piezocontact::problem::Problem;
use piezocontact::solver::CoupledSystem;
use std::path::Path;
use std::time::Instant;

const PAPER_CASE: &str = include_str!("../../../cases/paper-7.1.toml");
const PAPER_PV2: &str = include_str!("../../../cases/paper-7.2.toml");
const INDENTATION: &str = include_str!("../../../cases/indentation-3d.toml");

/// The default sizes of the factorisation benchmark.
pub const SIZES: [&str; 3] = ["96x16", "384x64", "1536x256"];
/// The default sizes of the contact benchmark.
pub const CONTACT_SIZES: [&str; 4] = ["96x16", "192x32", "384x64", "768x128"];

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

/// A case around a Gmsh mesh: every boundary part clamped and grounded.
pub(crate) fn mesh_case(path: &Path) -> Result<Case> {
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
    let t = std::time::Instant::now();
    let dofs = DofMap::new(problem)?;
    let dof_map = t.elapsed().as_secs_f64();
    let solver = || LdltSolver::with_ordering(ordering.clone()).on_threads(threads);
    let mut system = CoupledSystem::new(problem, dofs, &[], Box::new(solver()))?;
    let zero = vec![0.0; system.dofs().n_total()];
    let g = secant_moduli(problem, system.dofs(), &zero)?;
    system.factorize(problem, &g, &[])?;
    system.solve(None)?;
    let timings = system.timings();
    let stats = system.solver_stats();
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
        timings.symbolic,
        timings.numeric,
        timings.solve,
        solve_block,
        faer_numeric,
        faer_solve,
        assembly / timings.numeric,
        (timings.numeric + timings.solve) / (faer_numeric + faer_solve),
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
    Ok((timings.numeric, stats.factor_bytes))
}

/// Parses "NXxNY".
fn parse_size(size: &str) -> Result<(usize, usize)> {
    let (nx, ny) = size
        .split_once('x')
        .and_then(|(a, b)| Some((a.parse::<usize>().ok()?, b.parse::<usize>().ok()?)))
        .ok_or_else(|| anyhow!("--sizes: '{size}' is not NXxNY, e.g. 384x64"))?;
    if nx == 0 || ny == 0 {
        bail!("--sizes: '{size}' needs at least one cell each way");
    }
    Ok((nx, ny))
}

/// A paper case on an nx × ny mesh with more overrides.
fn paper_case(text: &str, nx: usize, ny: usize, extra: &[String]) -> Result<Case> {
    let mut overrides = vec![format!("mesh.nx={nx}"), format!("mesh.ny={ny}")];
    overrides.extend_from_slice(extra);
    Ok(Case::from_text(Path::new("cases/paper.toml"), text, &overrides)?)
}

/// The target of `bench --contact --case FILE`.
pub fn case_target(file: &Path) -> String {
    format!("{CASE_PREFIX}{}", file.display())
}

/// What marks a case file among the targets of the contact benchmark.
const CASE_PREFIX: &str = "case:";

/// The problems of the contact benchmark on a target: the paper's bar at a size "NXxNY"
/// (PV1, PV2 with µ = k_e = 0.2 and 0.6), a Gmsh mesh with the parts of
/// meshes/indent-3d.geo in the indentation case, or "case:FILE" (both: PV1, and PV2 with
/// µ = 0.3).
fn contact_problems(target: &str) -> Result<Vec<(&'static str, Case)>> {
    let newton = || vec!["solver.method=\"newton\"".to_string()];
    if let Some(file) = target.strip_prefix(CASE_PREFIX) {
        let with = |extra: &[&str]| -> Result<Case> {
            let mut overrides = newton();
            overrides.extend(extra.iter().map(|s| s.to_string()));
            let case = Case::load(Path::new(file), &overrides)?;
            case.one_position()
                .map_err(|e| anyhow!("{e}; `bench --path --case {file}` times the path"))?;
            Ok(case)
        };
        let pv2 = ["contact.problem=\"PV2\"", "friction.mu=0.3"];
        return Ok(vec![("PV1", with(&["contact.problem=\"PV1\""])?), ("PV2 mu=0.3", with(&pv2)?)]);
    }
    if let Ok((nx, ny)) = parse_size(target) {
        let pv2 = |mu: f64| {
            let mut o = newton();
            o.extend([format!("friction.mu={mu}"), format!("conductivity.ke={mu}")]);
            o
        };
        return Ok(vec![
            ("PV1", paper_case(PAPER_CASE, nx, ny, &newton())?),
            ("PV2 mu=0.2", paper_case(PAPER_PV2, nx, ny, &pv2(0.2))?),
            ("PV2 mu=0.6", paper_case(PAPER_PV2, nx, ny, &pv2(0.6))?),
        ]);
    }
    let file = std::fs::canonicalize(target).map_err(|e| anyhow!("--mesh {target}: {e}"))?;
    let with = |extra: &[&str]| -> Result<Case> {
        let mut overrides = newton();
        overrides.push(format!("mesh.file={:?}", file.display().to_string()));
        overrides.extend(extra.iter().map(|s| s.to_string()));
        Ok(Case::from_text(Path::new("cases/indentation-3d.toml"), INDENTATION, &overrides)?)
    };
    Ok(vec![("PV1", with(&["contact.problem=\"PV1\""])?), ("PV2 mu=0.3", with(&[])?)])
}

/// `bench --contact`: every measurement in a process of its own (peak memory per run), on
/// each target: a size "NXxNY" of the paper's bar or a Gmsh mesh.
pub fn contact(targets: &[String]) -> Result<()> {
    let names: Vec<Vec<&str>> = targets
        .iter()
        .map(|t| Ok(contact_problems(t)?.into_iter().map(|(name, _)| name).collect()))
        .collect::<Result<_>>()?;
    say!(
        "{:>10} {:>9} {:>11} {:>11} {:>7} {:>12} {:>9} {:>14} {:>8} {:>9} {:>15} {:>9}",
        "mesh",
        "DOFs",
        "problem",
        "condensed",
        "newton",
        "kkt_residual",
        "wall_s",
        "factorisation_s",
        "ratio",
        "peak_MB",
        "factorisation_MB",
        "mem_ratio"
    );
    let exe = std::env::current_exe()?;
    let one = |spec: String| -> Result<Vec<(String, String)>> {
        let out = std::process::Command::new(&exe).args(["bench", "--one", &spec]).output()?;
        if !out.status.success() {
            bail!("{spec}: {}", String::from_utf8_lossy(&out.stderr).trim());
        }
        Ok(String::from_utf8_lossy(&out.stdout)
            .split_whitespace()
            .filter_map(|kv| kv.split_once('=').map(|(k, v)| (k.to_string(), v.to_string())))
            .collect())
    };
    let get = |fields: &[(String, String)], key: &str| -> Result<f64> {
        fields
            .iter()
            .find(|(k, _)| k == key)
            .and_then(|(_, v)| v.parse().ok())
            .ok_or_else(|| anyhow!("the measurement printed no {key}"))
    };
    for (target, names) in targets.iter().zip(names) {
        let plain = one(format!("plain,{target}"))?;
        let (plain_s, plain_mb) = (get(&plain, "seconds")?, get(&plain, "peak_mb")?);
        let size =
            Path::new(target).file_name().map_or(target.clone(), |n| n.to_string_lossy().into());
        for (k, name) in names.into_iter().enumerate() {
            let run = one(format!("contact{k},{target}"))?;
            let (seconds, mb) = (get(&run, "seconds")?, get(&run, "peak_mb")?);
            say!(
                "{:>10} {:>9} {:>11} {:>11} {:>7} {:>12.3e} {:>9.3} {:>14.3} {:>8.2} {:>9.0} {:>15.0} {:>9.2}",
                size,
                get(&run, "dofs")?,
                name,
                format!("{}/{}", get(&run, "condensed")?, get(&run, "gamma3")?),
                get(&run, "newton")?,
                get(&run, "kkt")?,
                seconds,
                plain_s,
                seconds / plain_s,
                mb,
                plain_mb,
                mb / plain_mb
            );
        }
    }
    say!(
        "condensed: Γ3 nodes in the exact solver's dense problem / all Γ3 nodes; wall_s: \
         solve_contact with solver.method = \"newton\" (pattern, ordering, factorisations, \
         Schur complement, Newton, two solves per factorisation, KKT residual); factorisation_s: one plain \
         pattern + assembly + symbolic + numeric LDLᵀ of the same mesh, the floor; both with \
         solver.ordering = \"auto\" (nested dissection in 3D) on {} \
         threads in 3D (one in 2D); peak_MB: the process's peak resident memory; ratios: contact / factorisation",
        rayon::current_num_threads()
    );
    Ok(())
}

/// One measurement of `bench --contact`, printed as key=value pairs: "plain,TARGET" or
/// "contactK,TARGET".
pub fn measure_one(spec: &str) -> Result<()> {
    let (kind, target) = spec.split_once(',').ok_or_else(|| anyhow!("--one {spec}"))?;
    #[cfg(feature = "petsc")]
    if kind == "faer" {
        return crate::bench_petsc::measure_faer(Path::new(target));
    }
    let mut problems = contact_problems(target)?;
    if kind == "plain" {
        let problem = problems.swap_remove(0).1.problem()?;
        let start = std::time::Instant::now();
        let mut system =
            CoupledSystem::new(&problem, DofMap::new(&problem)?, &[], default_solver())?;
        let g = vec![problem.material.elasticity.mu1; problem.mesh.n_cells()];
        system.factorize(&problem, &g, &[])?;
        let seconds = start.elapsed().as_secs_f64();
        say!("seconds={seconds} peak_mb={}", peak_mb());
        return Ok(());
    }
    let k: usize = kind.trim_start_matches("contact").parse()?;
    let (_, case) = problems.into_iter().nth(k).ok_or_else(|| anyhow!("--one {spec}"))?;
    let Built { problem, model, settings, .. } = case.build()?;
    let model = model.ok_or_else(|| anyhow!("no [contact] table"))?;
    let start = std::time::Instant::now();
    let s = &piezocontact::algorithm::solve_contact(&problem, &model, &settings)?;
    let seconds = start.elapsed().as_secs_f64();
    say!(
        "seconds={seconds} peak_mb={} dofs={} condensed={} gamma3={} newton={} kkt={} converged={}",
        peak_mb(),
        s.dofs.n_free(),
        s.condensed_nodes,
        s.surface.len(),
        s.inner_iterations.iter().sum::<usize>(),
        s.kkt.max,
        s.converged
    );
    Ok(())
}

/// Peak resident memory of this process [MiB] (0 where the system does not say).
pub(crate) fn peak_mb() -> f64 {
    piezocontact::limits::peak_resident_bytes().map_or(0.0, |b| b / 1024.0 / 1024.0)
}

/// `bench --path`: the loading path of `case_file` (`--mesh` replacing its mesh) solved as
/// a path — each step from the last, the analysis, the factorisation and the condensation
/// kept — against the same steps solved cold, one solve each, in the same process.
pub fn path(case_file: &Path, mesh: Option<&Path>) -> Result<()> {
    let mut overrides = Vec::new();
    if let Some(mesh) = mesh {
        let file =
            std::fs::canonicalize(mesh).map_err(|e| anyhow!("--mesh {}: {e}", mesh.display()))?;
        overrides.push(format!("mesh.file={:?}", file.display().to_string()));
    }
    let case = Case::load(case_file, &overrides)?;
    let start = Instant::now();
    let path = PathRun::solve_built(&case, case.build()?, case.linear_solver()?, &|_| {})?;
    let path_seconds = start.elapsed().as_secs_f64();
    if let Some(failure) = &path.failure {
        bail!("{}: {failure}", case_file.display());
    }
    let start = Instant::now();
    let (mut factorisations, mut newton, mut difference) = (0, 0, 0.0_f64);
    for (step, row) in path.loading.steps.iter().zip(&path.curve) {
        let Built { mut problem, model, settings, .. } = case.build()?;
        let model = model.ok_or_else(|| anyhow!("no [contact] table"))?;
        problem.load_factor = step.load_factor;
        let model = path.loading.model_at(&model, step);
        let s = solve_contact_with(&problem, &model, &settings, case.linear_solver()?, &|_| {})?;
        factorisations += s.timings.numeric_count;
        newton += s.inner_iterations.iter().sum::<usize>();
        let force: f64 = s.balance.contact.iter().map(|f| f * f).sum::<f64>().sqrt();
        let path_force: f64 = row.force.iter().map(|f| f * f).sum::<f64>().sqrt();
        difference = difference.max((force - path_force).abs() / force.max(f64::MIN_POSITIVE));
    }
    let cold_seconds = start.elapsed().as_secs_f64();
    let t = path.last.solution.timings;
    let path_newton: usize = path.curve.iter().map(|r| r.newton_steps).sum();
    say!(
        "{}: {} steps, {} unknowns",
        case_file.display(),
        path.curve.len(),
        path.last.solution.dofs.n_free()
    );
    say!("{:>6} {:>9} {:>15} {:>13}", "", "wall_s", "factorisations", "newton_steps");
    say!("{:>6} {:>9.3} {:>15} {:>13}", "path", path_seconds, t.numeric_count, path_newton);
    say!("{:>6} {:>9.3} {:>15} {:>13}", "cold", cold_seconds, factorisations, newton);
    say!(
        "path / cold: {:.3} (wall time); largest relative difference of the force between a path step and its cold solve {difference:.1e}",
        path_seconds / cold_seconds
    );
    Ok(())
}

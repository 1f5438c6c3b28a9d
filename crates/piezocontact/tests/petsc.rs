//! The PETSc + MUMPS backend against faer's LDLᵀ, under `mpirun` with 1, 2 and 3 processes.
//!
//! Each test starts itself again under `mpirun -n N` (Open MPI's, found on PATH) for each N;
//! the processes run the test's body, in which every assertion is checked on every process.
//! Run with `cargo test --workspace --features piezocontact-cli/petsc --test petsc`.

use piezocontact::assembly::Assembler;
use piezocontact::assembly::secant_moduli;
use piezocontact::case::{Built, Case};
use piezocontact::dofs::DofMap;
use piezocontact::linalg::petsc::{self, PetscSolver};
use piezocontact::linalg::{
    LdltSolver, LinearRoute, LinearSolver, Patched, RowLu, RowMatrix, SymmetricMatrix,
};
use piezocontact::run::{ContactRun, Run};
use piezocontact::system::{CoupledSystem, solve_without_contact};
use std::path::PathBuf;
use std::process::Command;
use std::sync::Mutex;

/// The process counts every test runs with.
const PROCESSES: [usize; 3] = [1, 2, 3];

/// Runs `body` on N processes for each N of [`PROCESSES`]: from the test harness, starts
/// this test under mpirun (one MPI job at a time) and asserts that every process passed,
/// showing the processes' output when one did not; under mpirun, runs it.
fn on_processes(test: &str, body: impl FnOnce()) {
    on(&PROCESSES, test, body)
}

/// [`on_processes`] with the process counts `counts`.
fn on(counts: &[usize], test: &str, body: impl FnOnce()) {
    if std::env::var_os("OMPI_COMM_WORLD_SIZE").is_some() {
        // MPI first: MPI_Abort before MPI_Init cannot end the job, and the process would
        // exit with 1 and the MPI library's complaint instead of the assertion's.
        petsc::initialize("").expect("PETSc and MPI start");
        // A failed assertion on one process ends them all (the others would wait for it).
        let report = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            report(info);
            petsc::abort(101);
        }));
        body();
        return;
    }
    // One MPI job at a time: Open MPI's jobs on one machine share its session directory, and
    // jobs started together can fail to make theirs (Open MPI's issue 8510); this file's
    // tests run on parallel threads.
    static ONE_JOB: Mutex<()> = Mutex::new(());
    let _job = ONE_JOB.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    for &n in counts {
        let output = Command::new("mpirun")
            .args(["--allow-run-as-root", "--oversubscribe", "--timeout", "600", "-n"])
            .arg(n.to_string())
            .arg(std::env::current_exe().unwrap())
            .args(["--exact", test, "--test-threads=1", "--nocapture"])
            .env("RUST_BACKTRACE", "0") // the assertion's message and line, shown below
            .output()
            .expect("mpirun (Open MPI) on PATH");
        assert!(
            output.status.success(),
            "{test} under mpirun -n {n}: {}\n--- stdout ---\n{}\n--- stderr ---\n{}",
            output.status,
            tail(&output.stdout),
            tail(&output.stderr)
        );
    }
}

/// The last 60 lines of a process's output.
fn tail(output: &[u8]) -> String {
    let text = String::from_utf8_lossy(output);
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(60)..].join("\n")
}

fn case(name: &str, overrides: &[&str]) -> Case {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../cases").join(name);
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Case::load(&file, &overrides).unwrap()
}

fn petsc_solver() -> Box<dyn LinearSolver> {
    Box::new(PetscSolver::new().unwrap())
}

fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let norm = |v: &mut dyn Iterator<Item = f64>| v.map(|x| x * x).sum::<f64>().sqrt();
    norm(&mut a.iter().zip(b).map(|(x, y)| x - y)) / norm(&mut b.iter().copied())
}

/// The rows of `matrix` that the patched solves' tests change: every seventh.
fn patched(r: usize) -> bool {
    r.is_multiple_of(7)
}

/// `rows` (K's [`patched`] rows) with their diagonal × `diagonal` and their other entries
/// × (1 + `skew` (column mod 3)), unsymmetric when `skew` ≠ 0; of `rows`' pattern.
fn patch(rows: &RowMatrix, diagonal: f64, skew: f64) -> RowMatrix {
    let mut rows = rows.clone();
    for r in (0..rows.n()).filter(|&r| patched(r)) {
        let (columns, values) = rows.row_mut(r);
        for (c, v) in columns.iter().zip(values) {
            *v *= if *c == r { diagonal } else { 1.0 + skew * (c % 3) as f64 };
        }
    }
    rows
}

/// The sparse LU's solution of `matrix` with `jacobian`'s rows in place of its own.
fn patched_lu(matrix: &SymmetricMatrix, jacobian: &RowMatrix, b: &[f64]) -> Vec<f64> {
    let pattern = matrix.pattern();
    let whole = Patched::new(&pattern, jacobian, jacobian).unwrap();
    let mut x = b.to_vec();
    RowLu::default().solve(&whole.whole_jacobian(matrix).unwrap(), &mut x).unwrap();
    x
}

#[test]
fn mumps_solves_the_coupled_system_as_faer_does() {
    on_processes("mumps_solves_the_coupled_system_as_faer_does", || {
        let problem = case("paper-7.2.toml", &[]).problem().unwrap();
        let faer = solve_without_contact(&problem, Box::new(LdltSolver::new())).unwrap();
        let mumps = solve_without_contact(&problem, petsc_solver()).unwrap();
        let difference = relative_difference(&mumps.x, &faer.x);
        assert!(difference < 1e-10, "‖x_mumps − x_faer‖/‖x_faer‖ = {difference:e}");
        assert!(mumps.relative_residual < 1e-10, "residual {:e}", mumps.relative_residual);
        // The iterative route, with a held row for each constrained component of the rollers.
        let krylov = solve_without_contact(&problem, krylov_solver()).unwrap();
        let difference = relative_difference(&krylov.x, &faer.x);
        assert!(difference < 1e-8, "‖x_krylov − x_faer‖/‖x_faer‖ = {difference:e}");
    });
}

/// Each process's rows of the distributed matrix are the serial matrix's, entry by entry: on
/// the direct route (one AIJ matrix) and on the iterative one (the field blocks of PETSc's
/// MATNEST, read back through them).
#[test]
fn each_process_holds_its_rows_of_the_same_matrix() {
    on_processes("each_process_holds_its_rows_of_the_same_matrix", || {
        for iterative in [false, true] {
            let solver = match iterative {
                false => PetscSolver::new().unwrap(),
                true => PetscSolver::iterative(1e-10, 100).unwrap(),
            };
            holds_its_rows_of_the_same_matrix(solver, iterative);
        }
    });
}

fn holds_its_rows_of_the_same_matrix(mut solver: PetscSolver, blocks: bool) {
    let problem = case("paper-7.2.toml", &[]).problem().unwrap();
    let dofs = DofMap::new(&problem).unwrap();
    let moduli = vec![1.0; problem.mesh.n_cells()];
    let serial = || Box::new(LdltSolver::new()) as Box<dyn LinearSolver>;
    let mut faer = CoupledSystem::new(&problem, dofs.clone(), &[], serial()).unwrap();
    faer.factorize(&problem, &moduli, &[]).unwrap();
    let (ptr, neighbours) = piezocontact::assembly::node_neighbours(&problem.mesh);
    let weights = dofs.free_per_node();
    let owned = solver.distributed().unwrap().owned_nodes(&weights, (&ptr, &neighbours)).unwrap();
    // The assembly of this process's rows, then the backend fed with them.
    let mine = Assembler::new(&problem, dofs.clone(), &[], owned.as_deref()).unwrap();
    let (matrix, _) = mine.matrix(&problem, &moduli, &[]).unwrap();
    solver.analyze(mine.pattern(), &dofs.signs()).unwrap();
    solver.factorize(&matrix).unwrap();
    assert_eq!(solver.stores_field_blocks(), blocks, "MATNEST on the iterative route alone");
    let (rank, size) = petsc::rank_and_size();
    let whole: &SymmetricMatrix = faer.matrix().unwrap();
    let (n, nnz) = (whole.n(), whole.lower_entries().count());
    let rows = solver.owned_unknowns();
    assert!(rows.len().abs_diff(n / size) <= 4, "rank {rank}: {} of {n} rows", rows.len());
    // No process holds the whole matrix: its rows and the entries that couple to them.
    let held = matrix.lower_entries().count();
    if size > 1 {
        let bound = (1.0 / size as f64 + 0.15) * nnz as f64;
        assert!((held as f64) < bound, "rank {rank}: {held} of {nnz} entries");
    }
    // Every entry of the owned rows, both triangles, as the serial matrix has it.
    let mut serial_entries = std::collections::HashMap::new();
    for (i, j, v) in whole.lower_entries() {
        serial_entries.insert((i, j), v);
        serial_entries.insert((j, i), v);
    }
    let owned_set: std::collections::HashSet<usize> = rows.iter().copied().collect();
    let expected = serial_entries.keys().filter(|(i, _)| owned_set.contains(i)).count();
    let entries = solver.owned_entries().unwrap();
    assert_eq!(entries.len(), expected, "rank {rank}: stored entries");
    for (i, j, v) in entries {
        let e = serial_entries[&(i, j)];
        assert!((v - e).abs() <= 1e-14 * e.abs(), "({i}, {j}): {v} vs {e}");
    }
    let covered = petsc::gather(rows.len() as f64).unwrap();
    if rank == 0 {
        assert_eq!(covered.iter().sum::<f64>() as usize, n, "rows of all processes");
    }
}

#[test]
fn mumps_schur_complement_is_faers() {
    on_processes("mumps_schur_complement_is_faers", || {
        let problem = case("paper-7.2.toml", &[]).problem().unwrap();
        let dofs = DofMap::new(&problem).unwrap();
        // Unknowns of both kinds, out of order.
        let last = [40, 7, dofs.n_free() - 1, 1000, 3, dofs.n_free() / 2];
        let moduli = vec![1.0; problem.mesh.n_cells()];
        let mut both =
            [Box::new(LdltSolver::new()) as Box<dyn LinearSolver>, petsc_solver()].map(|solver| {
                let mut system =
                    CoupledSystem::with_last(&problem, dofs.clone(), &last, solver).unwrap();
                system.factorize(&problem, &moduli, &[]).unwrap();
                system
            });
        let [faer, mumps] = &mut both;
        let (s_faer, s_mumps) =
            (faer.schur_complement().unwrap(), mumps.schur_complement().unwrap());
        for a in 0..last.len() {
            for b in 0..last.len() {
                let (x, y) = (s_mumps.get(a, b), s_faer.get(a, b));
                let scale = (s_faer.get(a, a) * s_faer.get(b, b)).abs().sqrt();
                assert!((x - y).abs() <= 1e-10 * scale, "S[{a}, {b}]: {x} vs {y}");
            }
        }
        // A whole solve through the Schur complement.
        let (x_faer, x_mumps) = (faer.solve(None).unwrap(), mumps.solve(None).unwrap());
        for (name, sys, x) in [("faer", faer, &x_faer), ("mumps", mumps, &x_mumps)] {
            let residual = sys.relative_residual(x).unwrap();
            assert!(residual < 1e-10, "{name}: ‖B̌x − f̌‖/‖f̌‖ = {residual:e}");
        }
        let difference = relative_difference(&x_mumps, &x_faer);
        assert!(difference < 1e-11, "solve with a Schur set: {difference:e}");
    });
}

/// The one contact run of `built` with `solver`.
fn contact_run(built: &Built, solver: Box<dyn LinearSolver>) -> ContactRun {
    match Run::solve(built, solver, &|_| {}).unwrap() {
        Run::Contact(run) => run,
        _ => panic!("not one contact run"),
    }
}

/// The contact run of `case` with both backends: the same Γ3 fields and KKT bound.
fn same_contact(name: &str, overrides: &[&str], tolerance: f64) {
    same_contact_with(name, overrides, tolerance, petsc_solver);
}

/// The contact run of `case` with faer's LDLᵀ and with the PETSc solver `petsc` makes: the
/// same solution and Γ3 fields, and with the exact solver the KKT bound.
fn same_contact_with(
    name: &str,
    overrides: &[&str],
    tolerance: f64,
    petsc: fn() -> Box<dyn LinearSolver>,
) {
    let built = case(name, overrides).build().unwrap();
    let run = |solver| contact_run(&built, solver);
    let (faer, other) = (run(Box::new(LdltSolver::new())), run(petsc()));
    assert!(faer.solution.converged() && other.solution.converged());
    let distance = other.distance_to(&built, &faer).unwrap();
    assert!(distance < tolerance, "{name} {overrides:?}: ‖x − x_faer‖_X/‖x_faer‖_X = {distance:e}");
    let field = |run: &ContactRun| -> Vec<f64> {
        run.rows.iter().flat_map(|r| [r.u_nu, r.sigma_nu, r.phi, r.sigma_tau[0]]).collect()
    };
    let difference = relative_difference(&field(&other), &field(&faer));
    assert!(difference < tolerance, "{name} {overrides:?}: Γ3 rows differ by {difference:e}");
    let (k_faer, k_other) = (faer.solution.kkt.max, other.solution.kkt.max);
    if built.method_name() == "newton" {
        assert!(k_other <= 1e-10, "{name}: KKT residual {k_other:e} (faer: {k_faer:e})");
    }
}

#[test]
fn example_7_2_is_faers_with_uzawa_and_newton() {
    on_processes("example_7_2_is_faers_with_uzawa_and_newton", || {
        same_contact("paper-7.2.toml", &[], 1e-9);
        same_contact("paper-7.2.toml", &["solver.method=\"newton\""], 1e-9);
    });
}

#[test]
fn indentation_3d_is_faers() {
    on_processes("indentation_3d_is_faers", || {
        same_contact("indentation-3d.toml", &[], 1e-9);
    });
}

/// Two materials by region, both stiffness tensors from the library (PZT-5A on silicon).
#[test]
fn a_film_on_silicon_is_faers() {
    on_processes("a_film_on_silicon_is_faers", || {
        same_contact("film-on-silicon.toml", &[], 1e-9);
    });
}

/// The quarter model: Γ3 nodes on the symmetry planes' rollers, both methods.
#[test]
fn the_quarter_model_is_faers() {
    on_processes("the_quarter_model_is_faers", || {
        same_contact("indentation-quarter.toml", &[], 1e-9);
        same_contact("indentation-quarter.toml", &["solver.method=\"uzawa\""], 1e-9);
    });
}

/// A block turned by 30° about z on normal rollers (turned nodal frames in the global
/// system) under a pressure on its turned end: MUMPS's solution and the iterative route's
/// (the rollers' constrained components kept as identity rows) as faer's.
#[test]
fn rollers_on_turned_faces_are_faers() {
    on_processes("rollers_on_turned_faces_are_faers", || {
        let mesh = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes/box-turned.msh");
        let roller = |part: &str| {
            format!("[[boundary.support]]\nparts = [\"{part}\"]\nfix = [\"normal\"]\n")
        };
        let text = format!(
            "[mesh]\nfile = {:?}\n[material]\nlaw = \"linear\"\nyoung = 58.7\npoisson = 0.39\ne31 = -5.4\ne33 = 15.8\ne15 = 12.3\neps0 = 8.885e-3\nbeta11_rel = 916.0\nbeta33_rel = 830.0\n[boundary]\ngrounded = [\"bottom\"]\n[[boundary.traction]]\nparts = [\"x1\"]\nf2 = [-0.26, -0.15, 0.0]\n{}{}{}",
            mesh.display().to_string(),
            roller("x0"),
            roller("y0"),
            roller("bottom")
        );
        let problem =
            Case::from_text("turned.toml".as_ref(), &text, &[]).unwrap().problem().unwrap();
        let faer = solve_without_contact(&problem, Box::new(LdltSolver::new())).unwrap();
        let mumps = solve_without_contact(&problem, petsc_solver()).unwrap();
        let difference = relative_difference(&mumps.x, &faer.x);
        assert!(difference < 1e-10, "‖x_mumps − x_faer‖/‖x_faer‖ = {difference:e}");
        assert!(mumps.relative_residual < 1e-10, "residual {:e}", mumps.relative_residual);
        // The iterative route, with a held row for each constrained component of the rollers.
        let krylov = solve_without_contact(&problem, krylov_solver()).unwrap();
        let difference = relative_difference(&krylov.x, &faer.x);
        assert!(difference < 1e-8, "‖x_krylov − x_faer‖/‖x_faer‖ = {difference:e}");
    });
}

/// Floating electrodes: the force sensor (an open-circuit electrode on Γ3) as faer solves
/// it, on every process count (the process owning the electrode's row assembles every cell
/// touching it).
#[test]
fn floating_electrodes_are_faers_on_every_process_count() {
    on_processes("floating_electrodes_are_faers_on_every_process_count", || {
        let built = case("force-sensor.toml", &["loading.depths=[0.005, 0.01]"]).build().unwrap();
        let curve = |solver| match Run::solve(&built, solver, &|_| {}).unwrap() {
            Run::Path(path) if path.converged() => path.curve,
            _ => panic!("force-sensor.toml: not a converged path"),
        };
        let (faer, mumps) = (curve(Box::new(LdltSolver::new())), curve(petsc_solver()));
        for (a, b) in faer.iter().zip(&mumps) {
            let phi = (a.potentials[0] - b.potentials[0]).abs() / a.potentials[0].abs();
            let force = (a.force[1] - b.force[1]).abs() / a.force[1].abs();
            assert!(phi < 1e-9 && force < 1e-9, "step {}: {phi:e} {force:e}", a.step);
        }
    });
}

/// The iterative route of `solver.linear = "iterative"` at the default tolerance.
fn krylov_solver() -> Box<dyn LinearSolver> {
    Box::new(PetscSolver::iterative(petsc::KRYLOV_RTOL, petsc::KRYLOV_MAX_ITERATIONS).unwrap())
}

/// GMRES with the field split over u and ϕ and GAMG on each: the coupled system's solution
/// to 1e−8 of faer's, in 2D (Hencky's law by secant steps, a solve each) and in 3D (the bar
/// of cases/bar-3d.toml under its pressure, without contact). On more than one process the
/// multigrid's Galerkin products keep no intermediates by default (`-mat_product_clear`).
#[test]
fn the_krylov_route_solves_the_coupled_system_as_faer_does() {
    on_processes("the_krylov_route_solves_the_coupled_system_as_faer_does", || {
        for name in ["paper-7.2.toml", "bar-3d.toml"] {
            let problem = case(name, &[]).problem().unwrap();
            let faer = solve_without_contact(&problem, Box::new(LdltSolver::new())).unwrap();
            let krylov = solve_without_contact(&problem, krylov_solver()).unwrap();
            let difference = relative_difference(&krylov.x, &faer.x);
            assert!(difference < 1e-8, "{name}: ‖x_krylov − x_faer‖/‖x_faer‖ = {difference:e}");
            assert_eq!(faer.timings.linear, LinearRoute::default(), "{name}: faer is direct");
            let route = &krylov.timings.linear;
            assert_eq!(route.kind, "iterative");
            assert_eq!(route.krylov.as_deref(), Some("gmres"));
            assert_eq!(route.preconditioner.as_deref(), Some("fieldsplit (u: gamg, phi: gamg)"));
            // On more than one process GAMG's products keep no intermediates by default.
            let clear = petsc::option("-mat_product_clear").unwrap();
            let several = petsc::rank_and_size().1 > 1;
            assert_eq!(clear.as_deref(), several.then_some("true"), "-mat_product_clear");
            let solves = krylov.timings.solver.solve_count;
            assert!(solves >= 1);
            assert_eq!(route.krylov_iterations.len(), solves, "{name}: one count per solve");
            let most = petsc::KRYLOV_MAX_ITERATIONS;
            assert!(route.krylov_iterations.iter().all(|&k| (1..most).contains(&k)), "{route:?}");
        }
    });
}

/// The solve with a patched matrix on the iterative route (the whole system's Newton step;
/// on one process, as the LU it is checked against is whole): J = K but on every seventh row, where its diagonal is doubled and
/// its other entries made unsymmetric (× 1 + 0.01 (column mod 3)), and P = K with those rows'
/// diagonal doubled, written over PETSc's K for the preconditioner and K's rows written back
/// after. The solution is the sparse LU's of J whole to 1e−8, and the next solve with K is
/// faer's again. The system keeps no copy of K: its products are PETSc's, equal to those of
/// faer's K to 1e−12.
#[test]
fn a_solve_with_a_patched_matrix_is_the_lu_s_and_leaves_k_as_it_was() {
    on(&[1], "a_solve_with_a_patched_matrix_is_the_lu_s_and_leaves_k_as_it_was", || {
        let problem = case("bar-3d.toml", &[]).problem().unwrap();
        let faer = solve_without_contact(&problem, Box::new(LdltSolver::new())).unwrap();
        let dofs = DofMap::new(&problem).unwrap();
        let mut system = CoupledSystem::new(&problem, dofs, &[], krylov_solver()).unwrap();
        let zero = vec![0.0; system.dofs().n_total()];
        let moduli = secant_moduli(&problem, system.dofs(), &zero).unwrap();
        system.factorize(&problem, &moduli, &[]).unwrap();
        assert!(system.matrix().is_none(), "a copy of K beside PETSc's");
        let ldlt = Box::new(LdltSolver::new());
        let mut reference =
            CoupledSystem::new(&problem, DofMap::new(&problem).unwrap(), &[], ldlt).unwrap();
        reference.factorize(&problem, &moduli, &[]).unwrap();
        let matrix = reference.matrix().unwrap().clone();
        let probe: Vec<f64> = (0..matrix.n()).map(|k| (k as f64 * 0.37).sin()).collect();
        let difference = relative_difference(&system.product(&probe).unwrap(), &matrix.mul(&probe));
        assert!(difference < 1e-12, "PETSc's K x against faer's K x: {difference:e}");
        let rows = RowMatrix::from_symmetric_rows(&matrix, patched);
        let (jacobian, preconditioner) = (patch(&rows, 2.0, 0.01), patch(&rows, 2.0, 0.0));
        let b = system.rhs().to_vec();
        let mut x = b.clone();
        system.solve_unsymmetric((&jacobian, &preconditioner), &mut x, 1e-10).unwrap();
        let expected = patched_lu(&matrix, &jacobian, &b);
        let difference = relative_difference(&x, &expected);
        assert!(difference < 1e-8, "‖x − x_LU‖/‖x_LU‖ = {difference:e}");
        assert!(relative_difference(&expected, &b) > 1e-3, "J is not K: the test must tell");
        let again = system.solve(Some(&vec![0.0; b.len()])).unwrap();
        let difference = relative_difference(&again, &faer.x);
        assert!(difference < 1e-8, "K's solve after: ‖x − x_faer‖/‖x_faer‖ = {difference:e}");
    });
}

/// An operator other than its preconditioner on the iterative route (Hencky's whole tangent
/// preconditioned by the floored one): K factorised, then corrected to K′ = K with every
/// entry whose row and column are ≡ 0 (mod 5) times 1.1 (K′ quasi-definite as K is; the
/// correction K′ − K on those rows, [`RowMatrix::difference`]). Solves are the sparse LU's
/// of K′ to 1e−8 and products K′ x to 1e−12; a patched solve (J's rows from K′ on every
/// seventh row, unsymmetric) is the LU's of K′ with J's rows — the correction's rows outside
/// the patch kept — to 1e−8. With the Krylov
/// solver freed ([`LinearSolver::release_work`]), the next solve makes it again: the LU's of
/// K′ still, the solver's names kept. On one process, as the LU it is checked against is
/// whole; on the 3D indentation's coarse mesh, as two sparse LUs of the bar took 45 s.
#[test]
fn a_corrected_operator_is_solved_and_multiplied_as_the_lu_of_it() {
    on(&[1], "a_corrected_operator_is_solved_and_multiplied_as_the_lu_of_it", || {
        let coarse = ["mesh.file=\"../meshes/indent-3d-h0.05.msh\""];
        let problem = case("indentation-3d.toml", &coarse).problem().unwrap();
        let dofs = DofMap::new(&problem).unwrap();
        let moduli = secant_moduli(&problem, &dofs, &vec![0.0; dofs.n_total()]).unwrap();
        let assembler = Assembler::new(&problem, dofs.clone(), &[], None).unwrap();
        let (k, _) = assembler.matrix(&problem, &moduli, &[]).unwrap();
        let pattern = assembler.pattern();
        let scaled = k.lower_entries().map(|(i, j, v)| match i % 5 == 0 && j % 5 == 0 {
            true => 1.1 * v,
            false => v,
        });
        let corrected = pattern.matrix(scaled.collect()).unwrap();
        let mut solver = PetscSolver::iterative(petsc::KRYLOV_RTOL, 2000).unwrap();
        solver.analyze(pattern, &dofs.signs()).unwrap();
        solver.factorize(&k).unwrap();
        let correction = RowMatrix::difference(&corrected, &k).unwrap();
        let rows = (0..k.n()).filter(|&r| correction.has_row(r)).count();
        assert_eq!(rows, k.n().div_ceil(5), "the rows ≡ 0 (mod 5)");
        solver.unsymmetric().unwrap().correct(pattern, correction).unwrap();
        let n = k.n();
        let b: Vec<f64> = (0..n).map(|k| (k as f64 * 0.37).sin()).collect();
        let lu = |a: &RowMatrix| {
            let mut x = b.clone();
            RowLu::default().solve(a, &mut x).unwrap();
            x
        };
        let expected = lu(&RowMatrix::from_symmetric(&corrected));
        assert!(relative_difference(&corrected.mul(&b), &k.mul(&b)) > 1e-3, "K′ is not K");
        let product = solver.unsymmetric().unwrap().product(&b).unwrap();
        let difference = relative_difference(&product, &corrected.mul(&b));
        assert!(difference < 1e-12, "PETSc's K′ x against K′ x: {difference:e}");
        let solve = |solver: &mut PetscSolver| {
            let mut x = b.clone();
            solver.solve_in_place(&mut x).unwrap();
            relative_difference(&x, &expected)
        };
        let difference = solve(&mut solver);
        assert!(difference < 1e-8, "‖x − x_LU(K′)‖/‖x_LU(K′)‖ = {difference:e}");
        let route = solver.route();
        solver.release_work().unwrap();
        let difference = solve(&mut solver);
        assert!(
            difference < 1e-8,
            "after release_work: ‖x − x_LU(K′)‖/‖x_LU(K′)‖ = {difference:e}"
        );
        assert_eq!(
            (solver.route().krylov, solver.route().preconditioner),
            (route.krylov, route.preconditioner)
        );
        let patched = |r: usize| r.is_multiple_of(7);
        let mut jacobian = RowMatrix::from_symmetric_rows(&corrected, patched);
        let preconditioner = jacobian.clone();
        for r in (0..n).filter(|&r| patched(r)) {
            let (columns, values) = jacobian.row_mut(r);
            for (c, v) in columns.iter().zip(values) {
                *v *= 1.0 + 0.01 * (c % 3) as f64;
            }
        }
        let whole = Patched::new(pattern, &jacobian, &preconditioner).unwrap();
        let expected = lu(&whole.whole_jacobian(&corrected).unwrap());
        let mut x = b.clone();
        let unsymmetric = solver.unsymmetric().unwrap();
        unsymmetric.solve_unsymmetric(whole, &mut x, petsc::KRYLOV_RTOL).unwrap();
        let difference = relative_difference(&x, &expected);
        assert!(difference < 1e-8, "patched: ‖x − x_LU‖/‖x_LU‖ = {difference:e}");
    });
}

/// Hencky's whole tangent beyond e·t0 on the iterative route (Example 7.2, t0 = 1e−3, the
/// exact solver), preconditioned by the floored tangent: where B̌ loses its signs the Krylov
/// solve fails (the iterative route cannot see a pivot of the wrong sign) and the floored
/// tangent takes the step, as on faer's route, whose factorisation sees the sign: the same
/// outer steps, floored alike, the same criteria to 1e−6 (four outer steps, short of
/// convergence on both routes). The failing solve, the check of the signs, stops at its cap
/// (450 iterations here, not the 2,000 of a solve).
#[test]
fn hencky_s_tangent_falls_back_to_the_floor_on_the_iterative_route() {
    on_processes("hencky_s_tangent_falls_back_to_the_floor_on_the_iterative_route", || {
        let overrides = ["material.t0=1e-3", "solver.method=\"newton\"", "solver.max_outer=4"];
        let built = case("paper-7.2.toml", &overrides).build().unwrap();
        let run = |solver| contact_run(&built, solver).solution;
        let (faer, krylov) = (run(Box::new(LdltSolver::new())), run(krylov_solver()));
        assert!(faer.floored_steps > 0, "the test must see the floor: {}", faer.floored_steps);
        assert_eq!(krylov.floored_steps, faer.floored_steps);
        let difference = relative_difference(&krylov.outer_history, &faer.outer_history);
        assert!(difference < 1e-6, "outer criteria differ by {difference:e}");
        assert_eq!(krylov.outer_history.len(), 4, "{:?}", krylov.outer_history);
        // The failing solve is the check's, capped far below a solve's budget.
        let most = krylov.timings.linear.krylov_iterations.iter().max().copied().unwrap_or(0);
        assert!(most < petsc::KRYLOV_MAX_ITERATIONS / 2, "a solve took {most} iterations");
    });
}

/// Uzawa's method on the iterative route: Example 7.2's solution and Γ3 fields as with
/// faer's LDLᵀ (to the Krylov tolerance carried through Uzawa's iterations).
#[test]
fn uzawa_on_the_krylov_route_is_faers() {
    on_processes("uzawa_on_the_krylov_route_is_faers", || {
        same_contact_with("paper-7.2.toml", &[], 1e-7, krylov_solver);
    });
}

/// A Krylov solve that stops short of its tolerance is an error that names its iterations
/// and the options that change them.
#[test]
fn a_krylov_solve_short_of_its_tolerance_says_so() {
    on_processes("a_krylov_solve_short_of_its_tolerance_says_so", || {
        let problem = case("paper-7.2.toml", &[]).problem().unwrap();
        let solver = Box::new(PetscSolver::iterative(1e-12, 2).unwrap());
        let error = solve_without_contact(&problem, solver).unwrap_err().to_string();
        assert!(error.contains("stopped after 2 iterations"), "{error}");
        assert!(error.contains("(relative tolerance 1e-12, at most 2 iterations)"), "{error}");
        assert!(error.contains("-ksp_max_it"), "{error}");
    });
}

/// A Newton step's solve that does not converge with an earlier step's preconditioner is
/// solved again with one made from scratch for its own matrix (GAMG's setup for new values
/// keeps the interpolations of its first, which need not serve): K factorised, a first
/// patched solve (J₁ = K but on every seventh row, its diagonal × 1.5) sets the
/// preconditioner up and is kept, a second (J₂ with those rows' diagonals × 10⁴ and
/// unsymmetric entries) keeps it and does not converge within a cap set just above what a
/// preconditioner made from scratch for J₂ needs (measured first on a solver made for J₂
/// alone). The second solve's count is both attempts' and its answer the LU's of J₂.
#[test]
fn a_solve_short_with_a_kept_preconditioner_is_solved_with_one_made_anew() {
    on(&[1], "a_solve_short_with_a_kept_preconditioner_is_solved_with_one_made_anew", || {
        let problem = case("bar-3d.toml", &[]).problem().unwrap();
        let system = |most: usize| {
            let solver = Box::new(PetscSolver::iterative(petsc::KRYLOV_RTOL, most).unwrap());
            let dofs = DofMap::new(&problem).unwrap();
            let mut system = CoupledSystem::new(&problem, dofs, &[], solver).unwrap();
            let zero = vec![0.0; system.dofs().n_total()];
            let moduli = secant_moduli(&problem, system.dofs(), &zero).unwrap();
            system.factorize(&problem, &moduli, &[]).unwrap();
            system
        };
        let ldlt = Box::new(LdltSolver::new());
        let mut reference =
            CoupledSystem::new(&problem, DofMap::new(&problem).unwrap(), &[], ldlt).unwrap();
        let zero = vec![0.0; reference.dofs().n_total()];
        let moduli = secant_moduli(&problem, reference.dofs(), &zero).unwrap();
        reference.factorize(&problem, &moduli, &[]).unwrap();
        let matrix = reference.matrix().unwrap().clone();
        let rows = RowMatrix::from_symmetric_rows(&matrix, patched);
        let (first, second) = (patch(&rows, 1.5, 0.0), patch(&rows, 1e4, 0.01));
        let b = reference.rhs().to_vec();
        let solve = |system: &mut CoupledSystem, j: &RowMatrix| {
            let mut x = b.clone();
            system.solve_unsymmetric((j, j), &mut x, 1e-10).map(|()| x)
        };
        // What a preconditioner made from scratch for J₂ needs: the solver made again.
        let mut alone = system(petsc::KRYLOV_MAX_ITERATIONS);
        alone.release_work().unwrap();
        solve(&mut alone, &second).unwrap();
        let own = *alone.timings().linear.krylov_iterations.last().unwrap();
        let cap = own + 2;
        let mut capped = system(cap);
        solve(&mut capped, &first).unwrap();
        let x = solve(&mut capped, &second).unwrap();
        let counts = capped.timings().linear.krylov_iterations;
        assert_eq!(counts.last(), Some(&(cap + own)), "the kept attempt and the new: {counts:?}");
        let difference = relative_difference(&x, &patched_lu(&matrix, &second, &b));
        assert!(difference < 1e-8, "‖x − x_LU‖/‖x_LU‖ = {difference:e}");
    });
}

//! The assembled matrix of B̌: symmetric, u-block positive definite, ϕ-block negative
//! definite after Dirichlet elimination; one numeric factorisation serves many solves.

use super::common::{PAPER_UNITS, SI, paper_problem, perturbed_square, pzt, read_mesh};
use piezocontact::assembly::{Assembler, internal_force};
use piezocontact::dofs::DofMap;
use piezocontact::linalg::default_solver;
use piezocontact::material::ElasticLaw;
use piezocontact::mesh::Mesh;
use piezocontact::problem::{BodyLoads, Boundary, Problem, constant_vector};
use piezocontact::system::CoupledSystem;

fn clamped_problem(mesh: Mesh, clamped: &str, grounded: &str) -> Problem {
    let dim = mesh.dim();
    let boundary = Boundary {
        clamped: vec![mesh.part_index(clamped).unwrap()],
        grounded: vec![mesh.part_index(grounded).unwrap()],
        ..Boundary::default()
    };
    let loads =
        BodyLoads { f0: Some(constant_vector(vec![0.0, -1.0, 0.0][..dim].to_vec())), q0: None };
    Problem::new(mesh, pzt(dim, ElasticLaw::Linear), boundary, loads).unwrap()
}

#[test]
fn matrix_is_symmetric_and_its_blocks_are_definite() {
    for problem in [
        clamped_problem(perturbed_square(5, 0.3), "left", "bottom"),
        clamped_problem(read_mesh("cube.msh"), "bottom", "top"),
    ] {
        let assembler =
            Assembler::new(&problem, DofMap::new(&problem).unwrap(), &[], None).unwrap();
        let g = vec![problem.material(0).elasticity().unwrap().mu1; problem.mesh.n_cells()];
        let (matrix, _) = assembler.matrix(&problem, &g, &[]).unwrap();
        // The matrix stores its lower triangle only, so it is symmetric by construction if it
        // holds the right values: its product must equal the element-by-element product of the
        // full element matrices (whose symmetry the assembly's unit test checks).
        let n = matrix.n();
        let x: Vec<f64> = (0..n).map(|i| ((i * 7) as f64).sin()).collect();
        let stored = matrix.mul(&x);
        let global = assembler.dofs().expand(&x);
        let (full, scale) = internal_force(&problem, assembler.dofs(), &global, &g).unwrap();
        let full = assembler.restrict(&full);
        let size = scale.iter().copied().fold(0.0, f64::max);
        for (k, (a, b)) in stored.iter().zip(&full).enumerate() {
            assert!((a - b).abs() < 1e-12 * size, "row {k}: stored {a}, element by element {b}");
        }
        let n_u = assembler.dofs().n_free_u();
        assert!(matrix.block(0..n_u, 1.0).unwrap().is_positive_definite().unwrap());
        assert!(matrix.block(n_u..n, -1.0).unwrap().is_positive_definite().unwrap());
        assert!(!matrix.is_positive_definite().unwrap(), "the whole matrix is indefinite");
    }
}

/// The parallel assembly sums every entry in element order whatever the number of threads:
/// one thread and two threads give the same matrix and lifting to the last bit, in 2D (with a
/// prescribed displacement, so that the lifting is not zero, and nodal blocks) and in 3D.
#[test]
fn parallel_assembly_equals_serial_assembly_to_the_last_bit() {
    // 20000 cells: every group of node-disjoint cells spans several parallel tasks.
    let mut square = clamped_problem(perturbed_square(100, 0.3), "left", "bottom");
    square.boundary.clamped_value = Some(constant_vector(vec![1e-3, -2e-3]));
    let cube = clamped_problem(read_mesh("cube.msh"), "bottom", "top");
    for (problem, block_nodes) in [(square, vec![3, 17, 40]), (cube, vec![])] {
        let assemble = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| {
                let dofs = DofMap::new(&problem).unwrap();
                let assembler = Assembler::new(&problem, dofs, &block_nodes, None).unwrap();
                let g: Vec<f64> = (0..problem.mesh.n_cells())
                    .map(|c| {
                        problem.material(0).elasticity().unwrap().mu1
                            * (1.0 + 0.1 * (c as f64).sin())
                    })
                    .collect();
                let blocks = vec![[[2.0, 0.5, 0.0], [0.5, 3.0, 0.0], [0.0; 3]]; block_nodes.len()];
                let (matrix, lifting) = assembler.matrix(&problem, &g, &blocks).unwrap();
                (matrix.lower_entries().collect::<Vec<_>>(), lifting)
            })
        };
        let (serial, parallel) = (assemble(1), assemble(2));
        assert!(serial.1.iter().any(|l| *l != 0.0) || block_nodes.is_empty());
        assert_eq!(serial.0.len(), parallel.0.len());
        for (a, b) in serial.0.iter().zip(&parallel.0) {
            assert_eq!((a.0, a.1, a.2.to_bits()), (b.0, b.1, b.2.to_bits()));
        }
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&serial.1), bits(&parallel.1));
    }
}

#[test]
fn one_numeric_factorisation_serves_many_solves() {
    let problem = clamped_problem(read_mesh("paper-rectangle.msh"), "clamp", "load");
    let mut system =
        CoupledSystem::new(&problem, DofMap::new(&problem).unwrap(), &[], default_solver())
            .unwrap();
    let g = vec![problem.material(0).elasticity().unwrap().mu1; problem.mesh.n_cells()];
    system.factorize(&problem, &g, &[]).unwrap();
    let first = system.solve(None).unwrap();
    let n = system.dofs().n_free();
    for k in 1..=4 {
        let extra = vec![k as f64 * 1e-3; n];
        let x = system.solve(Some(&extra)).unwrap();
        assert_ne!(x, first);
    }
    let t = system.timings();
    assert_eq!((t.solver.numeric_count, t.solver.solve_count), (1, 5));
    // The solution without extra is kept: given again without a solve, until the loads or
    // the factorisation change.
    assert_eq!(system.solve(None).unwrap(), first);
    assert_eq!(system.timings().solver.solve_count, 5);
    // The loads scaled: f̌ assembled again with the factor, the factorisation kept; the same
    // factor again changes nothing and the solution is kept.
    system.scale_loads(&problem, 2.0);
    let doubled = system.solve(None).unwrap();
    assert_eq!(system.timings().solver.solve_count, 6);
    system.scale_loads(&problem, 2.0);
    assert_eq!(system.solve(None).unwrap(), doubled);
    assert_eq!(system.timings().solver.solve_count, 6);
    let size = first.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let apart = doubled.iter().zip(&first).fold(0.0_f64, |m, (d, f)| m.max((d - 2.0 * f).abs()));
    assert!(size > 0.0 && apart <= 1e-12 * size, "{apart:e} of {size:e}");
    system.factorize(&problem, &g, &[]).unwrap();
    system.solve(None).unwrap();
    assert_eq!(system.timings().solver.solve_count, 7);
}

#[test]
fn the_solution_does_not_depend_on_the_unit_system() {
    use piezocontact::dofs::DofMap;
    use piezocontact::system::solve_without_contact;
    // (m, GPa, C, GV) as the paper cases, and SI (m, Pa, C, V).
    let without_contact = |units| {
        let mut p = paper_problem(48, 8, units, ElasticLaw::Linear);
        p.boundary.contact.clear();
        p
    };
    let (paper, si) = (without_contact(PAPER_UNITS), without_contact(SI));
    let solve = |p| solve_without_contact(p, default_solver()).unwrap().x;
    let (x_paper, x_si) = (solve(&paper), solve(&si));
    let dofs = DofMap::new(&paper).unwrap();
    let n = paper.mesh.n_nodes();
    let max_u = (0..2 * n).map(|k| x_paper[k].abs()).fold(0.0, f64::max);
    let max_phi = (0..n).map(|a| x_paper[dofs.phi(a)].abs()).fold(0.0, f64::max);
    assert!(max_u > 0.1 && max_phi > 0.1, "the load must deform and polarise the bar");
    for a in 0..n {
        for i in 0..2 {
            let k = dofs.u(a, i);
            assert!((x_paper[k] - x_si[k]).abs() < 1e-10 * max_u, "u at node {a}");
        }
        let k = dofs.phi(a);
        assert!((x_paper[k] * 1e9 - x_si[k]).abs() < 1e-10 * max_phi * 1e9, "phi at node {a}");
    }
}

/// Without contact, Hencky's law beyond its elasticity limit is followed by secant steps: on
/// the cantilever with t0 lowered so that the bending passes it, every step of the path
/// satisfies the equations of the true law, R = F_int(x; g(x)) − f̌ = 0 on the free rows, to
/// 1e-8 of ‖f̌‖, where the linear law's solution misses them; the clamp holds the load.
#[test]
fn a_solve_without_contact_follows_hencky_s_law_beyond_its_limit() {
    use piezocontact::assembly::{load_vector, secant_moduli};
    use piezocontact::dofs::CONSTRAINED;
    use piezocontact::run::Run;
    let sets = ["material.law=\"hencky\"", "material.t0=1e-7"];
    let built =
        super::common::committed_case("cantilever-load-factors.toml", &sets).build().unwrap();
    let Run::StaticPath(path) = Run::solve(&built, default_solver(), &|_| {}).unwrap() else {
        panic!("not a path without contact");
    };
    let problem = &built.problem;
    let dofs = &path.last.solution.dofs;
    let residual = |x: &[f64], factor: f64| {
        let g = secant_moduli(problem, dofs, x).unwrap();
        let (f_int, _) = internal_force(problem, dofs, x, &g).unwrap();
        let f = load_vector(problem, dofs, factor);
        let free = (0..dofs.n_total()).filter(|&k| dofs.free_index(k) != CONSTRAINED);
        let (r, b) =
            free.fold((0.0, 0.0), |(r, b), k| (r + (f_int[k] - f[k]).powi(2), b + f[k].powi(2)));
        (r / b).sqrt()
    };
    eprintln!("factorisations of the last step: {}", path.last.solution.factorisations);
    assert!(path.last.solution.factorisations > 2, "{}", path.last.solution.factorisations);
    for ((x, row), factor) in path.states().zip(&path.curve).zip([0.5, 1.0, 1.5, 2.0]) {
        let r = residual(x, factor);
        eprintln!("step {}: relative residual of the true law {r:.2e}", row.step);
        assert!(r < 1e-8, "step {}: relative residual of the true law {r:.2e}", row.step);
        let applied = 0.001 * 2.0 * factor;
        assert!((row.reaction[1] - applied).abs() < 1e-8 * applied, "{row:?}");
    }
    // The linear law's solution, scaled, does not satisfy Hencky's equations here.
    let linear =
        super::common::committed_case("cantilever-load-factors.toml", &[]).build().unwrap();
    let Run::StaticPath(linear) = Run::solve(&linear, default_solver(), &|_| {}).unwrap() else {
        panic!("not a path without contact");
    };
    let x = linear.states().last().unwrap().to_vec();
    assert!(residual(&x, 2.0) > 1e-3, "{}", residual(&x, 2.0));
}

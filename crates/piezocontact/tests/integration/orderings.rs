//! Orderings and threads of the sparse factorisation (model §13): every ordering and thread
//! count gives the same solution to round-off; in 3D nested dissection's factor is the
//! smaller and the automatic choice takes it, in 2D AMD alone.

use piezocontact::algorithm::{ContactSolution, solve_contact_with};
use piezocontact::case::Built;
use piezocontact::dofs::DofMap;
use piezocontact::linalg::{LdltSolver, Ordering};
use piezocontact::system::CoupledSystem;

/// cases/indentation-3d.toml on its coarse committed mesh.
fn indentation() -> Built {
    let mesh = "mesh.file=\"../meshes/indent-3d-h0.05.msh\"";
    super::common::committed_case("indentation-3d.toml", &[mesh]).build().unwrap()
}

fn solve(built: &Built, ordering: Ordering, threads: usize) -> ContactSolution {
    let solver = Box::new(LdltSolver::with_ordering(ordering).on_threads(threads));
    let model = built.model.as_ref().unwrap();
    let solution =
        solve_contact_with(&built.problem, model, &built.settings, solver, &|_| {}).unwrap();
    assert!(solution.converged(), "{:?}", solution.failure);
    solution
}

/// The factor's entries and the ordering's name of the analysis of `built`'s matrix.
fn factor(built: &Built, ordering: Ordering) -> (usize, &'static str) {
    let solver = Box::new(LdltSolver::with_ordering(ordering));
    let dofs = DofMap::new(&built.problem).unwrap();
    let system = CoupledSystem::new(&built.problem, dofs, &[], solver).unwrap();
    let stats = system.solver_stats();
    (stats.factor_len, stats.ordering)
}

/// max |a − b| / max |a|.
fn relative(a: &[f64], b: &[f64]) -> f64 {
    let size = a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max) / size
}

#[test]
fn orderings_and_threads_give_the_same_3d_solution() {
    let built = indentation();
    let reference = solve(&built, Ordering::Amd, 1);
    for (ordering, threads) in [
        (Ordering::Amd, 2),
        (Ordering::NestedDissection, 1),
        (Ordering::NestedDissection, 2),
        (Ordering::Auto, 2),
    ] {
        let solution = solve(&built, ordering.clone(), threads);
        let d = relative(&reference.x, &solution.x);
        // Round-off of a factorisation in another order: the KKT tolerance is 1e−10.
        assert!(d < 1e-10, "{ordering:?} on {threads} threads: {d:e}");
        assert!(solution.kkt.max <= 1e-10, "{:?}", solution.kkt);
    }
}

#[test]
fn nested_dissection_gives_the_smaller_3d_factor_and_auto_keeps_it() {
    let built = indentation();
    let factor = |ordering: Ordering| factor(&built, ordering);
    let (amd, nd, auto) =
        (factor(Ordering::Amd), factor(Ordering::NestedDissection), factor(Ordering::Auto));
    println!("factor entries: amd {amd:?}, nd {nd:?}, auto {auto:?}");
    assert_eq!((amd.1, nd.1), ("amd", "nd"));
    assert!(nd.0 < amd.0, "nested dissection {} against AMD {}", nd.0, amd.0);
    assert_eq!(auto, nd);
}

/// On a 2D pattern `auto` is AMD: the same factor, from one analysis (model §13).
#[test]
fn auto_orders_a_2d_pattern_by_amd() {
    let built = super::common::committed_case("paper-7.2.toml", &["mesh.nx=48", "mesh.ny=8"])
        .build()
        .unwrap();
    let factor = |ordering: Ordering| factor(&built, ordering);
    assert_eq!(factor(Ordering::Auto), factor(Ordering::Amd));
    assert_eq!(factor(Ordering::Amd).1, "amd");
}

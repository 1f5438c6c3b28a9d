//! The exact solver (semismooth Newton on the condensed Γ3 problem) against the paper's
//! Uzawa algorithm run tightly: the same discrete solution on every kind of contact the model
//! has, a KKT residual at round-off, independence of r, Hencky's law active, and the Schur
//! complement read off the factor.

use super::common::{
    PAPER_UNITS, arch_problem, committed_case, paper_model, paper_problem,
    paper_problem_with_contact, paper_settings, pzt, read_mesh,
};
use piezocontact::algorithm::condensed::Guess;
use piezocontact::algorithm::newton::{self, Newton};
use piezocontact::algorithm::{ContactSolution, Settings, solve_contact};
use piezocontact::assembly::{Beyond, Linearisation};
use piezocontact::contact::ContactModel;
use piezocontact::contact::law::Regularization;
use piezocontact::dofs::DofMap;
use piezocontact::linalg::default_solver;
use piezocontact::material::ElasticLaw;
use piezocontact::problem::{BodyLoads, Boundary, Problem, constant_vector};
use piezocontact::system::CoupledSystem;

/// Newton with the KKT tolerance 1e−10 and r = `r_per_young`·E.
fn newton(r_per_young: f64) -> Settings {
    condensing(r_per_young, 2000)
}

/// Newton as [`newton`], condensing at most `max_condensed` Γ3 nodes.
fn condensing(r_per_young: f64, max_condensed: usize) -> Settings {
    let young = PAPER_UNITS.stress(58.7102);
    let r = r_per_young * young;
    let parameters = newton::Parameters {
        r,
        tol: 1e-10,
        max_inner: 100,
        max_condensed: Some(max_condensed),
        guess: Guess::Nearest(max_condensed),
    };
    Settings::new(Newton::new(parameters), 100)
}

fn solve(problem: &Problem, model: &ContactModel, settings: &Settings) -> ContactSolution {
    let solution = solve_contact(problem, model, settings).unwrap();
    assert!(solution.converged(), "{:?}", solution.failure);
    solution
}

/// The largest relative differences between two solutions of one problem: u and ϕ on all
/// nodes, σ_ν, λ_f and ϕ on Γ3, each relative to the largest value of its field.
fn differences(problem: &Problem, a: &ContactSolution, b: &ContactSolution) -> [f64; 5] {
    let dofs = DofMap::new(problem).unwrap();
    let (n, dim) = (problem.mesh.n_nodes(), problem.mesh.dim());
    let relative = |pairs: Vec<(f64, f64)>| {
        let size = pairs.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
        let gap = pairs.iter().map(|p| (p.0 - p.1).abs()).fold(0.0, f64::max);
        if size > 0.0 { gap / size } else { gap }
    };
    let u = (0..n).flat_map(|k| (0..dim).map(move |c| (k, c)));
    let u = relative(u.map(|(k, c)| (a.x[dofs.u(k, c)], b.x[dofs.u(k, c)])).collect());
    let phi = relative((0..n).map(|k| (a.x[dofs.phi(k)], b.x[dofs.phi(k)])).collect());
    let sigma = relative(a.sigma_nu.iter().copied().zip(b.sigma_nu.iter().copied()).collect());
    let lambda_f = relative(
        a.state
            .lambda_f
            .iter()
            .zip(&b.state.lambda_f)
            .flat_map(|(p, q)| (0..3).map(move |c| (p[c], q[c])))
            .collect(),
    );
    let surface = &b.surface;
    let phi3 = relative(
        (0..surface.len())
            .map(|i| (surface.phi(&dofs, &a.x, i), surface.phi(&dofs, &b.x, i)))
            .collect(),
    );
    [u, phi, sigma, lambda_f, phi3]
}

fn show(d: &[f64]) -> String {
    d.iter().map(|v| format!("{v:.1e}")).collect::<Vec<_>>().join(", ")
}

/// Newton and Uzawa run to ε = ε_fp = 1e−12 agree to 1e−7 and Newton's KKT residual is at
/// most 1e−10.
fn assert_agree(problem: &Problem, model: &ContactModel, what: &str) {
    let exact = solve(problem, model, &newton(0.25));
    assert!(exact.kkt.max <= 1e-10, "{what}: {:?}", exact.kkt);
    // Uzawa's distance to the discrete solution falls in proportion to ε (measured: 10× per
    // decade from 1e−12 to 1e−14, λ_f of the g_p = 0.05 layer at 96×16 going 1.6e−7, 1.7e−8,
    // 1.7e−9): ε = 1e−14 puts it well below the 1e−7 asked of the comparison.
    let mut tight = paper_settings(PAPER_UNITS, 1e-14);
    tight.max_outer = 400;
    let uzawa = solve(problem, model, &tight);
    let d = differences(problem, &exact, &uzawa);
    println!(
        "{what}: Newton {:?} steps, KKT {:.1e}; Uzawa KKT {:.1e}; differences u, ϕ, σ_ν, λ_f, ϕ|Γ3 {}",
        exact.inner_iterations,
        exact.kkt.max,
        uzawa.kkt.max,
        show(&d)
    );
    assert!(d.iter().all(|v| *v < 1e-7), "{what}: {d:?}");
}

/// PV1 and an active compliance and conduction layer on the nx × ny bar: its problem.
fn agree_on_pv1_and_the_layer(nx: usize, ny: usize) -> Problem {
    let problem = paper_problem(nx, ny, PAPER_UNITS, ElasticLaw::Linear);
    let mesh = format!("{nx}x{ny}");
    assert_agree(&problem, &paper_model(None, 0.0, PAPER_UNITS), &format!("{mesh} PV1"));
    // An active compliance and conduction layer: p_ν, h_ν and ψ φ_L act at the solution.
    let layer = paper_model(Some((0.2, 0.2)), 0.05, PAPER_UNITS);
    assert_agree(&problem, &layer, &format!("{mesh} PV2, g_p = 0.05"));
    problem
}

/// PV1 and the layer; PV2 with R = identity and the mollifier; µ per part.
fn agree_on_the_bar(nx: usize, ny: usize) {
    let problem = agree_on_pv1_and_the_layer(nx, ny);
    let mesh = format!("{nx}x{ny}");
    let pv2 = paper_model(Some((0.6, 1.0)), 0.0, PAPER_UNITS);
    assert_agree(&problem, &pv2, &format!("{mesh} PV2, R = identity"));
    let mut mollified = pv2.clone();
    mollified.friction.as_mut().unwrap().regularization = Regularization::Mollifier { radius: 1.0 };
    assert_agree(&problem, &mollified, &format!("{mesh} PV2, R = mollifier"));
    // µ per part: 0.6 on [2,6]×{0}, 0.1 on [6,10]×{0}.
    let split = paper_problem_with_contact(
        nx,
        ny,
        PAPER_UNITS,
        ElasticLaw::Linear,
        &[("left", "[2,6]x{0}"), ("right", "[6,10]x{0}")],
    );
    let mut per_part = pv2.clone();
    let part = |name: &str| split.mesh.part_index(name).unwrap();
    per_part.friction.as_mut().unwrap().mu_parts = vec![(part("left"), 0.6), (part("right"), 0.1)];
    assert_agree(&split, &per_part, &format!("{mesh} PV2, µ per part"));
}

#[test]
fn newton_agrees_with_tight_uzawa_on_the_paper_bar_48x8() {
    agree_on_the_bar(48, 8);
}

/// On the finer bar, PV1 and the case where every law acts at the solution (friction,
/// compliance and conduction in the g_p = 0.05 layer): Uzawa's distance to the discrete
/// solution is largest there (λ_f 1.7e−8 at ε = 1e−14, against 7e−9 for the other PV2 cases,
/// which the 48 × 8 bar checks and which took 185 of this test's 220 s).
#[test]
fn newton_agrees_with_tight_uzawa_on_the_paper_bar_96x16() {
    agree_on_pv1_and_the_layer(96, 16);
}

#[test]
fn newton_agrees_with_tight_uzawa_on_a_curved_face_and_in_3d() {
    let arch = arch_problem();
    let mut model = paper_model(Some((0.3, 0.5)), 0.0, PAPER_UNITS);
    model.compliance.gap = 0.02;
    assert_agree(&arch, &model, "arch PV2");

    // The unit cube hanging from its top face, pulled down and sideways by its weight onto a
    // foundation 0.01 below its bottom face.
    let mesh = read_mesh("cube.msh");
    let part = |n: &str| mesh.part_index(n).unwrap();
    let boundary = Boundary {
        clamped: vec![part("top")],
        grounded: vec![part("top")],
        contact: vec![part("bottom")],
        ..Boundary::default()
    };
    let loads = BodyLoads { f0: Some(constant_vector(vec![1.0, 0.5, -5.0])), q0: None };
    let cube = Problem::new(mesh, pzt(3, ElasticLaw::Linear), boundary, loads).unwrap();
    let mut model = paper_model(Some((0.3, 0.3)), 0.0, PAPER_UNITS);
    model.compliance.gap = 0.01;
    assert_agree(&cube, &model, "cube PV2");
}

/// A strong conduction: cases/block-3d.toml on the unit cube with k_e = 1, g_p = 0.01 and
/// ϕ0 = 220 GV, where nodes settle at the kink of ψ (u_ν = g_a) and Newton's iterates cycle
/// from either start (model §11), round a loop of 5 steps. Each start is left once it has
/// gone round its loop twice (without that, both go round it for 100 steps: 124 steps in all
/// instead of 34), and the continuation in k_e converges to a KKT residual at round-off, and
/// the solution is the one Uzawa tends to: Uzawa's distance to it falls in proportion to ε
/// (measured on u, ϕ, σ_ν: 9.4e−3, 7.8e−4, 4.8e−2 at ε = 1e−6; 1.1e−4, 9.0e−6, 6.1e−4 at
/// 1e−8), so it must fall at least tenfold and end below 2e−3.
#[test]
fn a_strong_conduction_converges_by_continuation_to_the_solution_uzawa_tends_to() {
    let built = |method: &[&str]| {
        let sets = [
            "mesh.file=\"../meshes/cube.msh\"",
            "contact.problem=\"PV2\"",
            "friction.mu=0",
            "conductivity.ke=1",
            "contact.penetration=0.01",
            "conductivity.phi0=220",
        ];
        committed_case("block-3d.toml", &[&sets, method].concat()).build().unwrap()
    };
    let exact = built(&[]);
    let (problem, model) = (&exact.problem, exact.model.as_ref().unwrap());
    let newton = solve(problem, model, &exact.settings);
    assert!(newton.kkt.max <= 1e-10, "{:?}", newton.kkt);
    let loop_of_5 = |h: &[f64]| (0..5).all(|k| (h[k + 5] - h[k]).abs() <= 1e-6 * h[k]);
    assert!(loop_of_5(&newton.inner_history[0]), "{:?}", newton.inner_history);
    assert!(newton.inner_iterations[0] <= 60, "{:?}", newton.inner_iterations);
    let distance = |eps: &str| {
        let (eps, eps_fp) = (format!("solver.eps={eps}"), format!("solver.eps_fp={eps}"));
        let sets = ["solver.method=\"uzawa\"", &eps, &eps_fp, "solver.max_inner=100000"];
        let uzawa = built(&sets);
        let d = differences(problem, &solve(problem, model, &uzawa.settings), &newton);
        println!("{eps}: differences u, ϕ, σ_ν, λ_f, ϕ|Γ3 {}", show(&d));
        // λ_f = 0 by the law (µ = 0): both are round-off, relative to round-off.
        [d[0], d[1], d[2], d[4]].into_iter().fold(0.0, f64::max)
    };
    let (loose, tight) = (distance("1e-6"), distance("1e-8"));
    assert!(tight <= loose / 10.0 && tight < 2e-3, "Uzawa's distance {loose:e}, then {tight:e}");
}

/// Where the continuation in k_e stops short — the paper's bar with k_e = 5, ϕ0 = 200 GV and
/// g_p = 0.01, where no stage past θ ≈ 0.574 converges (model §11) — the run fails and names
/// the fraction θ of k_e its iterate solves: with k_e scaled by θ the iterate's KKT residual
/// is at round-off, with the whole k_e it is not. A higher solver.max_inner would not lengthen
/// a stage, and the message does not ask for it; with solver.max_inner = 1 no stage converges,
/// and it does.
#[test]
fn a_continuation_that_stops_short_names_the_fraction_its_iterate_solves() {
    use piezocontact::algorithm::residual::assess;
    let run = |max_inner: &str| {
        let sets = [
            "solver.method=\"newton\"",
            max_inner,
            "conductivity.ke=5",
            "conductivity.phi0=200",
            "contact.penetration=0.01",
        ];
        let built = committed_case("paper-7.2.toml", &sets).build().unwrap();
        let model = built.model.as_ref().unwrap();
        let solution = solve_contact(&built.problem, model, &built.settings).unwrap();
        let failure = solution.failure.as_ref().map(|e| e.to_string()).unwrap_or_default();
        (built, solution, failure)
    };
    let (_, _, failure) = run("solver.max_inner=1");
    assert!(failure.contains("raise solver.max_inner (now 1)"), "{failure}");
    assert!(failure.contains("did not converge even with 1/4096 of k_e"), "{failure}");
    let (built, solution, failure) = run("solver.max_inner=100");
    let (problem, model) = (&built.problem, built.model.as_ref().unwrap());
    assert!(!failure.contains("raise solver.max_inner"), "{failure}");
    let theta: f64 = failure
        .split("θ = ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next()?.parse().ok())
        .unwrap_or_else(|| panic!("no θ in: {failure}"));
    assert!(!solution.converged() && 0.0 < theta && theta < 1.0, "{failure}");
    let c = built.settings.method.complementarity_constant();
    let mut part = model.clone();
    part.conduction.as_mut().unwrap().ke *= theta;
    let (at_part, _) = assess(problem, &part, c, &solution.view()).unwrap();
    let (at_whole, _) = assess(problem, model, c, &solution.view()).unwrap();
    println!(
        "θ = {theta}: KKT residual {:.1e} with θ k_e, {:.1e} with k_e",
        at_part.max, at_whole.max
    );
    assert!(at_part.max <= 1e-10 && at_whole.max > 1e-6, "{at_part:?}, {at_whole:?}");
}

/// r = 1e−3 E, 0.25 E and 1e3 E give one solution.
#[test]
fn the_exact_solution_does_not_depend_on_r() {
    let problem = paper_problem(96, 16, PAPER_UNITS, ElasticLaw::Linear);
    for model in [
        paper_model(Some((0.6, 1.0)), 0.0, PAPER_UNITS),
        paper_model(Some((0.2, 0.2)), 0.05, PAPER_UNITS),
    ] {
        let reference = solve(&problem, &model, &newton(0.25));
        for r in [1e-3, 1e3] {
            let other = solve(&problem, &model, &newton(r));
            let d = differences(&problem, &other, &reference);
            println!("r = {r:e} E: {:?} steps, differences {}", other.inner_iterations, show(&d));
            assert!(d.iter().all(|v| *v < 1e-9), "r = {r} E: {d:?}");
        }
    }
}

/// Hencky's law by Newton (model §13): on the paper's bar with t0 = 6e−2 the law softens
/// (g < µ1) where the bar bends most, with its tangent positive everywhere (‖ε^D‖² < e·t0,
/// (h1)(b)). The consistent tangent converges quadratically — at most 6 factorisations, each
/// criterion at most a constant times the square of the last — to the true nonlinear
/// equations (KKT residual with the true law), where the secant took 11.
#[test]
fn hencky_s_law_by_newton_converges_quadratically() {
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Hencky { t0: 6e-2 });
    for model in
        [paper_model(None, 0.0, PAPER_UNITS), paper_model(Some((0.2, 0.2)), 0.05, PAPER_UNITS)]
    {
        let solution = solve(&problem, &model, &newton(0.25));
        let dofs = &solution.dofs;
        let linearisation =
            Linearisation::tangent(&problem, dofs, &solution.x, Beyond::Floored).unwrap();
        let elasticity = *problem.material(0).elasticity().unwrap();
        let softened = linearisation.moduli.iter().filter(|g| **g < elasticity.mu1).count();
        let positive = linearisation.tangent.iter().all(|(_, b, d)| {
            let t: f64 = d.iter().flatten().map(|v| v * v).sum();
            *b == 4.0 * elasticity.dg(t)
        });
        let history = &solution.outer_history;
        println!("{}: {softened} softened elements, criteria {history:?}", model.name());
        assert!(softened > 0 && positive, "{softened} softened, tangent positive: {positive}");
        assert!(
            solution.timings.solver.numeric_count <= 6,
            "{}",
            solution.timings.solver.numeric_count
        );
        assert_eq!(solution.floored_steps, 0, "the tangent is not floored where it is positive");
        assert!(solution.kkt.max <= 1e-10, "{:?}", solution.kkt);
        // Past 1e−11 the criterion is round-off.
        for pair in history[1..].windows(2).filter(|w| w[1] > 1e-11) {
            assert!(pair[1] <= 100.0 * pair[0] * pair[0], "not quadratic: {history:?}");
        }
    }
}

/// The elements of a solution where Hencky's law is not positive along ε^D (t > e·t0).
fn beyond_e_t0(problem: &Problem, solution: &ContactSolution) -> usize {
    let whole = Linearisation::tangent(problem, &solution.dofs, &solution.x, Beyond::Whole);
    let el = *problem.material(0).elasticity().unwrap();
    let t = |d: &[[f64; 3]; 3]| d.iter().flatten().map(|v| v * v).sum::<f64>();
    whole
        .unwrap()
        .tangent
        .iter()
        .map(|(_, _, d)| t(d))
        .filter(|t| el.g(*t) + 2.0 * el.dg(*t) * t < 0.0)
        .count()
}

/// Beyond t = e·t0 Hencky's law is not positive along ε^D; Newton's iteration keeps its whole
/// tangent there (model §13). On the paper's bar with t0 = 1e−3 (PV1), where a part of the bar
/// is beyond e·t0 at the solution, it converges superlinearly — the last criterion under 1e−2
/// times the one before — in at most 12 factorisations; the floored tangent, used everywhere
/// before, converged linearly in 89.
#[test]
fn hencky_s_whole_tangent_converges_beyond_e_t0() {
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Hencky { t0: 1e-3 });
    let solution = solve(&problem, &paper_model(None, 0.0, PAPER_UNITS), &newton(0.25));
    let (beyond, history) = (beyond_e_t0(&problem, &solution), &solution.outer_history);
    let count = solution.timings.solver.numeric_count;
    println!("{beyond} elements beyond e·t0, {count} factorisations, criteria {history:?}");
    assert!(beyond > 0 && solution.floored_steps == 0, "{beyond}, {}", solution.floored_steps);
    assert!(count <= 12 && solution.kkt.max <= 1e-10, "{count}, {:?}", solution.kkt);
    let last = &history[history.len() - 2..];
    assert!(last[1] < 1e-2 * last[0], "not superlinear: {history:?}");
}

/// Where Newton's iteration on Hencky's law beyond e·t0 fails, the floored tangent takes a
/// step. PV2 with µ = k_e = 0.6, t0 = 1e−3: the criterion grows at step 8; after one floored
/// step Newton converges in at most 15 steps (the floored tangent kept to the end took 51).
/// PV1, t0 = 1e−4: the whole tangent gives B̌ a pivot of the wrong sign, B̌ is factorised
/// again with the floored one (a factorisation more than the steps that factorise), and after
/// a second failure the floor stays; the steps are then chord steps on the floored
/// factorisation while they contract: at most a third of the steps factorise (58
/// factorisations in 56 steps before, 14 in 54 with the chord). Both converge to the true
/// equations.
#[test]
fn newton_on_hencky_s_law_falls_back_to_the_floored_tangent() {
    for (t0, model, most_steps) in [
        (1e-3, paper_model(Some((0.6, 0.6)), 0.0, PAPER_UNITS), 15),
        (1e-4, paper_model(None, 0.0, PAPER_UNITS), 100),
    ] {
        let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Hencky { t0 });
        let solution = solve(&problem, &model, &newton(0.25));
        let (outer, count) = (solution.outer_iterations(), solution.timings.solver.numeric_count);
        let (floored, chords) = (solution.floored_steps, solution.chord_steps);
        println!(
            "t0 = {t0}: {outer} steps, {floored} floored, {chords} chord, {count} factorisations"
        );
        assert!(floored > 0 && outer <= most_steps, "{floored} floored, {outer} steps");
        let factorising = outer - chords;
        assert!(t0 > 1e-4 || count > factorising, "no factorisation refused: {count}, {outer}");
        assert!(t0 > 1e-4 || 3 * count <= outer, "{count} factorisations in {outer} steps");
        assert!(t0 < 1e-3 || chords == 0, "a chord step before the floor stays: {chords}");
        let tangent = piezocontact::report::summary::hencky_tangent(&solution, false);
        let said = tangent.contains(&format!("{chords} of them chord steps"));
        assert!(t0 > 1e-4 || said, "{tangent}");
        assert!(solution.kkt.max <= 1e-10, "{:?}", solution.kkt);
    }
}

/// With t0 small, Hencky's secant modulus drops below µ1 in much of the bar: the outer loop
/// refactorises until the moduli settle, and the KKT residual with the true law reaches 1e−10.
#[test]
fn the_exact_solver_converges_with_hencky_active() {
    let t0 = 1e-6;
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Hencky { t0 });
    for model in
        [paper_model(None, 0.0, PAPER_UNITS), paper_model(Some((0.2, 0.2)), 0.05, PAPER_UNITS)]
    {
        let solution = solve(&problem, &model, &newton(0.25));
        let dofs = &solution.dofs;
        let g = piezocontact::assembly::secant_moduli(&problem, dofs, &solution.x).unwrap();
        let softened =
            g.iter().filter(|g| **g < 0.99 * problem.material(0).elasticity().unwrap().mu1).count();
        println!(
            "{}: {softened} softened elements, {} outer steps, {} factorisations, KKT {:.1e}",
            model.name(),
            solution.outer_iterations(),
            solution.timings.solver.numeric_count,
            solution.kkt.max
        );
        assert!(softened > problem.mesh.n_cells() / 10, "Hencky is not active ({softened})");
        assert!(solution.timings.solver.numeric_count > 1);
        assert!(solution.kkt.max <= 1e-10, "{:?}", solution.kkt);
    }
}

/// A gap large enough that only the middle of Γ3 touches, and room for only a few more
/// nodes than touch: with equal gaps the first guess is the first nodes of Γ3, which misses
/// the contact zone's right end. The condensation trades clear nodes for touching ones and
/// ends at the solution of the whole condensation — with ϕ condensed (g_p > 0, conduction),
/// and with Hencky's law refactorising in the outer loop.
#[test]
fn a_grown_condensation_gives_the_whole_condensation_s_solution() {
    for (law, mut model, gap) in [
        (ElasticLaw::Linear, paper_model(Some((0.2, 0.2)), 0.05, PAPER_UNITS), 1.3),
        (ElasticLaw::Hencky { t0: 1e-6 }, paper_model(None, 0.0, PAPER_UNITS), 3.0),
    ] {
        model.compliance.gap = gap;
        let problem = paper_problem(48, 8, PAPER_UNITS, law);
        let whole = solve(&problem, &model, &newton(0.25));
        let n3 = whole.surface.len();
        let touching = whole.sigma_nu.iter().filter(|s| **s < 0.0).count();
        let max_condensed = touching + 4;
        let last = (0..n3).rfind(|&i| whole.sigma_nu[i] < 0.0).unwrap();
        assert!(last >= max_condensed, "the first guess holds the contact zone");
        let grown = solve(&problem, &model, &condensing(0.25, max_condensed));
        let d = differences(&problem, &grown, &whole);
        println!(
            "{}: {touching} of {n3} touch; {} condensed, {} factorisations and {} solves (whole: {}, {}), differences {}",
            model.name(),
            grown.condensed_nodes,
            grown.timings.solver.numeric_count,
            grown.timings.solver.solve_count,
            whole.timings.solver.numeric_count,
            whole.timings.solver.solve_count,
            show(&d)
        );
        assert!(grown.condensed_nodes < n3 && grown.kkt.max <= 1e-10, "{:?}", grown.kkt);
        // A growth costs a factorisation, or a solve per new unknown where that is cheaper.
        let counts =
            |s: &ContactSolution| (s.timings.solver.numeric_count, s.timings.solver.solve_count);
        let ((numeric, solves), (whole_numeric, whole_solves)) = (counts(&grown), counts(&whole));
        assert!(numeric > whole_numeric || solves > whole_solves + 2);
        assert!(d.iter().all(|v| *v < 1e-9), "{d:?}");
    }
}

/// The trailing block of the factor with the Γ3 unknowns last is the Schur complement
/// K_cc − K_ci K_ii⁻¹ K_ic, here computed column by column with solves of the interior.
#[test]
fn the_schur_complement_read_off_the_factor_is_the_schur_complement() {
    let problem = paper_problem(24, 4, PAPER_UNITS, ElasticLaw::Linear);
    let dofs = DofMap::new(&problem).unwrap();
    let surface = piezocontact::contact::ContactSurface::new(&problem, &dofs).unwrap();
    let last: Vec<usize> = surface
        .nodes
        .iter()
        .flat_map(|&a| [dofs.u(a, 0), dofs.u(a, 1), dofs.phi(a)])
        .map(|g| dofs.free_index(g))
        .filter(|&k| k != piezocontact::dofs::CONSTRAINED)
        .collect();
    let mut system = CoupledSystem::with_last(&problem, dofs, &last, default_solver()).unwrap();
    let g = vec![problem.material(0).elasticity().unwrap().mu1; problem.mesh.n_cells()];
    system.factorize(&problem, &g, &[]).unwrap();
    let schur = system.schur_complement().unwrap();
    // K in dense form, then S = K_cc − K_ci K_ii⁻¹ K_ic by Gaussian elimination of the
    // interior block.
    let matrix = system.matrix().unwrap();
    let n = matrix.n();
    let mut k = vec![vec![0.0; n]; n];
    for (i, j, v) in matrix.lower_entries() {
        k[i][j] = v;
        k[j][i] = v;
    }
    let mut order: Vec<usize> = (0..n).filter(|i| !last.contains(i)).collect();
    order.extend(&last);
    let mut a: Vec<Vec<f64>> =
        order.iter().map(|&i| order.iter().map(|&j| k[i][j]).collect()).collect();
    let interior = n - last.len();
    for p in 0..interior {
        let pivot = a[p][p];
        for i in p + 1..n {
            let factor = a[i][p] / pivot;
            if factor != 0.0 {
                for j in p..n {
                    a[i][j] -= factor * a[p][j];
                }
            }
        }
    }
    // Each entry against the geometric mean of its diagonal entries: the u and ϕ blocks
    // differ by orders of magnitude.
    let diagonal: Vec<f64> = (0..last.len()).map(|i| a[interior + i][interior + i].abs()).collect();
    for i in 0..last.len() {
        for j in 0..last.len() {
            let expected = a[interior + i][interior + j];
            assert!(
                (schur.get(i, j) - expected).abs() <= 1e-10 * (diagonal[i] * diagonal[j]).sqrt(),
                "S[{i}][{j}] = {} against {expected}",
                schur.get(i, j)
            );
        }
    }
}

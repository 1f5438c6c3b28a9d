//! Algorithms 1–4 on the paper's examples and a curved Γ3: the discrete KKT conditions of
//! contact and friction at convergence, the force balance, the limit PV2 → PV1, the active
//! compliance/conduction layer, the Hencky law, unit independence, and factorisation counts.

use super::common::{PAPER_UNITS, Units, paper_model, paper_problem, paper_settings};
use piezocontact::algorithm::residual::assess;
use piezocontact::algorithm::{ContactSolution, Settings, solve_contact};
use piezocontact::assembly::MassNorm;
use piezocontact::contact::{ContactModel, NodeStatus};
use piezocontact::dofs::DofMap;
use piezocontact::material::ElasticLaw;
use piezocontact::problem::Problem;

fn solve(problem: &Problem, model: &ContactModel, settings: &Settings) -> ContactSolution {
    let solution = solve_contact(problem, model, settings).unwrap();
    assert!(solution.converged(), "{:?}", solution.failure);
    solution
}

/// Checks the discrete contact and friction conditions of model §10 and the force balance;
/// returns the numbers of stick, slip and (PV1) contact nodes.
fn assert_kkt(
    problem: &Problem,
    model: &ContactModel,
    settings: &Settings,
    solution: &ContactSolution,
) -> [usize; 3] {
    let dofs = DofMap::new(problem).unwrap();
    let surface = &solution.surface;
    let max_u = (0..problem.mesh.n_nodes())
        .map(|a| (0..2).map(|c| solution.x[dofs.u(a, c)].powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    let tol = 1e-6 * max_u;
    let max_lambda = solution.state.lambda_c.iter().copied().fold(0.0, f64::max);
    let (mut stick, mut slip, mut contact) = (0, 0, 0);
    for i in 0..surface.len() {
        let (u_nu, u_tau) = surface.split(&dofs, &solution.x, i);
        let lambda_c = solution.state.lambda_c[i];
        let lambda_f = solution.state.lambda_f[i];
        let rho = model.compliance.stop(surface.gap[i]);
        assert!(u_nu <= rho + tol, "node {i}: u_nu {u_nu} > {rho}");
        assert!(lambda_c >= 0.0);
        assert!(
            (lambda_c * (u_nu - rho)).abs() <= tol * max_lambda.max(1.0),
            "complementarity at {i}"
        );
        let norm = |v: [f64; 3]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
        let s = solution.s[i];
        assert!(
            norm(lambda_f) <= s * (1.0 + 1e-6) + 1e-12,
            "node {i}: |lambda_f| {} > s {s}",
            norm(lambda_f)
        );
        match solution.status[i] {
            NodeStatus::Stick => {
                stick += 1;
                assert!(norm(u_tau) <= tol, "stick node {i} slides by {}", norm(u_tau));
            }
            NodeStatus::Slip if s > 0.0 => {
                slip += 1;
                assert!((norm(lambda_f) - s).abs() <= 1e-6 * s, "slip node {i} below the bound");
                // λ_f points along u_τ (σ_τ = −λ_f opposes the slip) when the node slides.
                if norm(u_tau) > tol {
                    let cos = (0..3).map(|c| lambda_f[c] * u_tau[c]).sum::<f64>()
                        / (norm(lambda_f) * norm(u_tau));
                    assert!(cos > 1.0 - 1e-6, "slip node {i}: λ_f not along u_τ (cos {cos})");
                }
            }
            NodeStatus::Contact | NodeStatus::Slip => contact += 1,
            NodeStatus::Separated => assert!(solution.sigma_nu[i] == 0.0),
        }
    }
    assert!(stick + slip + contact > 0, "no node in contact");
    let (kkt, balance) =
        assess(problem, model, settings.method.complementarity_constant(), &solution.view())
            .unwrap();
    assert!(kkt.max < 1e-5, "{kkt:?}");
    assert!(balance.imbalance < 1e-6, "{balance:?}");
    let applied = balance.applied[1];
    assert!(
        applied < 0.0 && balance.contact[1] > 0.0 && balance.contact[1] < -applied,
        "{balance:?}"
    );
    [stick, slip, contact]
}

#[test]
fn kkt_conditions_and_force_balance_hold_on_the_paper_cases() {
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Linear);
    let settings = paper_settings(PAPER_UNITS, 1e-9);
    for (pv2, expect) in
        [(None, "contact"), (Some((0.6, 1.0)), "stick and slip"), (Some((0.2, 0.2)), "slip")]
    {
        let model = paper_model(pv2, 0.0, PAPER_UNITS);
        let solution = solve(&problem, &model, &settings);
        let [stick, slip, contact] = assert_kkt(&problem, &model, &settings, &solution);
        println!("{pv2:?}: {stick} stick, {slip} slip, {contact} contact nodes");
        match expect {
            "contact" => assert!(contact > 0 && stick + slip == 0),
            "stick and slip" => assert!(stick > 0 && slip > 0),
            _ => assert!(slip > 0),
        }
    }
}

#[test]
fn kkt_conditions_hold_on_a_curved_contact_face() {
    let problem = super::common::arch_problem();
    let mut model = paper_model(Some((0.3, 0.5)), 0.0, PAPER_UNITS);
    model.compliance.gap = 0.02;
    let settings = paper_settings(PAPER_UNITS, 1e-9);
    let solution = solve(&problem, &model, &settings);
    // The normals follow the arc: tilted near the ends, vertical in the middle.
    let tilt = solution.surface.normal.iter().map(|n| n[0].abs()).fold(0.0, f64::max);
    assert!(tilt > 0.4, "normals do not follow the arc ({tilt})");
    let statuses: Vec<NodeStatus> = solution.status.clone();
    assert!(
        statuses.contains(&NodeStatus::Separated)
            && statuses.iter().any(|s| *s != NodeStatus::Separated)
    );
    let [stick, slip, _] = assert_kkt(&problem, &model, &settings, &solution);
    assert!(stick + slip > 0);
}

/// ‖a − b‖ / ‖b‖ in L2(Ω) over u and ϕ.
fn distance(problem: &Problem, a: &[f64], b: &[f64]) -> f64 {
    let dofs = DofMap::new(problem).unwrap();
    let d: Vec<f64> = a.iter().zip(b).map(|(p, q)| p - q).collect();
    let mass = MassNorm::new(problem).unwrap();
    (mass.squared(problem, &dofs, &d) / mass.squared(problem, &dofs, b)).sqrt()
}

/// Theorem 4.1: ‖x(µ, k_e) − x_PV1‖ ≤ c (µ + k_e). With µ = k_e = 0, PV2 is PV1. The
/// values are in the asymptotic range: for µ ≥ 0.1 most of Γ3 sticks and the distance grows
/// more slowly than µ (it saturates), which the bound allows.
#[test]
fn pv2_tends_to_pv1_at_least_linearly() {
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Linear);
    let settings = paper_settings(PAPER_UNITS, 1e-10);
    let pv1 = solve(&problem, &paper_model(None, 0.0, PAPER_UNITS), &settings);
    let zero = solve(&problem, &paper_model(Some((0.0, 0.0)), 0.0, PAPER_UNITS), &settings);
    assert!(distance(&problem, &zero.x, &pv1.x) < 1e-7, "PV2(0, 0) differs from PV1");
    let values = [0.04, 0.02, 0.01, 0.005, 0.0025];
    let d: Vec<f64> = values
        .iter()
        .map(|&m| {
            distance(
                &problem,
                &solve(&problem, &paper_model(Some((m, m)), 0.0, PAPER_UNITS), &settings).x,
                &pv1.x,
            )
        })
        .collect();
    println!("mu = ke: {values:?}\n‖x − x_PV1‖/‖x_PV1‖: {d:?}");
    assert!(d.windows(2).all(|w| w[1] < w[0]), "not decreasing: {d:?}");
    let n = values.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) =
        values.iter().zip(&d).map(|(m, e)| (m.ln(), e.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let slope = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum::<f64>()
        / lx.iter().map(|x| (x - mx).powi(2)).sum::<f64>();
    println!("fitted slope {slope:.3}");
    assert!(slope >= 0.95, "slope {slope}");
}

/// With g_p > 0 the compliance p_ν and the conduction ψ act: ϕ on the conducting part of
/// Γ3 moves towards ϕ0 as k_e grows, and the fixed point still converges.
#[test]
fn an_active_conduction_layer_pulls_phi_towards_phi0() {
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Linear);
    let settings = paper_settings(PAPER_UNITS, 1e-9);
    let dofs = DofMap::new(&problem).unwrap();
    let runs: Vec<(ContactModel, ContactSolution)> = [0.0, 0.1, 1.0]
        .iter()
        .map(|&ke| {
            let model = paper_model(Some((0.2, ke)), 0.05, PAPER_UNITS);
            let solution = solve(&problem, &model, &settings);
            (model, solution)
        })
        .collect();
    let phi0 = runs[0].0.phi0;
    let gap = runs[0].0.compliance.gap;
    let mut conducting = 0;
    for i in 0..runs[0].1.surface.len() {
        let node = runs[0].1.surface.nodes[i];
        let (u_nu, _) = runs[2].1.surface.split(&dofs, &runs[2].1.x, i);
        if u_nu <= gap || dofs.free_index(dofs.phi(node)) == piezocontact::dofs::CONSTRAINED {
            continue;
        }
        conducting += 1;
        let gaps: Vec<f64> =
            runs.iter().map(|(_, s)| (s.surface.phi(&dofs, &s.x, i) - phi0).abs()).collect();
        assert!(gaps[1] < gaps[0] && gaps[2] < gaps[1], "node {i}: |phi - phi0| = {gaps:?}");
    }
    assert!(conducting > 10, "only {conducting} conducting nodes");
    for (model, solution) in &runs {
        let (kkt, balance) =
            assess(&problem, model, settings.method.complementarity_constant(), &solution.view())
                .unwrap();
        assert!(kkt.max < 1e-5 && balance.imbalance < 1e-6, "{kkt:?} {balance:?}");
    }
}

/// With t0 below the strains, g varies over the body: the outer loop updates the secant,
/// refactors once per outer step while g changes, and converges to a solution of the
/// equations with the true nonlinear F.
#[test]
fn the_hencky_law_converges_to_the_true_nonlinear_equations() {
    // ‖ε^D‖² reaches ≈ 0.09 here: t0 = 0.04 softens the most strained elements and keeps t < e·t0,
    // where (h1)(b) (g + 2g't > 0) holds.
    let t0 = 0.04;
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Hencky { t0 });
    let settings = paper_settings(PAPER_UNITS, 1e-9);
    let dofs = DofMap::new(&problem).unwrap();
    for pv2 in [None, Some((0.6, 1.0))] {
        let model = paper_model(pv2, 0.0, PAPER_UNITS);
        let solution = solve(&problem, &model, &settings);
        let g = piezocontact::assembly::secant_moduli(&problem, &dofs, &solution.x).unwrap();
        let mu1 = problem.material(0).elasticity().unwrap().mu1;
        let softened = g.iter().filter(|&&v| v < mu1 * (1.0 - 1e-3)).count();
        assert!(softened >= 10, "g is constant: the test does not exercise Hencky");
        let t_max = (0..problem.mesh.n_cells())
            .map(|c| {
                let (eps, _) =
                    piezocontact::assembly::cell_gradients::<2, 3>(&problem, &dofs, &solution.x, c)
                        .unwrap();
                piezocontact::material::deviator_norm_squared(&eps)
            })
            .fold(0.0, f64::max);
        assert!(t_max < std::f64::consts::E * t0, "t = {t_max} leaves the range of (h1)(b)");
        let t = &solution.timings;
        println!(
            "{}: {softened} softened elements, t_max/t0 = {:.2}, {} outer steps, {} factorisations",
            model.name(),
            t_max / t0,
            solution.outer_iterations(),
            t.solver.numeric_count
        );
        assert!(
            t.solver.numeric_count > 1 && t.solver.numeric_count <= solution.outer_iterations(),
            "{t:?}"
        );
        let (kkt, _) =
            assess(&problem, &model, settings.method.complementarity_constant(), &solution.view())
                .unwrap();
        assert!(kkt.equilibrium_u < 1e-6 && kkt.max < 1e-5, "{kkt:?}");
    }
}

/// The linear material needs one numeric factorisation for the whole run; Uzawa iterations
/// are solves only.
#[test]
fn one_factorisation_serves_the_whole_linear_run() {
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Hencky { t0: 1.8 });
    let settings = paper_settings(PAPER_UNITS, 1e-4);
    for pv2 in [None, Some((0.6, 1.0))] {
        let solution = solve(&problem, &paper_model(pv2, 0.0, PAPER_UNITS), &settings);
        let t = solution.timings;
        assert_eq!(t.solver.numeric_count, 1);
        assert_eq!(t.solver.solve_count, solution.inner_iterations.iter().sum::<usize>());
    }
}

/// One physical problem in (m, GPa, C, GV) and in SI gives one answer when both are solved
/// tightly, although the mixed norms of (6.12) differ by 18 orders of magnitude. ε = 1e−12:
/// σ_ν comes from λ_c, which the increment test (6.12) does not measure; at ε = 1e−10 the two
/// runs' σ_ν still differ by 2e−6, at 1e−12 by 2e−8.
#[test]
fn the_contact_solution_does_not_depend_on_the_unit_system() {
    use super::common::SI;
    let solve_in = |units: Units| {
        let problem = paper_problem(48, 8, units, ElasticLaw::Linear);
        let solution = solve(
            &problem,
            &paper_model(Some((0.2, 0.2)), 0.05, units),
            &paper_settings(units, 1e-12),
        );
        (problem, solution)
    };
    let (paper, a) = solve_in(PAPER_UNITS);
    let (_, b) = solve_in(SI);
    let dofs = DofMap::new(&paper).unwrap();
    let n = paper.mesh.n_nodes();
    let max_u = (0..2 * n).map(|k| a.x[k].abs()).fold(0.0, f64::max);
    let max_phi = (0..n).map(|k| a.x[dofs.phi(k)].abs()).fold(0.0, f64::max);
    for k in 0..n {
        for c in 0..2 {
            assert!((a.x[dofs.u(k, c)] - b.x[dofs.u(k, c)]).abs() < 1e-6 * max_u, "u at node {k}");
        }
        assert!(
            (a.x[dofs.phi(k)] * 1e9 - b.x[dofs.phi(k)]).abs() < 1e-6 * max_phi * 1e9,
            "phi at node {k}"
        );
    }
    let max_sigma = a.sigma_nu.iter().map(|v| v.abs()).fold(0.0, f64::max);
    for (sa, sb) in a.sigma_nu.iter().zip(&b.sigma_nu) {
        assert!((sa * 1e9 - sb).abs() < 1e-6 * max_sigma * 1e9);
    }
}

/// Inner and outer iteration counts of the paper's algorithm (ε = ε_fp = 1e−4) at three
/// mesh sizes (the paper gives none). Example 7.1 stops after 2 outer steps, as the paper says:
/// without penetration only the compliance at Uzawa's round-off penetration is lagged, Hencky's
/// law stays linear, and the second step solves nearly the first one's problem again, from the
/// same cold start and in as many iterations. Every solve meets both stopping
/// rules, and the augmented Lagrangian with r = 0.25 E needs no more iterations on finer meshes.
#[test]
fn iteration_counts_at_three_mesh_sizes() {
    println!("{:>8} {:>4} {:>6} {:>30}", "mesh", "", "outer", "inner per outer step");
    let mut counts: Vec<(usize, usize)> = Vec::new(); // PV2: (outer, largest inner)
    for (nx, ny) in [(48, 8), (96, 16), (192, 32)] {
        let problem = paper_problem(nx, ny, PAPER_UNITS, ElasticLaw::Hencky { t0: 1.8 });
        for pv2 in [None, Some((0.6, 1.0))] {
            let model = paper_model(pv2, 0.0, PAPER_UNITS);
            let solution = solve(&problem, &model, &paper_settings(PAPER_UNITS, 1e-4));
            let inner = &solution.inner_iterations;
            println!(
                "{:>8} {:>4} {:>6} {:>30}",
                format!("{nx}x{ny}"),
                model.name(),
                solution.outer_iterations(),
                format!("{inner:?}")
            );
            assert_eq!(inner.len(), solution.outer_iterations());
            assert!(*solution.outer_history.last().unwrap() < 1e-4);
            for history in &solution.inner_history {
                assert!(*history.last().unwrap() < 1e-4, "an inner loop stopped early");
            }
            if pv2.is_none() {
                assert_eq!(solution.outer_iterations(), 2);
                assert_eq!(inner[0], inner[1], "the second step is nearly the first one again");
            } else {
                counts.push((solution.outer_iterations(), *inner.iter().max().unwrap()));
            }
        }
    }
    let (coarse, fine) = (counts[0], counts[2]);
    assert!(fine.0.abs_diff(coarse.0) <= 1, "outer counts {counts:?}");
    assert!(fine.1 <= coarse.1, "the inner counts grow with refinement: {counts:?}");
}

/// Nonlocal Coulomb friction: s = µ|Rσ_ν| with R the mollifier average over a radius a; a
/// radius below the node spacing is the local law; µ may differ per Γ3 part.
#[test]
fn nonlocal_friction_and_friction_per_part() {
    use piezocontact::contact::law::Regularization;
    let problem = paper_problem(48, 8, PAPER_UNITS, ElasticLaw::Linear);
    let settings = paper_settings(PAPER_UNITS, 1e-9);
    let local_model = paper_model(Some((0.6, 1.0)), 0.0, PAPER_UNITS);
    let local = solve(&problem, &local_model, &settings);
    let with = |regularization| {
        let mut model = local_model.clone();
        model.friction.as_mut().unwrap().regularization = regularization;
        (solve(&problem, &model, &settings), model)
    };
    let (tiny, _) = with(Regularization::Mollifier { radius: 0.1 }); // h = 0.25
    assert!(distance(&problem, &tiny.x, &local.x) < 1e-12);
    let a = 1.0;
    let (smooth, model) = with(Regularization::Mollifier { radius: a });
    assert_kkt(&problem, &model, &settings, &smooth);
    assert!(distance(&problem, &smooth.x, &local.x) > 1e-6, "the mollifier changed nothing");
    // s_i = µ |Σ_j w_j (1 − (r_ij/a)²)² σ_ν,j / Σ_j w_j (1 − (r_ij/a)²)²|, recomputed here.
    let surface = &smooth.surface;
    for i in 0..surface.len() {
        let xi = surface.position(&problem, i);
        let (mut num, mut den) = (0.0, 0.0);
        for j in 0..surface.len() {
            let xj = surface.position(&problem, j);
            let r2 = (xi[0] - xj[0]).powi(2) + (xi[1] - xj[1]).powi(2);
            if r2 < a * a {
                let k = surface.weight[j] * (1.0 - r2 / (a * a)).powi(2);
                num += k * smooth.sigma_nu[j];
                den += k;
            }
        }
        assert!(
            (smooth.s[i] - 0.6 * (num / den).abs()).abs() < 1e-12 * smooth.s[i].max(1.0),
            "node {i}"
        );
    }
    // µ per part: a part covering all of Γ3 with µ = 0.6 is the constant µ = 0.6.
    let mut per_part = local_model.clone();
    let contact = problem.mesh.part_index("contact").unwrap();
    per_part.friction = Some(piezocontact::contact::law::Friction {
        mu: 0.0,
        mu_parts: vec![(contact, 0.6)],
        regularization: Regularization::Identity,
        path: Default::default(),
    });
    let by_part = solve(&problem, &per_part, &settings);
    assert!(distance(&problem, &by_part.x, &local.x) < 1e-12);
}

/// A NaN that reaches an iterate (here through ϕ0, which a case file cannot set to NaN)
/// stops the run with a numerical failure naming the loop, and keeps a finite iterate.
#[test]
fn a_nan_in_an_iterate_is_a_numerical_failure() {
    let problem = paper_problem(24, 4, PAPER_UNITS, ElasticLaw::Linear);
    let mut model = paper_model(Some((0.2, 0.2)), 0.05, PAPER_UNITS);
    model.phi0 = f64::NAN;
    let solution = solve_contact(&problem, &model, &paper_settings(PAPER_UNITS, 1e-4)).unwrap();
    assert!(!solution.converged());
    let failure = solution.failure.expect("a failure").to_string();
    assert!(
        failure.contains("Uzawa loop (Algorithm 2) of outer step")
            && failure.contains("not finite"),
        "{failure}"
    );
    assert!(solution.x.iter().all(|v| v.is_finite()));
}

/// A mollifier as wide as Γ3 (radius 12 m on the paper's 12 m bar) couples every friction
/// bound to every σ_ν: the paper's fixed point, which lags them, stalls above ε_fp; its
/// message names the exact solver, which solves the same problem to its KKT conditions.
#[test]
fn a_fixed_point_that_stalls_names_the_exact_solver() {
    let run = |method: &str| {
        let sets = [
            "mesh.nx=24",
            "mesh.ny=4",
            "friction.regularization=\"mollifier\"",
            "friction.radius=12.0",
            &format!("solver.method=\"{method}\""),
        ];
        let built = super::common::committed_case("paper-7.2.toml", &sets).build().unwrap();
        (super::common::contact_run(&built), built)
    };
    let (uzawa, _) = run("uzawa");
    let failure = uzawa.solution.failure.map(|e| e.to_string()).unwrap_or_default();
    assert!(failure.contains("solver.method = \"newton\" (the exact solver)"), "{failure}");
    let (newton, built) = run("newton");
    assert!(newton.solution.converged(), "{:?}", newton.solution.failure);
    let (problem, model, settings) = (&built.problem, &newton.model, &built.settings);
    assert_kkt(problem, model, settings, &newton.solution);
}

use piezocontact::algorithm::Settings;
use piezocontact::algorithm::uzawa::{self, Uzawa};
use piezocontact::case::{Built, Case};
use piezocontact::contact::ContactModel;
use piezocontact::contact::law::{Conduction, Friction, NormalCompliance, Regularization};
use piezocontact::linalg::{LinearSolver, default_solver};
use piezocontact::material::{
    ElasticLaw, Elasticity, Material, PermittivityConstants, PiezoConstants,
};
use piezocontact::mesh::rectangle::{Diagonal, Rectangle, Segment};
use piezocontact::mesh::{Mesh, gmsh};
use piezocontact::problem::{BodyLoads, Boundary, Problem, constant_vector};
use piezocontact::run::{ContactRun, PathRun, Run, StaticRun};
use std::path::PathBuf;

/// ε0 in the paper cases' units (m, GPa, C, GV): 8.885e−12 C/(V m) = 8.885e−3 C/(GV m).
pub const EPS0: f64 = 8.885e-3;

/// The paper's PZT-5A (Table 1) in dimension `dim`.
pub fn pzt(dim: usize, law: ElasticLaw) -> Material {
    let elasticity = Elasticity::from_young_poisson(58.7102, 0.3912, law).unwrap();
    Material::new(
        dim,
        elasticity,
        PiezoConstants { e31: -5.4, e33: 15.8, e15: 12.3 },
        PermittivityConstants { beta11: 916.0 * EPS0, beta33: 830.0 * EPS0 },
    )
    .unwrap()
}

/// A committed test mesh from `meshes/`.
pub fn mesh_file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes").join(name)
}

/// The committed case `cases/name` with the overrides `sets` (dotted.key=value, as `--set`).
pub fn committed_case(name: &str, sets: &[&str]) -> Case {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../cases").join(name);
    let overrides: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Case::load(&file, &overrides).unwrap()
}

/// `built` solved as `piezocontact run` solves it, with the linear `solver`.
pub fn run_with(built: &Built, solver: Box<dyn LinearSolver>) -> Run {
    Run::solve(built, solver, &|_| {}).unwrap()
}

/// The contact run of `built` (which has a `[contact]` table and no `[loading]` path).
pub fn contact_run(built: &Built) -> ContactRun {
    match run_with(built, default_solver()) {
        Run::Contact(run) => run,
        _ => panic!("{}: not one contact run", built.origin.path.display()),
    }
}

/// The loading path of `built` (which has `[contact]` and `[loading]` tables).
pub fn path_run(built: &Built) -> PathRun {
    match run_with(built, default_solver()) {
        Run::Path(path) => path,
        _ => panic!("{}: not a loading path", built.origin.path.display()),
    }
}

/// A committed test mesh read.
pub fn read_mesh(name: &str) -> Mesh {
    gmsh::read(&std::fs::read(mesh_file(name)).unwrap()).unwrap()
}

/// The unit square on an n × n grid with interior nodes moved by up to 30 % of h
/// (deterministically), parts left, right, bottom, top.
pub fn perturbed_square(n: usize, amplitude: f64) -> Mesh {
    let h = 1.0 / n as f64;
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut coords = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let interior = i > 0 && i < n && j > 0 && j < n;
            let (a, b) = if interior {
                (((i * 7 + j * 13) as f64).sin(), ((i * 11 + j * 5) as f64).cos())
            } else {
                (0.0, 0.0)
            };
            coords.push(i as f64 * h + amplitude * h * a);
            coords.push(j as f64 * h + amplitude * h * b);
        }
    }
    let mut cells = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                cells.extend_from_slice(&[a, b, c, a, c, d]);
            } else {
                cells.extend_from_slice(&[a, b, d, b, c, d]);
            }
        }
    }
    let side = |f: &dyn Fn(usize) -> [usize; 2]| (0..n).flat_map(f).collect::<Vec<_>>();
    let parts = vec![
        piezocontact::mesh::BoundaryPart::new("left", side(&|j| [id(0, j), id(0, j + 1)])),
        piezocontact::mesh::BoundaryPart::new("right", side(&|j| [id(n, j), id(n, j + 1)])),
        piezocontact::mesh::BoundaryPart::new("bottom", side(&|i| [id(i, 0), id(i + 1, 0)])),
        piezocontact::mesh::BoundaryPart::new("top", side(&|i| [id(i, n), id(i + 1, n)])),
    ];
    Mesh::new(2, coords, cells, parts).unwrap()
}

/// A unit system for the paper's example: the stress unit is `stress` Pa and the potential
/// unit `potential` V; lengths in m, charges in C. (1e9, 1e9) is the paper cases' (GPa, GV).
#[derive(Clone, Copy)]
pub struct Units {
    pub stress: f64,
    pub potential: f64,
}

pub const PAPER_UNITS: Units = Units { stress: 1e9, potential: 1e9 };
pub const SI: Units = Units { stress: 1.0, potential: 1.0 };

impl Units {
    /// A stress given in GPa, in these units.
    pub fn stress(&self, gpa: f64) -> f64 {
        gpa * 1e9 / self.stress
    }
    /// A potential given in GV, in these units.
    pub fn potential(&self, gv: f64) -> f64 {
        gv * 1e9 / self.potential
    }
}

/// Example 7.1's bar on an nx × ny rectangle: ends clamped (Γ1 = Γb), top and bottom ends
/// loaded by f2 = (0, −5 GPa) and grounded (Γ2 = Γa), Γ3 = [2,10]×{0}.
pub fn paper_problem(nx: usize, ny: usize, units: Units, law: ElasticLaw) -> Problem {
    paper_problem_with_contact(nx, ny, units, law, &[("contact", "[2,10]x{0}")])
}

/// [`paper_problem`] with Γ3 = [2,10]×{0} made of the named `contact` segments.
pub fn paper_problem_with_contact(
    nx: usize,
    ny: usize,
    units: Units,
    law: ElasticLaw,
    contact: &[(&str, &str)],
) -> Problem {
    let seg = |s: &str| s.parse::<Segment>().unwrap();
    let mut parts = vec![
        ("ends".to_string(), vec![seg("{0}x[0,2]"), seg("{12}x[0,2]")]),
        ("load".to_string(), vec![seg("[0,12]x{2}"), seg("[0,2]x{0}"), seg("[10,12]x{0}")]),
    ];
    parts.extend(contact.iter().map(|(name, s)| (name.to_string(), vec![seg(s)])));
    let mesh = Rectangle { x: [0.0, 12.0], y: [0.0, 2.0], nx, ny, diagonal: Diagonal::Right }
        .mesh(&parts)
        .unwrap();
    let elasticity = Elasticity::from_young_poisson(units.stress(58.7102), 0.3912, law).unwrap();
    let eps0 = 8.885e-12 * units.potential;
    let material = Material::new(
        2,
        elasticity,
        PiezoConstants { e31: -5.4, e33: 15.8, e15: 12.3 },
        PermittivityConstants { beta11: 916.0 * eps0, beta33: 830.0 * eps0 },
    )
    .unwrap();
    let load = mesh.part_index("load").unwrap();
    let boundary = Boundary {
        clamped: vec![mesh.part_index("ends").unwrap()],
        grounded: vec![load],
        contact: contact.iter().map(|(name, _)| mesh.part_index(name).unwrap()).collect(),
        traction: vec![(load, constant_vector(vec![0.0, units.stress(-5.0)]))],
        ..Boundary::default()
    };
    Problem::new(mesh, material, boundary, BodyLoads::default()).unwrap()
}

/// The contact model of Examples 7.1 (`pv2 = None`) and 7.2 (`Some((µ, k_e))`), with gap 0.5,
/// penetration `penetration`, ϕ0 = 32 GV and the case files' defaults for the constants the
/// paper does not give.
pub fn paper_model(pv2: Option<(f64, f64)>, penetration: f64, units: Units) -> ContactModel {
    let phi0 = units.potential(32.0);
    let compliance = NormalCompliance {
        gap: 0.5,
        penetration,
        c_nu: units.stress(1.0),
        alpha_nu: 2.0,
        n_nu: 1.0,
        h_nu_range: units.potential(128.0),
    };
    let pv2 = pv2.map(|(mu, ke)| {
        (
            Friction {
                mu,
                mu_parts: Vec::new(),
                regularization: Regularization::Identity,
                path: Default::default(),
            },
            // ψ φ_L is a charge density: ψ scales inversely to the potential unit.
            Conduction {
                ke: ke * units.potential / 1e9,
                delta: 1.0,
                truncation: units.potential(1000.0),
            },
        )
    });
    let (friction, conduction) = pv2.unzip();
    ContactModel { compliance, friction, conduction, foundation: Default::default(), phi0 }
}

/// The paper's settings (r = 0.25 E) with tolerances `eps` = `eps_fp`.
pub fn paper_settings(units: Units, eps: f64) -> Settings {
    let r = units.stress(0.25 * 58.7102);
    let parameters = uzawa::Parameters { r, eps, eps_fp: eps, max_inner: 100_000 };
    Settings::new(Uzawa::new(parameters), 200)
}

/// The arch of `meshes/arch.msh`: a block on a curved contact face (Γ3), clamped at its
/// sides, grounded and loaded by f2 = (0, −5) on its top.
pub fn arch_problem() -> Problem {
    let mesh = read_mesh("arch.msh");
    let part = |n: &str| mesh.part_index(n).unwrap();
    let boundary = Boundary {
        clamped: vec![part("clamp")],
        grounded: vec![part("top")],
        contact: vec![part("contact")],
        traction: vec![(part("top"), constant_vector(vec![0.0, -5.0]))],
        ..Boundary::default()
    };
    Problem::new(mesh, pzt(2, ElasticLaw::Linear), boundary, BodyLoads::default()).unwrap()
}

/// Builds a case from its text (named "block.toml" in messages).
pub fn build_text(text: &str) -> piezocontact::Result<Built> {
    Case::from_text("block.toml".as_ref(), text, &[])?.build()
}

/// Solves a case without contact from its text.
pub fn solve_static(text: &str) -> (Built, StaticRun) {
    let built = build_text(text).unwrap();
    match Run::solve(&built, default_solver(), &|_| {}).unwrap() {
        Run::Static(run) => (built, run),
        _ => panic!("not a run without contact"),
    }
}

/// Asserts that u at every node is `expected(position)` (d components) to `tolerance`.
pub fn assert_displacements(
    built: &Built,
    run: &StaticRun,
    expected: impl Fn(&[f64]) -> Vec<f64>,
    tolerance: f64,
) {
    let (dofs, x) = (&run.solution.dofs, &run.solution.x);
    let mesh = &built.problem.mesh;
    for node in 0..mesh.n_nodes() {
        let p = mesh.node(node);
        for (k, want) in expected(p).iter().enumerate() {
            let got = x[dofs.u(node, k)];
            assert!((got - want).abs() < tolerance, "u_{k} at {p:?}: {got} vs {want}");
        }
    }
}

//! Case files (model §9): a TOML document, checked and turned into what the solver takes.
//! The flow is ripgrep's — raw arguments, then one conversion to validated settings:
//! - [`schema`]: the serde view of the file, every key documented, every default in one table
//!   ([`DEFAULTS`]);
//! - [`overrides`]: `--set dotted.key=value` edits the document before it is read, so an
//!   override is checked exactly like the file;
//! - [`mod@file`]: the case read ([`Case`]) and where its keys are ([`Origin`]);
//! - [`validate`]: magnitudes and ranges, each error naming the file, the line of the key and
//!   the fix ([`Error::Input`](crate::Error::Input)); the paper's hypotheses as warnings;
//! - [`build`]: [`Case::build`] validates once and returns everything a run takes
//!   ([`Built`]): the problem, the contact model, the loading path, the settings, the
//!   warnings, and the case's title, units, method and backend.
//!
//! Each file imports its siblings' files, never this one.

/// An [`Error::Input`] with a formatted message.
macro_rules! input {
    ($($arg:tt)*) => { crate::error::Error::Input(format!($($arg)*)) };
}

pub mod build;
pub mod expression;
pub mod file;
mod geometry;
mod material;
pub mod overrides;
mod regions;
pub mod schema;
pub mod validate;

pub use build::Built;
pub use file::{Case, Origin};
pub use overrides::key_line;
pub use schema::*;
pub use validate::{MAGNITUDE, MIN_MAGNITUDE};

#[cfg(test)]
mod tests {
    use super::build::MethodParameters;
    use super::*;
    use crate::algorithm::{newton, uzawa};
    use crate::error::Result;
    use std::path::Path;

    const PAPER_71: &str = include_str!("../../../../cases/paper-7.1.toml");
    const PAPER_72: &str = include_str!("../../../../cases/paper-7.2.toml");
    const MINIMAL: &str = r#"
[mesh]
x = [0.0, 4.0]
y = [0.0, 1.0]
nx = 8
ny = 2
[mesh.segments]
left = ["{0}x[0,1]"]
bottom = ["[0,4]x{0}"]
[material]
young = 100.0
poisson = 0.25
e31 = -5.4
e33 = 15.8
e15 = 12.3
eps0 = 8.885e-3
beta11_rel = 916.0
beta33_rel = 830.0
[boundary]
clamped = ["left"]
grounded = ["left"]
contact = ["bottom"]
[contact]
gap = 0.1
[solver]
"#;

    fn case(text: &str, overrides: &[&str]) -> Result<Case> {
        let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        Case::from_text(Path::new("case.toml"), text, &overrides)
    }

    fn error(text: &str, overrides: &[&str]) -> String {
        let checked = case(text, overrides).and_then(|c| {
            let built = c.build()?;
            Ok(built.model)
        });
        checked.map(|_| String::new()).unwrap_or_else(|e| e.to_string())
    }

    #[test]
    fn defaults_live_in_one_place_and_follow_e() {
        let c = case(MINIMAL, &[]).unwrap();
        let d = DEFAULTS;
        let newton = newton::Parameters {
            r: 0.25 * 100.0,
            tol: d.tol,
            max_inner: d.max_newton,
            max_condensed: None,
            guess: crate::algorithm::condensed::Guess::Interpenetration(d.first_condensed),
        };
        assert_eq!(c.method_parameters().unwrap(), MethodParameters::Newton(newton));
        let built = c.build().unwrap();
        assert_eq!((built.settings.method.name(), built.settings.max_outer), ("newton", 100));
        let uzawa =
            case(MINIMAL, &["solver.method=\"uzawa\""]).unwrap().method_parameters().unwrap();
        let expected =
            uzawa::Parameters { r: 25.0, eps: d.eps, eps_fp: d.eps_fp, max_inner: d.max_uzawa };
        assert_eq!(uzawa, MethodParameters::Uzawa(expected));
        // The values `check` prints are those the solver uses.
        let lines = c.contact_settings().unwrap();
        let value = |key: &str| lines.iter().find(|(k, _)| k == key).map(|(_, v)| *v);
        assert_eq!(value("solver.r"), Some(25.0));
        assert_eq!(value("solver.max_outer"), Some(d.max_outer as f64));
        let with = case(MINIMAL, &["solver.r=3", "solver.method=\"uzawa\""]).unwrap();
        assert!(
            matches!(with.method_parameters().unwrap(), MethodParameters::Uzawa(p) if p.r == 3.0)
        );
        // Keys of the other method are reported, not silently dropped.
        let unused = case(MINIMAL, &["solver.eps=1e-6"]).unwrap().setting_warnings();
        assert!(unused[0].contains("solver.eps is not used by solver.method = \"newton\""));
        let overrides = ["solver.method=\"uzawa\"", "solver.max_condensed=10"];
        let unused = case(MINIMAL, &overrides).unwrap().setting_warnings();
        assert!(
            unused[0].contains("solver.max_condensed is not used by solver.method = \"uzawa\"")
        );
        // The whole system's Newton method (the iterative route) has no condensed set.
        let iterative = ["solver.backend=\"petsc\"", "solver.linear=\"iterative\""];
        let unused = case(MINIMAL, &[&iterative[..], &["solver.max_condensed=10"]].concat());
        let unused = unused.unwrap().setting_warnings();
        assert!(unused[0].contains("solver.max_condensed is not used with solver.linear"));
        assert!(case(MINIMAL, &iterative).unwrap().setting_warnings().is_empty());
        // Both keys of the other method in one warning.
        let unused = case(MINIMAL, &["solver.eps=1e-6", "solver.eps_fp=1e-6"]).unwrap();
        let unused = unused.setting_warnings();
        assert_eq!(unused.len(), 1, "{unused:?}");
        assert!(unused[0].contains("solver.eps, solver.eps_fp are not used by"), "{unused:?}");
    }

    /// Friction and conduction keys that the problem does not read are reported, each at its
    /// key; the paper's cases (PV1 with µ = k_e = 0, PV2) and a path with incremental
    /// friction report none.
    #[test]
    fn keys_the_problem_does_not_read_are_reported() {
        let warned = |overrides: &[&str]| case(MINIMAL, overrides).unwrap().setting_warnings();
        let pv1 = "contact.problem=\"PV1\"";
        let friction = warned(&[pv1, "friction.mu=0.3"]);
        assert!(
            friction.len() == 1 && friction[0].contains("friction is not used"),
            "{friction:?}"
        );
        let parts = warned(&[pv1, "friction.mu_parts={bottom=0.3}"]);
        assert!(parts.len() == 1 && parts[0].contains("\"PV1\" is frictionless"), "{parts:?}");
        let ke = warned(&[pv1, "conductivity.ke=0.5", "conductivity.phi0=1.0"]);
        assert!(ke.len() == 1 && ke[0].contains("conductivity.ke is not used"), "{ke:?}");
        let radius = warned(&["friction.mu=0.3", "friction.radius=0.2"]);
        assert!(radius.len() == 1 && radius[0].contains("friction.radius is not used"));
        let path = warned(&["friction.mu=0.3", "friction.path=\"incremental\""]);
        assert!(path.len() == 1 && path[0].contains("friction.path is not used"), "{path:?}");
        for read in [
            &[pv1, "friction.mu=0.0", "conductivity.phi0=1.0"][..],
            &["friction.mu=0.3", "conductivity.ke=0.5"],
            &["friction.regularization=\"mollifier\"", "friction.radius=0.2"],
            &["friction.path=\"incremental\"", "loading.depths=[0.1]", "foundation.kind=\"plane\""],
        ] {
            assert!(warned(read).is_empty(), "{read:?}: {:?}", warned(read));
        }
        for text in [PAPER_71, PAPER_72] {
            assert!(case(text, &[]).unwrap().setting_warnings().is_empty());
        }
        // A segment's end between two nodes (cells of 0.5 along x): the part stops short.
        let short = warned(&["mesh.segments.bottom=[\"[0,1.2]x{0}\", \"{4}x[0,1]\"]"]);
        assert!(
            short.len() == 1
                && short[0].contains(
                    "'[0,1.2]x{0}' ends between two nodes at x = 1.2 (nodes at 1 and 1.5)"
                ),
            "{short:?}"
        );
        let paper = case(PAPER_71, &["mesh.nx=100"]).unwrap().setting_warnings();
        assert!(
            paper.iter().any(|w| w.contains(
                "at x = 2 (nodes at 1.92 and 2.04) and x = 10 (nodes at 9.96 and 10.08)"
            )),
            "{paper:?}"
        );
    }

    #[test]
    fn the_paper_case_gives_the_paper_model() {
        let c = case(PAPER_71, &["mesh.nx=12", "mesh.ny=2"]).unwrap();
        let problem = c.problem().unwrap();
        let model = c.contact_model(&problem).unwrap().unwrap();
        assert_eq!(c.problem_kind(), ProblemKey::PV1);
        assert!(model.friction.is_none() && model.conduction.is_none());
        assert_eq!((model.compliance.gap, model.phi0), (0.5, 32.0));
        // The paper's cases ask for the paper's algorithm.
        assert_eq!(c.build().unwrap().settings.method.name(), "uzawa");
        assert_eq!(c.file.units.potential, "GV");
        // PV2 is implied by a [friction] table; conduction then takes its defaults.
        let pv2 = case(MINIMAL, &["friction.mu=0.3"]).unwrap();
        let problem = pv2.problem().unwrap();
        let model = pv2.contact_model(&problem).unwrap().unwrap();
        assert_eq!(model.friction.unwrap().mu, 0.3);
        assert_eq!(model.conduction.unwrap(), {
            let d = ConductivitySection::default();
            crate::contact::law::Conduction { ke: 0.0, delta: d.delta, truncation: d.truncation }
        });
    }

    #[test]
    fn errors_name_the_file_the_line_the_key_and_the_fix() {
        for (overrides, pieces) in [
            (vec!["solver.r=-1"], vec!["case.toml:", "solver.r = -1 is not allowed: r > 0"]),
            (vec!["solver.max_inner=0"], vec!["solver.max_inner = 0", "at least 1"]),
            // The default r = 0.25 E: a zero E is named, at its line, not r.
            (
                vec!["material.young=0"],
                vec![&format!("case.toml:{}: material.young = 0", line("young")), "E must be > 0"],
            ),
            (vec!["solver.method=\"simplex\""], vec!["unknown variant `simplex`", "uzawa"]),
            (vec!["solver.tol=0"], vec!["solver.tol = 0 is not allowed: a tolerance > 0"]),
            (vec!["solver.max_condensed=0"], vec!["solver.max_condensed = 0", "at least 1"]),
            (vec!["contact.alpha_nu=1"], vec!["contact.alpha_nu = 1", "α_ν > 1"]),
            (
                vec!["material.poisson=0.5"],
                vec![&format!("case.toml:{}", line("poisson")), "poisson"],
            ),
            (
                vec!["boundary.contact=[\"nowhere\"]"],
                vec!["'nowhere' is not a boundary part of the mesh", "bottom"],
            ),
            (
                vec!["material.beta33_rel=0"],
                vec![&format!("case.toml:{}: material.beta33_rel = 0", line("beta33_rel"))],
            ),
            (vec!["boundary.contact=[\"bottom\", \"bottom\"]"], vec!["names 'bottom' twice"]),
            (
                vec!["boundary.traction=[{parts=[], f2=[0.0, -1.0]}]"],
                vec!["boundary.traction.parts is empty: name the boundary parts"],
            ),
            (vec!["boundary.charge=[{parts=[], q2=1.0}]"], vec!["boundary.charge.parts is empty"]),
            (
                vec![
                    "mesh.segments.a=[\"[0,2]x{1}\"]",
                    "mesh.segments.b=[\"[1,3]x{1}\"]",
                    "boundary.traction=[{parts=[\"a\", \"b\"], f2=[0.0, -1.0]}]",
                ],
                vec!["parts 'a' and 'b' share the facet", "act twice"],
            ),
            (
                vec!["boundary.clamped=[\"left\", \"bottom\"]"],
                vec!["'bottom' (Γ3 (contact)) and 'bottom' (Γ1 (clamped))", "must be disjoint"],
            ),
            (
                vec![
                    "mesh.segments.half=[\"[0,2]x{0}\"]",
                    "boundary.contact=[\"bottom\", \"half\"]",
                ],
                vec!["'bottom' and 'half' of Γ3 (contact) share the facet", "count twice"],
            ),
            (
                vec!["friction.mu_parts.left=0.2"],
                vec!["friction.mu_parts.left", "not a contact part"],
            ),
            (
                vec!["friction.regularization=\"mollifier\""],
                vec!["regularization = \"mollifier\" needs its radius a > 0"],
            ),
        ] {
            assert_error_names(&overrides, &pieces);
        }
    }

    /// The line (1-based) of MINIMAL that starts with `key`.
    fn line(key: &str) -> usize {
        MINIMAL.lines().position(|l| l.starts_with(key)).map_or(0, |k| k + 1)
    }

    /// The error of MINIMAL with `overrides` holds each of `pieces`.
    fn assert_error_names(overrides: &[&str], pieces: &[&str]) {
        let e = error(MINIMAL, overrides);
        for piece in pieces {
            assert!(e.contains(piece), "{overrides:?}: '{e}' lacks '{piece}'");
        }
    }

    #[test]
    fn errors_of_the_mesh_and_of_the_syntax_name_the_key_and_the_fix() {
        // An empty list of segments made an empty Γ3: the run ended without contact.
        let empty = format!("case.toml:{}: mesh.segments.bottom is empty", line("bottom"));
        for (overrides, pieces) in [
            (vec!["mesh.segments.bottom=[]"], vec![empty.as_str()]),
            (vec!["mesh.file=\"x.msh\""], vec!["mesh.x describes the built-in rectangle"]),
            (vec!["solver.nonsense=1"], vec!["unknown field `nonsense`"]),
            (vec!["solver"], vec!["the override solver: expected dotted.key=value"]),
            (vec!["mesh.nx.deep=1"], vec!["'mesh.nx' is not a table"]),
            (
                vec!["mesh.nx=2000000000", "mesh.ny=2000000000"],
                vec!["would need about", "reduce mesh.nx"],
            ),
        ] {
            assert_error_names(&overrides, &pieces);
        }
        let e = error("[mesh]\nnx = 'a'\n", &[]);
        assert!(e.starts_with("case.toml: TOML parse error at line 2"), "{e}");
    }

    #[test]
    fn the_foundation_table_is_read_and_checked() {
        let with = |sets: &[&str]| {
            let c = case(MINIMAL, sets)?;
            c.foundation(2)
        };
        let plane = with(&[
            "foundation.kind=\"plane\"",
            "foundation.point=[0.0, -0.5]",
            "foundation.normal=[0.0, 2.0]",
        ])
        .unwrap();
        assert_eq!(
            plane,
            crate::contact::Foundation::Plane { point: [0.0, -0.5, 0.0], normal: [0.0, 1.0, 0.0] }
        );
        let ball = with(&[
            "foundation.kind=\"sphere\"",
            "foundation.center=[2.0, -1.0]",
            "foundation.radius=0.5",
        ])
        .unwrap();
        assert_eq!(
            ball,
            crate::contact::Foundation::Sphere { center: [2.0, -1.0, 0.0], radius: 0.5 }
        );
        assert_eq!(with(&[]).unwrap(), crate::contact::Foundation::ConstantGap);
        let cone = with(&[
            "foundation.kind=\"cone\"",
            "foundation.apex=[0.0, 0.1]",
            "foundation.axis=[0.0, 3.0]",
            "foundation.half_angle=60",
        ])
        .unwrap();
        let axis = [0.0, 1.0, 0.0];
        let half_angle = 60f64.to_radians();
        let apex = [0.0, 0.1, 0.0];
        assert_eq!(cone, crate::contact::Foundation::Cone { apex, axis, half_angle });
        let punch = with(&[
            "foundation.kind=\"punch\"",
            "foundation.center=[0.5, 0.0]",
            "foundation.axis=[0.0, 1.0]",
            "foundation.radius=0.2",
        ])
        .unwrap();
        let center = [0.5, 0.0, 0.0];
        assert_eq!(punch, crate::contact::Foundation::Punch { center, axis, radius: 0.2 });
    }

    #[test]
    fn the_foundation_table_s_errors_name_the_key() {
        let with = |sets: &[&str]| {
            let c = case(MINIMAL, sets)?;
            c.foundation(2)
        };
        for (sets, piece) in [
            (
                vec!["foundation.kind=\"plane\"", "foundation.point=[0.0, 0.0]"],
                "foundation.normal is missing",
            ),
            (
                vec![
                    "foundation.kind=\"plane\"",
                    "foundation.point=[0.0]",
                    "foundation.normal=[0.0, 1.0]",
                ],
                "foundation.point = [0.0] must have 2 finite components",
            ),
            (
                vec![
                    "foundation.kind=\"plane\"",
                    "foundation.point=[0.0, 0.0]",
                    "foundation.normal=[0.0, 0.0]",
                ],
                "a nonzero vector",
            ),
            (
                vec![
                    "foundation.kind=\"sphere\"",
                    "foundation.center=[0.0, 0.0]",
                    "foundation.radius=-1",
                ],
                "foundation.radius = -1 is not allowed: a length > 0",
            ),
            (
                vec![
                    "foundation.kind=\"sphere\"",
                    "foundation.center=[0.0, 0.0]",
                    "foundation.normal=[0.0, 1.0]",
                ],
                "foundation.normal does not belong to kind = \"sphere\"",
            ),
        ] {
            let e = with(&sets).unwrap_err().to_string();
            assert!(e.contains(piece) && e.starts_with("case.toml"), "{sets:?}: {e}");
        }
    }

    #[test]
    fn incremental_friction_is_refused_to_the_uzawa_method() {
        let built = case(PAPER_72, &["friction.path=\"incremental\""]).unwrap().build();
        let e = built.err().unwrap().to_string();
        assert!(
            e.contains("friction.path = \"incremental\" is solved by the exact solver only")
                && e.contains("solver.method = \"newton\""),
            "{e}"
        );
    }

    #[test]
    fn the_indenters_errors_name_the_key() {
        for (sets, piece) in [
            (vec!["foundation.kind=\"wedge\""], "unknown variant `wedge`"),
            (
                vec![
                    "foundation.kind=\"cone\"",
                    "foundation.apex=[0.0, 0.0]",
                    "foundation.axis=[0.0, 1.0]",
                    "foundation.half_angle=90",
                ],
                "foundation.half_angle = 90 is not allowed: degrees between the axis and the flank, in (0, 90)",
            ),
            (
                vec![
                    "foundation.kind=\"cone\"",
                    "foundation.apex=[0.0, 0.0]",
                    "foundation.axis=[0.0, 0.0]",
                    "foundation.half_angle=60",
                ],
                "foundation.axis = [0.0, 0.0] is not allowed: a nonzero vector",
            ),
            (
                vec![
                    "foundation.kind=\"cone\"",
                    "foundation.apex=[0.0, 0.0]",
                    "foundation.axis=[0.0, 1.0]",
                ],
                "foundation.half_angle is missing",
            ),
            (
                vec![
                    "foundation.kind=\"punch\"",
                    "foundation.center=[0.0, 0.0]",
                    "foundation.axis=[0.0, 1.0]",
                    "foundation.radius=0.2",
                    "foundation.half_angle=30",
                ],
                "foundation.half_angle does not belong to kind = \"punch\"",
            ),
        ] {
            let e = case(MINIMAL, &sets).and_then(|c| c.foundation(2)).unwrap_err().to_string();
            assert!(e.contains(piece) && e.starts_with("case.toml"), "{sets:?}: {e}");
        }
    }

    #[test]
    fn overrides_replace_a_key_under_either_spelling() {
        let c = case(PAPER_71, &["material.e31=-1.5", "material.beta11_rel=100"]).unwrap();
        assert_eq!(
            (c.file.material.tables()[0].e31, c.file.material.tables()[0].beta11_rel),
            (Some(-1.5), Some(100.0))
        );
        assert_eq!(c.locate("material.e32"), "case.toml");
        assert!(c.locate("material.e31").starts_with("case.toml:"));
    }

    #[test]
    fn a_table_override_sets_its_keys_and_keeps_the_others() {
        // The paper's case runs Uzawa with its own eps_fp: a table naming eps alone keeps them.
        let c = case(PAPER_71, &["solver={eps=1e-7}"]).unwrap();
        let solver = &c.file.solver;
        assert_eq!((solver.eps, solver.eps_fp), (Some(1e-7), Some(1e-4)));
        assert!(matches!(solver.method, Some(MethodKey::Uzawa)));
        // Nested tables, a table the file lacks, and a key under its other spelling.
        let c = case(PAPER_71, &["material={e32=-1.5}", "mesh={segments={extra=[\"[0,1]x{1}\"]}}"])
            .unwrap();
        assert_eq!(
            (c.file.material.tables()[0].e31, c.file.material.tables()[0].young),
            (Some(-1.5), Some(58.7102))
        );
        assert!(c.origin.text.contains("extra"), "{}", c.origin.text);
        let c = case(MINIMAL, &["friction={mu=0.3}"]).unwrap();
        assert_eq!(c.file.friction.map(|f| f.mu), Some(0.3));
        // Into a table the file writes inline.
        let inline = format!("solver = {{ eps = 1e-3 }}\n{}", MINIMAL.replace("[solver]\n", ""));
        let c = case(&inline, &["solver.eps_fp=1e-5", "solver={eps=1e-6}"]);
        let c = c.map_err(|e| e.to_string());
        let solver = c.as_ref().map(|c| (c.file.solver.eps, c.file.solver.eps_fp));
        assert_eq!(solver, Ok((Some(1e-6), Some(1e-5))));
        let e = case(PAPER_71, &["mesh.nx={a=1}"]).unwrap_err().to_string();
        assert!(e.contains("'mesh.nx' is not a table"), "{e}");
    }

    #[test]
    fn the_hypotheses_are_reported_with_their_numbers() {
        let c = case(MINIMAL, &["material.poisson=0.05"]).unwrap();
        let problem = c.problem().unwrap();
        let warnings = c.hypothesis_warnings(&problem.materials);
        assert!(warnings.iter().any(|w| w.starts_with("(h1)(a) fails")), "{warnings:?}");
        assert!(warnings.iter().any(|w| w.contains("e·t0 = 4.8929e0")), "{warnings:?}");
        let linear = case(MINIMAL, &["material.law=\"linear\""]).unwrap();
        assert!(linear.hypothesis_warnings(&linear.problem().unwrap().materials).is_empty());
        assert!(c.uniqueness_note().unwrap().contains("M_h·L_p + L_h·M_p"));
    }

    #[test]
    fn the_rectangle_s_regions_are_boxes_of_cell_centroids() {
        let material = MINIMAL
            [MINIMAL.find("[material]").unwrap() + 11..MINIMAL.find("[boundary]").unwrap()]
            .to_string();
        let text = MINIMAL.replace(&format!("[material]\n{material}"), "")
            .replace("[boundary]", &format!(
                "[mesh.regions]\nlower = [\"[0,4]x[0,0.5]\"]\nupper = [\"[0,4]x[0.5,1]\"]\n[[material]]\nname = \"soft\"\nregions = [\"lower\"]\n{}\n[[material]]\nname = \"hard\"\nregions = [\"upper\"]\n{material}\n[boundary]",
                material.replace("young = 100.0", "young = 50.0")
            ));
        let problem = case(&text, &[]).unwrap().problem().unwrap();
        let materials = &problem.materials;
        assert_eq!(materials.cell_counts(problem.mesh.n_cells()), vec![16, 16]);
        for c in 0..problem.mesh.n_cells() {
            let y: f64 =
                problem.mesh.cell(c).iter().map(|&n| problem.mesh.node(n)[1]).sum::<f64>() / 3.0;
            let young = problem.material(c).elasticity().unwrap().young();
            assert!((young - if y < 0.5 { 50.0 } else { 100.0 }).abs() < 1e-9, "cell {c}: {young}");
        }
        let moved = case(&text.replace("[0,4]x[0,0.5]", "[5,6]x[0,1]"), &[]).unwrap();
        let e = moved.problem().err().unwrap().to_string();
        assert!(e.contains("mesh.regions.lower") && e.contains("holds no cell"), "{e}");
    }

    #[test]
    fn the_2d_continuum_refuses_full_tensors_and_keeps_the_shorthand() {
        let zero = "d = [[0,0,0,0,0,0],[0,0,0,0,0,0],[0,0,0,0,0,0]]\n";
        let text = MINIMAL.replace("e31 = -5.4\ne33 = 15.8\ne15 = 12.3\n", zero);
        assert!(text.contains(zero));
        let e = case(&text, &[]).unwrap().problem().err().unwrap().to_string();
        assert!(e.contains("material.d: the 2D continuum model") && e.contains("3D mesh"), "{e}");
        // eps_rel is the shorthand's permittivity written out: the same material.
        let written = ["material.beta11_rel=916.0", "material.beta33_rel=830.0"];
        let given = case(MINIMAL, &written).unwrap().problem().unwrap().materials;
        let text = MINIMAL
            .replace("beta11_rel = 916.0\nbeta33_rel = 830.0", "eps_rel = [916.0, 916.0, 830.0]");
        assert!(text.contains("eps_rel"));
        assert_eq!(case(&text, &[]).unwrap().problem().unwrap().materials, given);
    }
}

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository's root (the command runs there, so case paths are relative to it).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The `piezocontact` command, run from the root.
pub fn command() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_piezocontact"));
    c.current_dir(root());
    c
}

/// Runs the command with `args`.
pub fn piezocontact(args: &[&str]) -> Output {
    command().args(args).output().unwrap()
}

/// stdout and stderr together.
pub fn text(o: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr))
}

/// A fresh, empty temporary directory for test `name`.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("piezocontact-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `piezocontact run CASE --out OUT` on the coarse 24 × 4 mesh, with more `--set`s.
pub fn run_coarse(case: &str, out: &Path, sets: &[&str]) -> Output {
    let mut args = vec![
        "run",
        case,
        "--out",
        out.to_str().unwrap(),
        "--set",
        "mesh.nx=24",
        "--set",
        "mesh.ny=4",
    ];
    for set in sets {
        args.extend(["--set", set]);
    }
    piezocontact(&args)
}

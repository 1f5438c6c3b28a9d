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

/// Runs the command with `args`, then checks every output file it wrote under its `--out`
/// directory ([`assert_strict_outputs`]).
pub fn piezocontact(args: &[&str]) -> Output {
    let output = command().args(args).output().unwrap();
    if let Some(k) = args.iter().position(|a| *a == "--out") {
        assert_strict_outputs(&root().join(args[k + 1]));
    }
    output
}

/// Every summary.json under `dir` parses with a strict JSON parser (serde_json rejects NaN
/// and Infinity tokens), a null number comes with its reason in `non_finite`, and no CSV
/// under `dir` holds a NaN or inf token.
pub fn assert_strict_outputs(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.filter_map(|e| e.ok()) {
        let path = entry.path();
        if path.is_dir() {
            assert_strict_outputs(&path);
            continue;
        }
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name == "summary.json" {
            let text = std::fs::read_to_string(&path).unwrap();
            let summary: serde_json::Value = serde_json::from_str(&text)
                .unwrap_or_else(|e| panic!("{} is not strict JSON: {e}", path.display()));
            assert_nulls_explained(&summary, &path);
        } else if name.ends_with(".csv") {
            let text = std::fs::read_to_string(&path).unwrap();
            for cell in text.lines().flat_map(|l| l.split(',')) {
                let lower = cell.trim().to_ascii_lowercase();
                assert!(
                    !lower.contains("nan") && !lower.contains("inf"),
                    "{} holds the token {cell:?}",
                    path.display()
                );
            }
        }
    }
}

/// The paths of the nulls in summary.json other than `failure` (which is null when the run
/// did not fail): serde_json writes a NaN or an infinity as null.
pub fn null_paths(value: &serde_json::Value) -> Vec<String> {
    fn walk(value: &serde_json::Value, at: String, out: &mut Vec<String>) {
        match value {
            serde_json::Value::Null if at != ".failure" => out.push(at),
            serde_json::Value::Array(a) => {
                a.iter().enumerate().for_each(|(i, v)| walk(v, format!("{at}[{i}]"), out))
            }
            serde_json::Value::Object(o) => {
                o.iter().for_each(|(k, v)| walk(v, format!("{at}.{k}"), out))
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(value, String::new(), &mut out);
    out
}

/// Every null of summary.json but `failure` is a number that was not finite, for which
/// `non_finite` names the top-level field and the reason.
fn assert_nulls_explained(summary: &serde_json::Value, file: &Path) {
    for at in null_paths(summary) {
        let top = at.trim_start_matches('.').split(['.', '[']).next().unwrap_or("");
        let explained = summary["non_finite"].get(top).is_some_and(|v| v.is_string());
        assert!(explained, "{}: null at {at} with no reason in non_finite", file.display());
    }
}

/// stdout and stderr together.
pub fn text(o: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr))
}

/// A temporary directory of one test: removed when the test passes, kept (its path printed)
/// when it fails, for a look at what the command wrote.
pub struct TempDir(PathBuf);

impl TempDir {
    /// The path for test `name`, with nothing there yet (as `--out` wants it).
    pub fn unmade(name: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("piezocontact-cli-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        TempDir(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("the failed test's files are in {}", self.0.display());
        } else {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

impl std::ops::Deref for TempDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for TempDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

/// A fresh, empty temporary directory for test `name`.
pub fn temp_dir(name: &str) -> TempDir {
    let dir = TempDir::unmade(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `piezocontact run CASE --out OUT` on the coarse 24 × 4 mesh, with more `--set`s.
pub fn run_coarse(case: &str, out: &Path, sets: &[&str]) -> Output {
    coarse(&["run", case], out, sets)
}

/// `piezocontact sweep CASE --set-list LIST --out OUT` (and `extra` arguments) on the coarse
/// 24 × 4 mesh, with more `--set`s.
pub fn sweep_coarse(case: &str, list: &str, extra: &[&str], out: &Path, sets: &[&str]) -> Output {
    let head: Vec<&str> =
        ["sweep", case, "--set-list", list].iter().chain(extra).copied().collect();
    coarse(&head, out, sets)
}

/// The command `head` with `--out OUT` on the coarse 24 × 4 mesh and more `--set`s.
fn coarse(head: &[&str], out: &Path, sets: &[&str]) -> Output {
    let mut args = head.to_vec();
    args.extend(["--out", out.to_str().unwrap(), "--set", "mesh.nx=24", "--set", "mesh.ny=4"]);
    for set in sets {
        args.extend(["--set", set]);
    }
    piezocontact(&args)
}

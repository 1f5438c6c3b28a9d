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
pub fn coarse(head: &[&str], out: &Path, sets: &[&str]) -> Output {
    let mut args = head.to_vec();
    args.extend(["--out", out.to_str().unwrap(), "--set", "mesh.nx=24", "--set", "mesh.ny=4"]);
    for set in sets {
        args.extend(["--set", set]);
    }
    piezocontact(&args)
}

/// What the tests read from a .vtu file.
pub struct Vtu {
    /// Whether the file holds appended raw data (the default binary encoding).
    pub binary: bool,
    pub points: usize,
    pub cells: usize,
    /// The points' coordinates, 3 per point.
    pub coordinates: Vec<f64>,
    /// The cells' nodes.
    pub connectivity: Vec<i64>,
    /// Point-data arrays (name, values).
    pub point_data: Vec<(String, Vec<f64>)>,
    /// Cell-data arrays (name, values).
    pub cell_data: Vec<(String, Vec<f64>)>,
}

/// Reads a .vtu file: the binary encoding (appended raw data) with [`appended_arrays`], the
/// text with vtkio — readers apart from the writer.
pub fn read_vtu(path: &Path) -> Vtu {
    let bytes = std::fs::read(path).unwrap();
    if bytes.windows(RAW.len()).any(|w| w == RAW) {
        return binary_vtu(&bytes);
    }
    use vtkio::model::{Attribute, DataSet, Piece, VertexNumbers};
    let vtk = vtkio::Vtk::import(path).unwrap();
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        panic!("not an unstructured grid")
    };
    let Piece::Inline(piece) = &pieces[0] else { panic!("piece not inline") };
    let VertexNumbers::XML { offsets, connectivity } = &piece.cells.cell_verts else {
        panic!("legacy cells")
    };
    let arrays = |attrs: &[Attribute]| -> Vec<(String, Vec<f64>)> {
        attrs
            .iter()
            .map(|a| match a {
                Attribute::DataArray(d) => (d.name.clone(), d.data.clone().cast_into().unwrap()),
                Attribute::Field { name, .. } => (name.clone(), Vec::new()),
            })
            .collect()
    };
    Vtu {
        binary: false,
        points: piece.num_points(),
        cells: offsets.len(),
        coordinates: piece.points.clone().cast_into().unwrap(),
        connectivity: connectivity.iter().map(|&n| n as i64).collect(),
        point_data: arrays(&piece.data.point),
        cell_data: arrays(&piece.data.cell),
    }
}

/// Where a binary .vtu file's appended raw data begins.
const RAW: &[u8] = b"<AppendedData encoding=\"raw\">\n_";

/// The arrays of a binary .vtu file — each DataArray's section (the XML element it is in:
/// Points, Cells, PointData, CellData), Name and bytes, in the file's order — read from
/// their offsets after the `_` and their UInt64 byte counts.
pub fn appended_arrays(bytes: &[u8]) -> Vec<(String, String, Vec<u8>)> {
    let start = bytes.windows(RAW.len()).position(|w| w == RAW).unwrap() + RAW.len();
    let header = std::str::from_utf8(&bytes[..start]).unwrap();
    assert!(header.contains(r#"header_type="UInt64""#), "{header}");
    let mut section = String::new();
    let mut arrays = Vec::new();
    for tag in header.split('<').skip(1) {
        let name = tag.split([' ', '>', '/']).next().unwrap();
        if ["Points", "Cells", "PointData", "CellData"].contains(&name) {
            section = name.to_string();
        }
        if name != "DataArray" {
            continue;
        }
        let attribute = |key: &str| {
            let rest = tag.split(&format!(" {key}=\"")).nth(1)?;
            Some(rest.split('"').next().unwrap().to_string())
        };
        assert_eq!(attribute("format").as_deref(), Some("appended"), "{tag}");
        let at = start + attribute("offset").unwrap().parse::<usize>().unwrap();
        let length = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) as usize;
        let name = attribute("Name").unwrap_or_default();
        arrays.push((section.clone(), name, bytes[at + 8..at + 8 + length].to_vec()));
    }
    arrays
}

/// A binary .vtu file's arrays as [`Vtu`].
fn binary_vtu(bytes: &[u8]) -> Vtu {
    let floats = |b: &[u8]| -> Vec<f64> {
        b.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
    };
    let ints = |b: &[u8]| -> Vec<i64> {
        b.chunks_exact(8).map(|c| i64::from_le_bytes(c.try_into().unwrap())).collect()
    };
    let arrays = appended_arrays(bytes);
    let find = |section: &str, name: &str| {
        arrays.iter().find(|a| a.0 == section && a.1 == name).map(|a| a.2.clone()).unwrap()
    };
    let data = |section: &str| -> Vec<(String, Vec<f64>)> {
        arrays.iter().filter(|a| a.0 == section).map(|a| (a.1.clone(), floats(&a.2))).collect()
    };
    let coordinates = floats(&find("Points", ""));
    let offsets = ints(&find("Cells", "offsets"));
    Vtu {
        binary: true,
        points: coordinates.len() / 3,
        cells: offsets.len(),
        coordinates,
        connectivity: ints(&find("Cells", "connectivity")),
        point_data: data("PointData"),
        cell_data: data("CellData"),
    }
}

/// Whether every number of a .vtu file (coordinates and fields) is finite.
pub fn finite_vtu(path: &Path) -> bool {
    let vtu = read_vtu(path);
    let fields = vtu.point_data.iter().chain(&vtu.cell_data).flat_map(|(_, v)| v);
    vtu.coordinates.iter().chain(fields).all(|x| x.is_finite())
}

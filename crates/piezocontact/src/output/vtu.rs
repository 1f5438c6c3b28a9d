//! ASCII VTK UnstructuredGrid (`.vtu`) output that ParaView opens: nodes (padded to 3D),
//! cells (VTK_TRIANGLE = 5, VTK_TETRA = 10), point data and cell data; and the collection
//! (`.pvd`) of a loading path's files.

use crate::mesh::Mesh;
use std::fmt::Write;

/// A named field with its number of components.
pub struct Field<'a> {
    /// Field name, shown in ParaView (paper symbols: `u`, `phi`, `sigma`, `D`).
    pub name: &'a str,
    /// Components per point or cell (1, 3 or 9).
    pub components: usize,
    /// Values, `components` per point or cell.
    pub values: &'a [f64],
}

/// Writes the mesh with point and cell fields as a VTU document.
pub fn to_vtu(mesh: &Mesh, point_data: &[Field], cell_data: &[Field]) -> String {
    let (n_points, n_cells, dim) = (mesh.n_nodes(), mesh.n_cells(), mesh.dim());
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0"?>"#);
    let _ =
        writeln!(s, r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">"#);
    let _ = writeln!(s, "<UnstructuredGrid>");
    let _ = writeln!(s, r#"<Piece NumberOfPoints="{n_points}" NumberOfCells="{n_cells}">"#);
    let _ =
        writeln!(s, r#"<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">"#);
    for i in 0..n_points {
        let x = mesh.node(i);
        let z = if dim == 3 { x[2] } else { 0.0 };
        let _ = writeln!(s, "{:e} {:e} {:e}", x[0], x[1], z);
    }
    let _ = writeln!(s, "</DataArray></Points>");
    let _ = writeln!(s, "<Cells>");
    let _ = writeln!(s, r#"<DataArray type="Int64" Name="connectivity" format="ascii">"#);
    for c in 0..n_cells {
        let line: Vec<String> = mesh.cell(c).iter().map(|n| n.to_string()).collect();
        let _ = writeln!(s, "{}", line.join(" "));
    }
    let _ = writeln!(s, "</DataArray>");
    let _ = writeln!(s, r#"<DataArray type="Int64" Name="offsets" format="ascii">"#);
    let offsets: Vec<String> = (1..=n_cells).map(|c| (c * (dim + 1)).to_string()).collect();
    let _ = writeln!(s, "{}\n</DataArray>", offsets.join(" "));
    let _ = writeln!(s, r#"<DataArray type="UInt8" Name="types" format="ascii">"#);
    let vtk_type = if dim == 2 { "5" } else { "10" };
    let _ = writeln!(s, "{}\n</DataArray>", vec![vtk_type; n_cells].join(" "));
    let _ = writeln!(s, "</Cells>");
    write_data(&mut s, "PointData", point_data);
    write_data(&mut s, "CellData", cell_data);
    let _ = writeln!(s, "</Piece>\n</UnstructuredGrid>\n</VTKFile>");
    s
}

fn write_data(s: &mut String, tag: &str, fields: &[Field]) {
    let _ = writeln!(s, "<{tag}>");
    for f in fields {
        let _ = writeln!(
            s,
            r#"<DataArray type="Float64" Name="{}" NumberOfComponents="{}" format="ascii">"#,
            f.name, f.components
        );
        for chunk in f.values.chunks(f.components) {
            let line: Vec<String> = chunk.iter().map(|v| format!("{v:e}")).collect();
            let _ = writeln!(s, "{}", line.join(" "));
        }
        let _ = writeln!(s, "</DataArray>");
    }
    let _ = writeln!(s, "</{tag}>");
}

/// A ParaView collection of the steps' files, the step number as its time.
pub fn pvd(files: &[(usize, String)]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n",
    );
    for (step, name) in files {
        s += &format!("<DataSet timestep=\"{step}\" group=\"\" part=\"0\" file=\"{name}\"/>\n");
    }
    s + "</Collection>\n</VTKFile>\n"
}

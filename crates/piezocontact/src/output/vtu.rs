//! VTK UnstructuredGrid (`.vtu`) output that ParaView opens: nodes (padded to 3D), cells
//! (VTK_TRIANGLE = 5, VTK_TETRA = 10), point data and cell data — in ParaView's binary
//! encoding (appended raw data) by default, or as ASCII text; and the collection (`.pvd`) of
//! a loading path's files.
//!
//! The binary file is the XML header, each DataArray `format="appended"` with its `offset`,
//! then `<AppendedData encoding="raw">_` and the arrays one after the other, each a UInt64
//! byte count and its values, little-endian (`header_type="UInt64"`): the numbers written
//! bit for bit, at the disk's speed. The ASCII file writes each number in the shortest form
//! that reads back to the same bits.

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

/// How a `.vtu` file holds its numbers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Encoding {
    /// ParaView's appended raw data: the numbers' bytes after the XML.
    #[default]
    Binary,
    /// Text: every number written out, readable, several times larger and slower.
    Ascii,
}

/// One array's values, as they are written.
enum Values<'a> {
    Float(&'a [f64]),
    Int(Vec<i64>),
    Byte(Vec<u8>),
}

impl Values<'_> {
    fn type_name(&self) -> &'static str {
        match self {
            Values::Float(_) => "Float64",
            Values::Int(_) => "Int64",
            Values::Byte(_) => "UInt8",
        }
    }

    fn byte_len(&self) -> usize {
        match self {
            Values::Float(v) => 8 * v.len(),
            Values::Int(v) => 8 * v.len(),
            Values::Byte(v) => v.len(),
        }
    }

    /// The values as text, `per_line` on each line.
    fn ascii(&self, per_line: usize, s: &mut String) {
        let words: Box<dyn Iterator<Item = String>> = match self {
            Values::Float(v) => Box::new(v.iter().map(|x| format!("{x:e}"))),
            Values::Int(v) => Box::new(v.iter().map(|x| x.to_string())),
            Values::Byte(v) => Box::new(v.iter().map(|x| x.to_string())),
        };
        for (k, word) in words.enumerate() {
            s.push_str(&word);
            s.push(if (k + 1).is_multiple_of(per_line) { '\n' } else { ' ' });
        }
        if !s.ends_with('\n') {
            s.push('\n');
        }
    }

    /// The values' little-endian bytes after their UInt64 byte count.
    fn append_to(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&(self.byte_len() as u64).to_le_bytes());
        match self {
            Values::Float(v) => v.iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            Values::Int(v) => v.iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            Values::Byte(v) => out.extend_from_slice(v),
        }
    }
}

/// A document being written: the XML, and in binary the appended arrays.
struct Document {
    encoding: Encoding,
    xml: String,
    appended: Vec<u8>,
}

impl Document {
    /// A DataArray with `attributes` (name, components) holding `values`.
    fn array(&mut self, attributes: &str, values: Values, per_line: usize) {
        let kind = values.type_name();
        match self.encoding {
            Encoding::Ascii => {
                let _ =
                    writeln!(self.xml, r#"<DataArray type="{kind}"{attributes} format="ascii">"#);
                values.ascii(per_line, &mut self.xml);
                self.xml.push_str("</DataArray>\n");
            }
            Encoding::Binary => {
                let offset = self.appended.len();
                let _ = writeln!(
                    self.xml,
                    r#"<DataArray type="{kind}"{attributes} format="appended" offset="{offset}"/>"#
                );
                values.append_to(&mut self.appended);
            }
        }
    }

    fn fields(&mut self, tag: &str, fields: &[Field]) {
        let _ = writeln!(self.xml, "<{tag}>");
        for f in fields {
            let attributes = format!(r#" Name="{}" NumberOfComponents="{}""#, f.name, f.components);
            self.array(&attributes, Values::Float(f.values), f.components);
        }
        let _ = writeln!(self.xml, "</{tag}>");
    }

    fn finish(self) -> Vec<u8> {
        let mut out = self.xml.into_bytes();
        if self.encoding == Encoding::Binary {
            out.extend_from_slice(b"<AppendedData encoding=\"raw\">\n_");
            out.extend_from_slice(&self.appended);
            out.extend_from_slice(b"\n</AppendedData>\n");
        }
        out.extend_from_slice(b"</VTKFile>\n");
        out
    }
}

/// Writes the mesh with point and cell fields as a VTU document in `encoding`.
pub fn to_vtu(
    mesh: &Mesh,
    point_data: &[Field],
    cell_data: &[Field],
    encoding: Encoding,
) -> Vec<u8> {
    let (n_points, n_cells, dim) = (mesh.n_nodes(), mesh.n_cells(), mesh.dim());
    let header = match encoding {
        Encoding::Ascii => "",
        Encoding::Binary => r#" header_type="UInt64""#,
    };
    let mut doc = Document { encoding, xml: String::new(), appended: Vec::new() };
    let _ = writeln!(doc.xml, r#"<?xml version="1.0"?>"#);
    let _ = writeln!(
        doc.xml,
        r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian"{header}>"#
    );
    let _ = writeln!(doc.xml, "<UnstructuredGrid>");
    let _ = writeln!(doc.xml, r#"<Piece NumberOfPoints="{n_points}" NumberOfCells="{n_cells}">"#);
    let points: Vec<f64> = (0..n_points)
        .flat_map(|i| {
            let x = mesh.node(i);
            [x[0], x[1], if dim == 3 { x[2] } else { 0.0 }]
        })
        .collect();
    doc.xml.push_str("<Points>\n");
    doc.array(r#" NumberOfComponents="3""#, Values::Float(&points), 3);
    doc.xml.push_str("</Points>\n<Cells>\n");
    let connectivity = (0..n_cells).flat_map(|c| mesh.cell(c).iter().map(|&n| n as i64));
    doc.array(r#" Name="connectivity""#, Values::Int(connectivity.collect()), dim + 1);
    let offsets = (1..=n_cells).map(|c| (c * (dim + 1)) as i64).collect();
    doc.array(r#" Name="offsets""#, Values::Int(offsets), usize::MAX);
    let vtk_type = if dim == 2 { 5 } else { 10 };
    doc.array(r#" Name="types""#, Values::Byte(vec![vtk_type; n_cells]), usize::MAX);
    doc.xml.push_str("</Cells>\n");
    doc.fields("PointData", point_data);
    doc.fields("CellData", cell_data);
    doc.xml.push_str("</Piece>\n</UnstructuredGrid>\n");
    doc.finish()
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

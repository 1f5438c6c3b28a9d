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
use std::io::{self, Write};

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

/// One array's values as they are written: how many, and the numbers, each read once (the
/// arrays are streamed to the file, never held whole as bytes).
enum Values<'a> {
    Float(usize, Box<dyn Iterator<Item = f64> + 'a>),
    Int(usize, Box<dyn Iterator<Item = i64> + 'a>),
    Byte(usize, Box<dyn Iterator<Item = u8> + 'a>),
}

impl Values<'_> {
    fn type_name(&self) -> &'static str {
        match self {
            Values::Float(..) => "Float64",
            Values::Int(..) => "Int64",
            Values::Byte(..) => "UInt8",
        }
    }

    fn byte_len(&self) -> usize {
        match self {
            Values::Float(n, _) | Values::Int(n, _) => 8 * n,
            Values::Byte(n, _) => *n,
        }
    }

    /// The values as text, `per_line` on each line.
    fn write_ascii(self, per_line: usize, out: &mut dyn Write) -> io::Result<()> {
        let mut k = 0;
        let mut word = |out: &mut dyn Write, word: std::fmt::Arguments| {
            k += 1;
            let end = if k % per_line == 0 { '\n' } else { ' ' };
            write!(out, "{word}{end}")
        };
        match self {
            Values::Float(_, v) => {
                v.into_iter().try_for_each(|x| word(out, format_args!("{x:e}")))?
            }
            Values::Int(_, v) => v.into_iter().try_for_each(|x| word(out, format_args!("{x}")))?,
            Values::Byte(_, v) => v.into_iter().try_for_each(|x| word(out, format_args!("{x}")))?,
        }
        if k % per_line != 0 {
            out.write_all(b"\n")?;
        }
        Ok(())
    }

    /// The values' little-endian bytes after their UInt64 byte count.
    fn write_raw(self, out: &mut dyn Write) -> io::Result<()> {
        out.write_all(&(self.byte_len() as u64).to_le_bytes())?;
        match self {
            Values::Float(_, v) => v.into_iter().try_for_each(|x| out.write_all(&x.to_le_bytes())),
            Values::Int(_, v) => v.into_iter().try_for_each(|x| out.write_all(&x.to_le_bytes())),
            Values::Byte(_, v) => v.into_iter().try_for_each(|x| out.write_all(&[x])),
        }
    }
}

/// A DataArray: its attributes (name, components), values, and numbers per line in text.
struct Array<'a> {
    attributes: String,
    values: Values<'a>,
    per_line: usize,
}

/// A document's parts in order: XML text and the arrays between.
enum Part<'a> {
    Xml(String),
    Array(Array<'a>),
}

/// The parts of a field section (`PointData`, `CellData`).
fn field_parts<'a>(tag: &str, fields: &[Field<'a>], parts: &mut Vec<Part<'a>>) {
    parts.push(Part::Xml(format!("<{tag}>\n")));
    for f in fields {
        let attributes = format!(r#" Name="{}" NumberOfComponents="{}""#, f.name, f.components);
        let values = Values::Float(f.values.len(), Box::new(f.values.iter().copied()));
        parts.push(Part::Array(Array { attributes, values, per_line: f.components }));
    }
    parts.push(Part::Xml(format!("</{tag}>\n")));
}

/// Writes the parts in `encoding`: in text each array inside its DataArray element; in
/// binary the XML first, each DataArray with the offset of its bytes, then the bytes.
fn write_parts(parts: Vec<Part>, encoding: Encoding, out: &mut dyn Write) -> io::Result<()> {
    let mut offset = 0;
    let mut appended = Vec::new();
    for part in parts {
        let array = match part {
            Part::Xml(xml) => {
                out.write_all(xml.as_bytes())?;
                continue;
            }
            Part::Array(array) => array,
        };
        let (kind, attributes) = (array.values.type_name(), &array.attributes);
        match encoding {
            Encoding::Ascii => {
                writeln!(out, r#"<DataArray type="{kind}"{attributes} format="ascii">"#)?;
                array.values.write_ascii(array.per_line, out)?;
                out.write_all(b"</DataArray>\n")?;
            }
            Encoding::Binary => {
                let format = format!(r#"format="appended" offset="{offset}""#);
                writeln!(out, r#"<DataArray type="{kind}"{attributes} {format}/>"#)?;
                offset += 8 + array.values.byte_len();
                appended.push(array.values);
            }
        }
    }
    if encoding == Encoding::Binary {
        out.write_all(b"<AppendedData encoding=\"raw\">\n_")?;
        appended.into_iter().try_for_each(|values| values.write_raw(out))?;
        out.write_all(b"\n</AppendedData>\n")?;
    }
    out.write_all(b"</VTKFile>\n")
}

/// Writes the mesh with point and cell fields as a VTU document in `encoding` to `out`,
/// array by array (nothing of the size of the file is held).
pub fn write_vtu(
    mesh: &Mesh,
    (point_data, cell_data): (&[Field], &[Field]),
    encoding: Encoding,
    out: &mut dyn Write,
) -> io::Result<()> {
    let (n_points, n_cells, dim) = (mesh.n_nodes(), mesh.n_cells(), mesh.dim());
    let header = match encoding {
        Encoding::Ascii => "",
        Encoding::Binary => r#" header_type="UInt64""#,
    };
    let version = r#"type="UnstructuredGrid" version="1.0" byte_order="LittleEndian""#;
    let mut parts = vec![Part::Xml(format!(
        "<?xml version=\"1.0\"?>\n<VTKFile {version}{header}>\n<UnstructuredGrid>\n\
         <Piece NumberOfPoints=\"{n_points}\" NumberOfCells=\"{n_cells}\">\n<Points>\n"
    ))];
    let points = (0..n_points).flat_map(|i| {
        let x = mesh.node(i);
        [x[0], x[1], if dim == 3 { x[2] } else { 0.0 }]
    });
    let array = |attributes: &str, values, per_line| {
        Part::Array(Array { attributes: attributes.to_string(), values, per_line })
    };
    parts.push(array(
        r#" NumberOfComponents="3""#,
        Values::Float(3 * n_points, Box::new(points)),
        3,
    ));
    parts.push(Part::Xml("</Points>\n<Cells>\n".into()));
    let connectivity = (0..n_cells).flat_map(|c| mesh.cell(c).iter().map(|&n| n as i64));
    let connectivity = Values::Int(n_cells * (dim + 1), Box::new(connectivity));
    parts.push(array(r#" Name="connectivity""#, connectivity, dim + 1));
    let offsets = (1..=n_cells).map(move |c| (c * (dim + 1)) as i64);
    parts.push(array(r#" Name="offsets""#, Values::Int(n_cells, Box::new(offsets)), usize::MAX));
    let vtk_type = if dim == 2 { 5 } else { 10 };
    let types = Values::Byte(n_cells, Box::new(std::iter::repeat_n(vtk_type, n_cells)));
    parts.push(array(r#" Name="types""#, types, usize::MAX));
    parts.push(Part::Xml("</Cells>\n".into()));
    field_parts("PointData", point_data, &mut parts);
    field_parts("CellData", cell_data, &mut parts);
    parts.push(Part::Xml("</Piece>\n</UnstructuredGrid>\n".into()));
    write_parts(parts, encoding, out)
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

//! Gmsh MSH 4.1 input (ASCII and binary) through the `mshio` crate.
//!
//! Cells are the elements of the highest dimension (linear triangles in 2D, linear tetrahedra
//! in 3D); each physical group of dimension d − 1 becomes a boundary part named by its
//! physical name (or by its tag when it has none), and each of dimension d a region (a set of
//! cells, for materials). `mshio` does not read `$PhysicalNames`, so
//! that section, ASCII in both encodings, is read here.

use super::{BoundaryPart, Mesh, Region};
use crate::error::{Error, Result};
use mshio::mshfile::ElementType;
use std::collections::{BTreeMap, HashMap};

/// A physical group of a Gmsh file.
#[derive(Clone, Debug, PartialEq)]
pub struct PhysicalGroup {
    /// Dimension of its entities (0 points, 1 curves, 2 surfaces, 3 volumes).
    pub dim: i32,
    /// Physical tag.
    pub tag: i32,
    /// Physical name, or the tag as text when the group has no name.
    pub name: String,
    /// Number of elements in the group.
    pub elements: usize,
}

/// What a Gmsh file holds, for `piezocontact mesh-info`.
#[derive(Clone, Debug)]
pub struct GmshInfo {
    /// Whether the file is binary.
    pub binary: bool,
    /// Number of nodes.
    pub nodes: usize,
    /// Element counts by type name (`Tri3`, `Lin2`, ...) and dimension.
    pub elements: Vec<(String, i32, usize)>,
    /// Physical groups, sorted by dimension and tag.
    pub groups: Vec<PhysicalGroup>,
}

type MshFile = mshio::MshFile<u64, i32, f64>;
/// Physical names keyed by (dimension, physical tag).
type PhysicalNames = HashMap<(i32, i32), String>;

/// Reads what a Gmsh file holds without building a mesh.
pub fn inspect(bytes: &[u8]) -> Result<GmshInfo> {
    let (msh, names) = parse(bytes)?;
    let mut elements: BTreeMap<(i32, String), usize> = BTreeMap::new();
    for block in blocks(&msh) {
        *elements.entry((block.entity_dim, format!("{:?}", block.element_type))).or_default() +=
            block.elements.len();
    }
    Ok(GmshInfo {
        binary: msh.header.file_type == 1,
        nodes: msh.total_node_count(),
        elements: elements.into_iter().map(|((dim, name), n)| (name, dim, n)).collect(),
        groups: physical_groups(&msh, &names),
    })
}

/// What a physical group of dimension `dim` is when a case names it as a boundary part.
fn other_group(dim: i32) -> String {
    let kind = match dim {
        0 => "points",
        1 => "curves",
        2 => "surfaces",
        _ => "volumes",
    };
    format!("a physical group of {kind} (dimension {dim}) in the mesh file, not of facets")
}

/// Reads a Gmsh MSH 4.1 file into a checked [`Mesh`].
pub fn read(bytes: &[u8]) -> Result<Mesh> {
    let (msh, names) = parse(bytes)?;
    let dim = blocks(&msh).map(|b| b.entity_dim).max().unwrap_or(0);
    if dim != 2 && dim != 3 {
        return Err(Error::NoCells {
            dim: 2,
            what: format!(
                "the file's highest element dimension is {dim}; piezocontact needs triangles \
                 (2D) or tetrahedra (3D) — add a Physical Surface or Physical Volume for the body"
            ),
        });
    }
    let (coords, index) = nodes(&msh, dim as usize)?;
    let node_index = |tag: u64| {
        index.get(&tag).copied().ok_or_else(|| {
            Error::Gmsh(format!(
                "an element refers to node tag {tag}, which the file does not define"
            ))
        })
    };
    let (cell_type, facet_type) = if dim == 2 {
        (ElementType::Tri3, ElementType::Lin2)
    } else {
        (ElementType::Tet4, ElementType::Tri3)
    };
    let tags = entity_physical_tags(&msh);
    let mut cells = Vec::new();
    let mut facets: BTreeMap<i32, Vec<usize>> = BTreeMap::new();
    let mut regions: BTreeMap<i32, Vec<usize>> = BTreeMap::new();
    for block in blocks(&msh) {
        let wanted = if block.entity_dim == dim {
            cell_type
        } else if block.entity_dim == dim - 1 {
            facet_type
        } else {
            continue;
        };
        if block.element_type != wanted {
            return Err(Error::GmshUnsupported(format!(
                "{:?} elements of dimension {}: piezocontact uses linear {} (mesh with \
                 Mesh.ElementOrder = 1 and without recombination)",
                block.element_type,
                block.entity_dim,
                if dim == 2 { "triangles and segments" } else { "tetrahedra and triangles" }
            )));
        }
        let flat = element_nodes(block, wanted, &node_index)?;
        if block.entity_dim == dim {
            let first = cells.len() / (dim as usize + 1);
            cells.extend(flat);
            let last = cells.len() / (dim as usize + 1);
            for &g in tags.get(&(block.entity_dim, block.entity_tag)).into_iter().flatten() {
                regions.entry(g).or_default().extend(first..last);
            }
        } else if let Some(groups) = tags.get(&(block.entity_dim, block.entity_tag)) {
            for &g in groups {
                facets.entry(g).or_default().extend_from_slice(&flat);
            }
        }
    }
    let parts = facets
        .into_iter()
        .map(|(tag, f)| BoundaryPart::new(group_name(&names, dim - 1, tag), f))
        .collect();
    let others = physical_groups(&msh, &names).into_iter().filter(|g| g.dim != dim - 1);
    let others = others.map(|g| (g.name, other_group(g.dim))).collect();
    let regions = regions
        .into_iter()
        .map(|(tag, cells)| Region { name: group_name(&names, dim, tag), cells })
        .collect();
    Mesh::new(dim as usize, coords, cells, parts)?.with_other_groups(others).with_regions(regions)
}

/// The node indices of a block's elements, `wanted`'s count per element.
fn element_nodes(
    block: &mshio::mshfile::ElementBlock<u64, i32>,
    wanted: ElementType,
    node_index: &impl Fn(u64) -> Result<usize>,
) -> Result<Vec<usize>> {
    let mut flat = Vec::with_capacity(block.elements.len() * wanted_nodes(wanted));
    for element in &block.elements {
        if element.nodes.len() != wanted_nodes(wanted) {
            return Err(Error::Gmsh(format!(
                "element {} has {} nodes, a {:?} has {}",
                element.element_tag,
                element.nodes.len(),
                wanted,
                wanted_nodes(wanted)
            )));
        }
        for &tag in &element.nodes {
            flat.push(node_index(tag)?);
        }
    }
    Ok(flat)
}

/// A triangulated surface: points (3 coordinates) and triangles of point indices.
pub type Triangulation = (Vec<[f64; 3]>, Vec<[usize; 3]>);

/// The triangles of a Gmsh MSH 4.1 file (a surface mesh: every 3-node triangle of it).
pub fn read_triangles(bytes: &[u8]) -> Result<Triangulation> {
    let (msh, _) = parse(bytes)?;
    let (coords, index) = nodes(&msh, 3)?;
    let points = coords.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    let mut triangles = Vec::new();
    for block in blocks(&msh).filter(|b| b.element_type == ElementType::Tri3) {
        for element in &block.elements {
            let mut t = [0; 3];
            for (slot, tag) in t.iter_mut().zip(&element.nodes) {
                *slot = *index.get(tag).ok_or_else(|| {
                    Error::Gmsh(format!(
                        "an element refers to node tag {tag}, which the file does not define"
                    ))
                })?;
            }
            triangles.push(t);
        }
    }
    Ok((points, triangles))
}

fn wanted_nodes(t: ElementType) -> usize {
    match t {
        ElementType::Lin2 => 2,
        ElementType::Tri3 => 3,
        _ => 4,
    }
}

fn blocks(msh: &MshFile) -> impl Iterator<Item = &mshio::mshfile::ElementBlock<u64, i32>> {
    msh.data.elements.iter().flat_map(|e| e.element_blocks.iter())
}

/// Checks the format line, then parses with mshio and reads the physical names.
fn parse(bytes: &[u8]) -> Result<(MshFile, PhysicalNames)> {
    let header = section(bytes, "MeshFormat")
        .ok_or_else(|| Error::Gmsh("not a Gmsh MSH file: it has no $MeshFormat section".into()))?;
    let words: Vec<&str> = header.split_whitespace().collect();
    let version = words.first().copied().unwrap_or("").to_string();
    if version != "4.1" {
        return Err(Error::GmshUnsupported(format!(
            "MSH version {version}; piezocontact reads MSH 4.1 (ASCII or binary): re-export with \
             `gmsh -format msh41` or set Mesh.MshFileVersion = 4.1 in the .geo file"
        )));
    }
    // mshio does not check these and stops the program on values it has no parser for.
    match (words.get(1), words.get(2)) {
        (Some(&("0" | "1")), Some(&("4" | "8"))) => {}
        _ => {
            return Err(Error::Gmsh(format!(
                "the $MeshFormat line '{}' is not 'version file-type data-size' with file-type 0 \
                 (ASCII) or 1 (binary) and data-size 4 or 8",
                header.trim()
            )));
        }
    }
    let parsed =
        std::panic::catch_unwind(|| mshio::parse_msh_bytes(bytes).map_err(|e| e.to_string()));
    let msh = match parsed {
        Ok(Ok(msh)) => msh,
        Ok(Err(text)) => {
            let summary: Vec<&str> =
                text.lines().filter(|l| !l.trim().is_empty()).take(6).collect();
            return Err(Error::Gmsh(summary.join("; ")));
        }
        Err(_) => return Err(Error::Gmsh("the MSH parser failed on malformed content".into())),
    };
    Ok((msh, physical_names(bytes)?))
}

/// The text between `$Name` and `$EndName`, if present and valid UTF-8.
fn section<'a>(bytes: &'a [u8], name: &str) -> Option<&'a str> {
    let start_tag = format!("${name}");
    let end_tag = format!("$End{name}");
    let start = find(bytes, start_tag.as_bytes())? + start_tag.len();
    let end = start + find(&bytes[start..], end_tag.as_bytes())?;
    std::str::from_utf8(&bytes[start..end]).ok()
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}

/// Parses `$PhysicalNames`: a count, then lines `dim tag "name"`.
fn physical_names(bytes: &[u8]) -> Result<PhysicalNames> {
    let Some(text) = section(bytes, "PhysicalNames") else {
        return Ok(HashMap::new());
    };
    let bad = |line: &str| Error::Gmsh(format!("malformed $PhysicalNames line '{line}'"));
    let mut names = HashMap::new();
    for line in text.lines().map(str::trim).filter(|l| !l.is_empty()).skip(1) {
        let mut words = line.splitn(3, char::is_whitespace);
        let dim = words.next().and_then(|w| w.parse().ok()).ok_or_else(|| bad(line))?;
        let tag = words.next().and_then(|w| w.parse().ok()).ok_or_else(|| bad(line))?;
        let name = words.next().ok_or_else(|| bad(line))?.trim().trim_matches('"');
        names.insert((dim, tag), name.to_string());
    }
    Ok(names)
}

fn group_name(names: &PhysicalNames, dim: i32, tag: i32) -> String {
    names.get(&(dim, tag)).cloned().unwrap_or_else(|| tag.to_string())
}

/// Physical tags of every entity, keyed by (dimension, entity tag).
fn entity_physical_tags(msh: &MshFile) -> HashMap<(i32, i32), Vec<i32>> {
    let mut tags = HashMap::new();
    if let Some(e) = &msh.data.entities {
        tags.extend(e.points.iter().map(|p| ((0, p.tag), p.physical_tags.clone())));
        tags.extend(e.curves.iter().map(|c| ((1, c.tag), c.physical_tags.clone())));
        tags.extend(e.surfaces.iter().map(|s| ((2, s.tag), s.physical_tags.clone())));
        tags.extend(e.volumes.iter().map(|v| ((3, v.tag), v.physical_tags.clone())));
    }
    tags
}

fn physical_groups(msh: &MshFile, names: &PhysicalNames) -> Vec<PhysicalGroup> {
    let tags = entity_physical_tags(msh);
    let mut count: BTreeMap<(i32, i32), usize> = BTreeMap::new();
    for (&(dim, _), groups) in &tags {
        for &g in groups {
            count.entry((dim, g)).or_default();
        }
    }
    for block in blocks(msh) {
        for &g in tags.get(&(block.entity_dim, block.entity_tag)).into_iter().flatten() {
            *count.entry((block.entity_dim, g)).or_default() += block.elements.len();
        }
    }
    count
        .into_iter()
        .map(|((dim, tag), elements)| PhysicalGroup {
            dim,
            tag,
            name: group_name(names, dim, tag),
            elements,
        })
        .collect()
}

/// The error for a node of a mesh without tetrahedra off the plane z = 0: a 2D mesh that is
/// not plane, or — when the file has volumes — a 3D body whose Physical Volume is missing,
/// so that Gmsh saved only the triangles of its physical surfaces.
fn off_plane(msh: &MshFile, tag: u64, z: f64) -> Error {
    let volumes = msh.data.entities.as_ref().is_some_and(|e| !e.volumes.is_empty());
    let fix = if volumes {
        "; the file has volumes, not meshed in it: add a Physical Volume for the body (Gmsh \
         saves only the elements of physical groups once any is defined)"
    } else {
        ""
    };
    Error::GmshUnsupported(format!(
        "node {tag} has z = {z} in a mesh without tetrahedra: a 2D mesh must lie in the plane \
         z = 0{fix}"
    ))
}

/// Node coordinates (`dim` per node) and the map from node tag to index.
fn nodes(msh: &MshFile, dim: usize) -> Result<(Vec<f64>, HashMap<u64, usize>)> {
    let nodes = msh
        .data
        .nodes
        .as_ref()
        .ok_or_else(|| Error::Gmsh("the file has no $Nodes section".into()))?;
    let mut coords = Vec::new();
    let mut index = HashMap::new();
    let mut next_tag = nodes.min_node_tag;
    for block in &nodes.node_blocks {
        let mut tags: Vec<(u64, usize)> = match &block.node_tags {
            Some(map) => map.iter().map(|(&t, &i)| (t, i)).collect(),
            None => (0..block.nodes.len()).map(|i| (next_tag + i as u64, i)).collect(),
        };
        next_tag += block.nodes.len() as u64;
        tags.sort_unstable_by_key(|&(_, i)| i);
        for (tag, i) in tags {
            let n = &block.nodes[i];
            if dim == 2 && n.z != 0.0 {
                return Err(off_plane(msh, tag, n.z));
            }
            if index.insert(tag, coords.len() / dim).is_some() {
                return Err(Error::Gmsh(format!("node tag {tag} is defined twice")));
            }
            coords.extend_from_slice(&[n.x, n.y, n.z][..dim]);
        }
    }
    Ok((coords, index))
}

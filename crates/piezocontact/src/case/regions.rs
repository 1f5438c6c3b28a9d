//! The body's materials by region: each `[[material]]` fills the regions it names (physical
//! groups of dimension d of a mesh file, or the rectangle's `[mesh.regions]` boxes), and every
//! cell belongs to exactly one material.

use super::file::Case;
use super::material::Table;
use crate::error::Result;
use crate::material::Materials;
use crate::mesh::rectangle::Segment;
use crate::mesh::{Mesh, Region};

/// No cell's material yet.
const UNSET: usize = usize::MAX;

/// The material and the region that fill each cell so far.
struct Filled<'a> {
    of_cell: Vec<usize>,
    region: Vec<&'a str>,
}

impl Case {
    /// The materials of the cells of `mesh`: one table without `regions` covers the body;
    /// otherwise each table names its regions, and a cell covered by none or by two is an
    /// error naming it.
    pub fn materials(&self, mesh: &Mesh) -> Result<Materials> {
        let tables = self.material_tables();
        let mut list = Vec::with_capacity(tables.len());
        for table in &tables {
            list.push(table.material(mesh.dim())?);
        }
        if tables.len() == 1 && tables[0].table.regions.is_none() {
            return Materials::new(list, Vec::new()).map_err(|e| self.context(e));
        }
        let mut filled =
            Filled { of_cell: vec![UNSET; mesh.n_cells()], region: vec![""; mesh.n_cells()] };
        for (k, table) in tables.iter().enumerate() {
            let name = self.several_name(&tables, k, mesh)?;
            for region in table.table.regions.iter().flatten() {
                for &c in &self.region(mesh, &table.key, region)?.cells {
                    if filled.of_cell[c] != UNSET {
                        let other = list[filled.of_cell[c]].name.as_str();
                        return Err(input!(
                            "{}: cell {c} is in region '{region}' of material '{name}' and in region '{}' of material '{other}': a cell belongs to one material",
                            self.locate(&table.key),
                            filled.region[c]
                        ));
                    }
                    (filled.of_cell[c], filled.region[c]) = (k, region.as_str());
                }
            }
        }
        let of_cell = filled.of_cell;
        if let Some(c) = of_cell.iter().position(|&k| k == UNSET) {
            let centroid = centroid(mesh, c);
            return Err(input!(
                "{}: cell {c} (centroid {centroid:?}) belongs to no material: name its region in a [[material]] (the mesh has {})",
                self.path().display(),
                region_names(mesh)
            ));
        }
        Materials::new(list, of_cell).map_err(|e| self.context(e))
    }

    /// The name of table k, checked: present where there are several, unique, and with
    /// regions.
    fn several_name<'t>(&self, tables: &'t [Table<'_>], k: usize, mesh: &Mesh) -> Result<&'t str> {
        let table = &tables[k];
        let at = self.locate(&table.key);
        let lone = (tables.len() == 1).then_some("material");
        let Some(name) = table.table.name.as_deref().or(lone) else {
            return Err(input!(
                "{at}: [[material]] number {} has no name: with several materials each needs name = \"...\" (outputs and overrides use it)",
                k + 1
            ));
        };
        if tables[..k].iter().any(|t| t.table.name.as_deref() == Some(name)) {
            return Err(input!("{at}: two materials are named '{name}': give each its own"));
        }
        if table.table.regions.is_none() {
            return Err(input!(
                "{at}: material '{name}' has no regions: with several materials each names the regions it fills (regions = [...], the mesh has {})",
                region_names(mesh)
            ));
        }
        Ok(name)
    }

    /// The region `name` of the mesh, or an error saying what the mesh has.
    fn region<'m>(&self, mesh: &'m Mesh, key: &str, name: &str) -> Result<&'m Region> {
        mesh.regions().iter().find(|r| r.name == name).ok_or_else(|| {
            let part = mesh.part_index(name).is_ok();
            let what = if part {
                format!("; '{name}' is a boundary part (dimension {}), not a set of cells", mesh.dim() - 1)
            } else {
                String::new()
            };
            input!(
                "{}: {key}.regions names '{name}', which is no region of the mesh (it has {}){what}",
                self.locate(&format!("{key}.regions")),
                region_names(mesh)
            )
        })
    }

    /// The mesh with the regions of `[mesh.regions]` beside its own (a file's volume
    /// groups): the cells whose centroid lies in one of each region's boxes.
    pub(super) fn with_box_regions(&self, mesh: Mesh) -> Result<Mesh> {
        let mut regions = mesh.regions().to_vec();
        for (name, specs) in &self.file.mesh.regions {
            let key = format!("mesh.regions.{name}");
            if regions.iter().any(|r| &r.name == name) {
                return Err(input!(
                    "{}: {key}: the mesh file has a region '{name}' already: give the boxes another name",
                    self.locate(&key)
                ));
            }
            let boxes: Result<Vec<Segment>, _> = specs.iter().map(|s| s.parse()).collect();
            let boxes = boxes.map_err(|e| input!("{}: {e}", self.locate(&key)))?;
            if boxes.is_empty() {
                return Err(input!(
                    "{}: {key} is empty: give the region its boxes, e.g. [\"[0,12]x[1,2]\"], or remove it",
                    self.locate(&key)
                ));
            }
            let cells: Vec<usize> = (0..mesh.n_cells())
                .filter(|&c| boxes.iter().any(|b| b.contains(&centroid(&mesh, c), 0.0)))
                .collect();
            if cells.is_empty() {
                return Err(input!(
                    "{}: {key} = {specs:?} holds no cell (a cell is in a box when its centroid is)",
                    self.locate(&key)
                ));
            }
            regions.push(Region { name: name.clone(), cells });
        }
        mesh.with_regions(regions).map_err(|e| self.context(e))
    }
}

/// The centroid of cell c.
fn centroid(mesh: &Mesh, c: usize) -> Vec<f64> {
    let nodes = mesh.cell(c);
    (0..mesh.dim())
        .map(|i| nodes.iter().map(|&n| mesh.node(n)[i]).sum::<f64>() / nodes.len() as f64)
        .collect()
}

/// The mesh's region names, for messages.
fn region_names(mesh: &Mesh) -> String {
    if mesh.regions().is_empty() {
        return format!(
            "no regions: add physical groups of dimension {} to the mesh file, or [mesh.regions] boxes to the rectangle",
            mesh.dim()
        );
    }
    let names: Vec<String> = mesh.regions().iter().map(|r| format!("'{}'", r.name)).collect();
    format!("the regions {}", names.join(", "))
}

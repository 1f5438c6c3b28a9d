//! Fill-reducing orderings of a [`SymmetricPattern`], with a list of unknowns kept last for
//! the Schur complement (model §11, §13):
//! - approximate minimum degree (faer's AMD) of the whole matrix, the kept unknowns then moved
//!   to the end;
//! - nested dissection (METIS's `NodeND`) of the graph of the pattern's groups — the nodes of
//!   the mesh, whose unknowns stay together — without the kept unknowns, which come last.
//!
//! An ordering is a permutation `order` of 0..n: `order[k]` is the unknown eliminated k-th.

use super::sparse::SymmetricPattern;
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::linalg::amd;
use std::sync::Mutex;

/// Stored entries per row of a pattern's lower half above which
/// [`Ordering::Auto`](super::Ordering::Auto) takes it for a 3D mesh's: P1 tetrahedra give about 30 (a node and its
/// ~14 neighbours, d + 1 unknowns each, halved), P1 triangles about 11.
pub const DENSE_ROWS: f64 = 20.0;

/// Whether `pattern` is that of a 3D mesh, by its entries per row.
pub fn three_dimensional(pattern: &SymmetricPattern) -> bool {
    pattern.nnz() as f64 > DENSE_ROWS * pattern.n() as f64
}

/// The spread of a 2D pattern's numbering above which [`Ordering::Auto`](super::Ordering::Auto)
/// orders it by nested dissection ([`spread`]): the built-in rectangle, numbered row by row,
/// gives 1.33; Gmsh's triangulations measured 39–124.
pub const SPREAD: f64 = 4.0;

/// Unknowns from which [`Ordering::Auto`](super::Ordering::Auto) may order a 2D pattern by
/// nested dissection.
pub const NESTED_2D: usize = 100_000;

/// Whether [`Ordering::Auto`](super::Ordering::Auto) orders `pattern` by nested dissection:
/// a 3D mesh's; a 2D mesh's of at least [`NESTED_2D`] unknowns numbered without locality
/// ([`spread`] above [`SPREAD`]). AMD's ties follow the numbering: on a grid numbered row by
/// row its factorisation cost was within 5 % of nested dissection's, on Gmsh's numbering
/// 1.5–2× it (model §13).
pub fn nested_pays(pattern: &SymmetricPattern) -> bool {
    if three_dimensional(pattern) {
        return true;
    }
    if pattern.n() < NESTED_2D {
        return false;
    }
    let spread = spread(pattern);
    log::debug!("2D pattern of {} unknowns, numbering spread {spread:.2}", pattern.n());
    spread > SPREAD
}

/// The mean distance in numbering between the groups (mesh nodes) that the pattern's entries
/// couple, in units of √groups: about 1 for a 2D grid numbered row by row, about √groups / 3
/// for a numbering without locality.
pub fn spread(pattern: &SymmetricPattern) -> f64 {
    let a = pattern.symbolic();
    let (mut sum, mut last) = (0.0, 0);
    for j in 0..pattern.n() {
        let h = pattern.group(j);
        last = last.max(h);
        for &i in &a.row_idx()[a.col_range(j)] {
            sum += pattern.group(i as usize).abs_diff(h) as f64;
        }
    }
    sum / pattern.nnz().max(1) as f64 / ((last + 1) as f64).sqrt()
}

/// METIS's API functions install and remove signal handlers through a global state of GKlib:
/// calls from several threads (a sweep) go one at a time.
static METIS: Mutex<()> = Mutex::new(());

/// Marks the unknowns of `last` (distinct, below n).
fn marks(n: usize, last: &[usize]) -> Result<Vec<bool>> {
    let mut is_last = vec![false; n];
    for &i in last {
        if i >= n || is_last[i] {
            return Err(Error::LinearAlgebra(format!("unknown {i} is repeated or not below {n}")));
        }
        is_last[i] = true;
    }
    Ok(is_last)
}

/// Every unknown not in `last` in the order an approximate minimum degree ordering of the
/// whole matrix gives them, then the unknowns of `last` in the given order. (Ordering the rest
/// by its own minimum degree gave 5 % more fill on the paper's bar with Γ3 last.)
pub fn amd_with_last(a: SymbolicSparseColMatRef<'_, usize>, last: &[usize]) -> Result<Vec<usize>> {
    let n = a.ncols();
    let is_last = marks(n, last)?;
    let (mut order, mut inverse) = (vec![0usize; n], vec![0usize; n]);
    let mut mem = MemBuffer::try_new(amd::order_scratch::<usize>(n, a.row_idx().len()))
        .map_err(|_| Error::LinearAlgebra("out of memory for the ordering".into()))?;
    amd::order(&mut order, &mut inverse, a, Default::default(), MemStack::new(&mut mem))
        .map_err(|e| Error::LinearAlgebra(format!("ordering: {e:?}")))?;
    order.retain(|&i| !is_last[i]);
    order.extend_from_slice(last);
    Ok(order)
}

/// Nested dissection of the pattern's group graph without the unknowns of `last`: each group's
/// other unknowns together (ascending) in the order METIS gives the groups, then `last`.
pub fn nested_dissection(pattern: &SymmetricPattern, last: &[usize]) -> Result<Vec<usize>> {
    let n = pattern.n();
    let is_last = marks(n, last)?;
    let (members, group_of) = groups(pattern, &is_last);
    let graph = Graph::new(pattern, &is_last, &group_of, members.len())?;
    let weights: Vec<i32> = members.iter().map(|m| m.len() as i32).collect();
    let group_order = graph.node_nd(weights)?;
    let mut order: Vec<usize> = group_order.into_iter().flat_map(|g| members[g].clone()).collect();
    order.extend_from_slice(last);
    Ok(order)
}

/// The groups of the unknowns not in `last`, numbered 0.. in order of first appearance: the
/// members of each (ascending), and each unknown's group (`usize::MAX` for those of `last`).
fn groups(pattern: &SymmetricPattern, is_last: &[bool]) -> (Vec<Vec<usize>>, Vec<usize>) {
    let mut index = std::collections::HashMap::new();
    let mut members: Vec<Vec<usize>> = Vec::new();
    let mut group_of = vec![usize::MAX; is_last.len()];
    for (i, slot) in group_of.iter_mut().enumerate().filter(|(i, _)| !is_last[*i]) {
        let next = members.len();
        let g = *index.entry(pattern.group(i)).or_insert(next);
        if g == next {
            members.push(Vec::new());
        }
        members[g].push(i);
        *slot = g;
    }
    (members, group_of)
}

/// A graph in METIS's compressed form.
struct Graph {
    xadj: Vec<i32>,
    adjncy: Vec<i32>,
}

impl Graph {
    /// The graph of `count` groups: g ~ h when an entry of the pattern couples an unknown of
    /// g with one of h (unknowns of `last` left out).
    fn new(
        pattern: &SymmetricPattern,
        is_last: &[bool],
        group_of: &[usize],
        count: usize,
    ) -> Result<Self> {
        let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); count];
        let a = pattern.symbolic();
        for j in (0..pattern.n()).filter(|&j| !is_last[j]) {
            let rows = a.row_idx()[a.col_range(j)].iter().map(|&i| i as usize);
            for i in rows.filter(|&i| !is_last[i]) {
                let (g, h) = (group_of[i], group_of[j]);
                if g != h {
                    neighbours[g].push(h);
                    neighbours[h].push(g);
                }
            }
        }
        let mut xadj = vec![0i32];
        let mut adjncy = Vec::new();
        for mut list in neighbours {
            list.sort_unstable();
            list.dedup();
            adjncy.extend(list.into_iter().map(|h| h as i32));
            let end = i32::try_from(adjncy.len()).map_err(|_| {
                Error::LinearAlgebra("the graph is too large for METIS's 32-bit indices".into())
            })?;
            xadj.push(end);
        }
        Ok(Self { xadj, adjncy })
    }

    /// METIS's nested dissection of the graph with vertex `weights`: the vertices in
    /// elimination order.
    fn node_nd(mut self, mut weights: Vec<i32>) -> Result<Vec<usize>> {
        let count = self.xadj.len() - 1;
        if count <= 1 {
            return Ok((0..count).collect());
        }
        let mut nvtxs = count as i32;
        let (mut perm, mut iperm) = (vec![0i32; count], vec![0i32; count]);
        let status = {
            let _one_at_a_time = METIS.lock().unwrap_or_else(|e| e.into_inner());
            // SAFETY: the arrays have the lengths METIS_NodeND requires (xadj n + 1, adjncy
            // xadj[n], vwgt, perm and iperm n) and outlive the call; options are the defaults.
            unsafe {
                metis_sys::METIS_NodeND(
                    &mut nvtxs,
                    self.xadj.as_mut_ptr(),
                    self.adjncy.as_mut_ptr(),
                    weights.as_mut_ptr(),
                    std::ptr::null_mut(),
                    perm.as_mut_ptr(),
                    iperm.as_mut_ptr(),
                )
            }
        };
        if status != metis_sys::rstatus_et_METIS_OK {
            return Err(Error::LinearAlgebra(format!("METIS_NodeND failed (status {status})")));
        }
        // perm[k] is the vertex at position k.
        Ok(perm.into_iter().map(|v| v as usize).collect())
    }
}

/// METIS's k-way partition of a graph into `parts` parts of about equal total weight, the
/// graph given by each vertex's neighbours (`adjacency.1[adjacency.0[v]..adjacency.0[v + 1]]`,
/// the vertex itself allowed), `weights[v]` the weight of vertex v: the part of each vertex.
/// Deterministic (METIS's fixed seed), so every process of a run computes the same.
pub fn partition(
    adjacency: (&[usize], &[usize]),
    weights: &[usize],
    parts: usize,
) -> Result<Vec<usize>> {
    let count = weights.len();
    if parts <= 1 || count <= parts {
        return Ok((0..count).map(|v| v * parts.max(1) / count.max(1)).collect());
    }
    let too_large =
        || Error::LinearAlgebra("the graph is too large for METIS's 32-bit indices".into());
    let (ptr, list) = adjacency;
    let mut xadj = vec![0i32];
    let mut adjncy = Vec::new();
    for v in 0..count {
        adjncy.extend(list[ptr[v]..ptr[v + 1]].iter().filter(|&&w| w != v).map(|&w| w as i32));
        xadj.push(i32::try_from(adjncy.len()).map_err(|_| too_large())?);
    }
    let mut vwgt: Vec<i32> = weights.iter().map(|&w| w.max(1) as i32).collect();
    let (mut nvtxs, mut ncon, mut nparts) = (count as i32, 1i32, parts as i32);
    let (mut objval, mut part) = (0i32, vec![0i32; count]);
    let status = {
        let _one_at_a_time = METIS.lock().unwrap_or_else(|e| e.into_inner());
        // SAFETY: the arrays have the lengths METIS_PartGraphKway requires (xadj n + 1, adjncy
        // xadj[n], vwgt and part n) and outlive the call; the null pointers take METIS's
        // defaults (no sizes or edge weights, equal parts, default options and seed).
        unsafe {
            metis_sys::METIS_PartGraphKway(
                &mut nvtxs,
                &mut ncon,
                xadj.as_mut_ptr(),
                adjncy.as_mut_ptr(),
                vwgt.as_mut_ptr(),
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                &mut nparts,
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                &mut objval,
                part.as_mut_ptr(),
            )
        }
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(Error::LinearAlgebra(format!("METIS_PartGraphKway failed (status {status})")));
    }
    Ok(part.into_iter().map(|p| p as usize).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pattern of a 2D grid Laplacian of `side` × `side` nodes with `per_node` unknowns
    /// each (all coupled), grouped by node.
    fn grid(side: usize, per_node: usize) -> SymmetricPattern {
        grid_numbered(side, per_node, &|k| k)
    }

    /// [`grid`] with the node numbered k row by row given the number `number(k)`.
    fn grid_numbered(
        side: usize,
        per_node: usize,
        number: &dyn Fn(usize) -> usize,
    ) -> SymmetricPattern {
        let node = |x: usize, y: usize| number(y * side + x);
        let mut positions = Vec::new();
        for y in 0..side {
            for x in 0..side {
                let a = node(x, y);
                let mut near = vec![a];
                if x + 1 < side {
                    near.push(node(x + 1, y));
                }
                if y + 1 < side {
                    near.push(node(x, y + 1));
                }
                for b in near {
                    for p in 0..per_node {
                        for q in 0..per_node {
                            let (i, j) = (b * per_node + p, a * per_node + q);
                            if i >= j {
                                positions.push((i, j));
                            } else if b != a {
                                positions.push((j, i));
                            }
                        }
                    }
                }
            }
        }
        let n = side * side * per_node;
        let groups = (0..n).map(|i| i / per_node).collect();
        SymmetricPattern::from_positions(n, &positions).unwrap().with_groups(groups).unwrap()
    }

    /// The spread of a grid numbered row by row is its mean coupling distance over √nodes,
    /// counted from its entries (each node with itself, its right and its upper neighbour);
    /// numbered without locality it is far larger. `auto` orders the first by AMD and the
    /// second by nested dissection (above [`NESTED_2D`] unknowns).
    #[test]
    fn the_spread_tells_a_grid_numbered_row_by_row_from_a_scattered_numbering() {
        let side = 190;
        let (nodes, pairs) = ((side * side) as f64, (side * (side - 1)) as f64);
        let sum = 9.0 * pairs * (1.0 + side as f64);
        let entries = 6.0 * nodes + 18.0 * pairs;
        let rows = grid(side, 3);
        assert!(rows.n() >= NESTED_2D);
        let expected = sum / entries / nodes.sqrt();
        assert!((spread(&rows) - expected).abs() < 1e-12, "{} {expected}", spread(&rows));
        assert!(expected < SPREAD);
        assert!(!nested_pays(&rows));
        // 7919 is prime to side², so k ↦ 7919 k mod side² numbers the nodes afresh.
        let scattered = grid_numbered(side, 3, &|k| k * 7919 % (side * side));
        assert!(spread(&scattered) > 10.0 * SPREAD, "{}", spread(&scattered));
        assert!(nested_pays(&scattered));
    }

    fn is_permutation(order: &[usize], n: usize) -> bool {
        let mut seen = vec![false; n];
        order.len() == n && order.iter().all(|&i| i < n && !std::mem::replace(&mut seen[i], true))
    }

    #[test]
    fn a_partition_balances_the_weights_and_cuts_few_edges() {
        // A 20 × 20 grid of nodes, each with its right and upper neighbours.
        let side = 20;
        let (mut ptr, mut list) = (vec![0], Vec::new());
        for v in 0..side * side {
            let (x, y) = (v % side, v / side);
            let near = [(x > 0).then(|| v - 1), (x + 1 < side).then(|| v + 1)];
            let far = [(y > 0).then(|| v - side), (y + 1 < side).then(|| v + side)];
            list.extend(near.into_iter().chain(far).flatten());
            ptr.push(list.len());
        }
        let weights = vec![3; side * side];
        for parts in [2, 3] {
            let part = partition((&ptr, &list), &weights, parts).unwrap();
            let sizes: Vec<usize> =
                (0..parts).map(|p| part.iter().filter(|&&q| q == p).count()).collect();
            assert!(sizes.iter().all(|&s| s.abs_diff(side * side / parts) <= side * side / 30));
            let cut = (0..side * side)
                .flat_map(|v| list[ptr[v]..ptr[v + 1]].iter().map(move |&w| (v, w)))
                .filter(|&(v, w)| part[v] != part[w])
                .count()
                / 2;
            // A straight cut of the grid is 20 edges per boundary; a scattered one hundreds.
            assert!(cut <= 2 * side * (parts - 1), "{parts} parts: {cut} edges cut");
            assert_eq!(part, partition((&ptr, &list), &weights, parts).unwrap());
        }
    }

    #[test]
    fn nested_dissection_keeps_nodes_together_and_the_kept_unknowns_last() {
        let pattern = grid(12, 3);
        let last = vec![5, 100, 7];
        for order in
            [nested_dissection(&pattern, &[]).unwrap(), nested_dissection(&pattern, &last).unwrap()]
        {
            assert!(is_permutation(&order, pattern.n()));
        }
        let order = nested_dissection(&pattern, &last).unwrap();
        assert_eq!(&order[order.len() - 3..], last.as_slice());
        // Without kept unknowns, each node's three unknowns are consecutive and ascending.
        let order = nested_dissection(&pattern, &[]).unwrap();
        for chunk in order.chunks(3) {
            assert_eq!((chunk[0] % 3, chunk[1], chunk[2]), (0, chunk[0] + 1, chunk[0] + 2));
        }
        assert!(nested_dissection(&pattern, &[5, 5]).is_err());
        let wide = pattern.wide();
        assert_eq!(amd_with_last(wide.as_ref(), &last).unwrap()[order.len() - 3..], last[..]);
    }
}

"""Mirror a quarter mesh (indent-quarter.geo) about its symmetry planes x = 0 and y = 0 into
the full block, node for node: every node of the quarter keeps its coordinates (a reflection
changes only signs, exactly), the nodes on a plane are shared, the tetrahedra and triangles of
an odd number of reflections have two nodes swapped (so that every cell keeps its
orientation), and the groups on the planes (sym_x, sym_y) are left out: they are inside the
full block. Needs Gmsh's Python API (pip install gmsh).

Usage: python3 mirror-quarter.py indent-quarter-h0.05.msh indent-full-h0.05.msh
       python3 mirror-quarter.py --turn 30 indent-quarter-h0.05.msh indent-quarter-turned-h0.05.msh
With --turn DEG it writes the quarter itself turned by DEG degrees about the z axis instead,
every group kept (its symmetry planes then lie along no axis: rollers on them fix the normal).
"""
import math
import sys

import gmsh

PLANES = ("sym_x", "sym_y")


def read(path):
    """Nodes {tag: (x, y, z)}, tetrahedra [(n1..n4)], and triangles per group name."""
    gmsh.open(path)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    nodes = {int(t): tuple(coords[3 * k:3 * k + 3]) for k, t in enumerate(tags)}
    _, cells = gmsh.model.mesh.getElementsByType(4)
    tets = [tuple(int(a) for a in cells[4 * k:4 * k + 4]) for k in range(len(cells) // 4)]
    groups = {}
    for dim, tag in gmsh.model.getPhysicalGroups(2):
        name = gmsh.model.getPhysicalName(dim, tag)
        triangles = []
        for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            _, _, elements = gmsh.model.mesh.getElements(dim, entity)
            flat = [int(a) for a in elements[0]]
            triangles += [tuple(flat[3 * k:3 * k + 3]) for k in range(len(flat) // 3)]
        groups[name] = triangles
    return nodes, tets, groups


def mirrored(nodes, tets, groups):
    """The four copies (sx, sy) of the quarter, nodes on the planes shared."""
    index, coords = {}, []

    def node(point):
        key = tuple(0.0 if c == 0.0 else c for c in point)
        if key not in index:
            index[key] = len(coords) + 1
            coords.append(key)
        return index[key]

    full_tets, full_groups = [], {n: [] for n in groups if n not in PLANES}
    for sx, sy in ((1, 1), (-1, 1), (1, -1), (-1, -1)):
        new = {t: node((sx * p[0], sy * p[1], p[2])) for t, p in nodes.items()}

        def turn(cell):
            c = [new[a] for a in cell]
            if sx * sy < 0:
                c[0], c[1] = c[1], c[0]
            return c

        full_tets += [turn(c) for c in tets]
        for name in full_groups:
            full_groups[name] += [turn(c) for c in groups[name]]
    return coords, full_tets, full_groups


def write(path, coords, tets, groups):
    gmsh.model.add("full")
    gmsh.model.addDiscreteEntity(3, 1)
    flat = [c for p in coords for c in p]
    gmsh.model.mesh.addNodes(3, 1, list(range(1, len(coords) + 1)), flat)
    first = 1
    gmsh.model.mesh.addElementsByType(1, 4, list(range(first, first + len(tets))), [a for c in tets for a in c])
    first += len(tets)
    gmsh.model.addPhysicalGroup(3, [1], name="body")
    for k, (name, triangles) in enumerate(sorted(groups.items())):
        gmsh.model.addDiscreteEntity(2, k + 1)
        tags = list(range(first, first + len(triangles)))
        gmsh.model.mesh.addElementsByType(k + 1, 2, tags, [a for c in triangles for a in c])
        first += len(triangles)
        gmsh.model.addPhysicalGroup(2, [k + 1], name=name)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1)
    gmsh.write(path)


def turned(nodes, tets, groups, degrees):
    """The quarter turned about z, its nodes in their order."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    tags = sorted(nodes)
    number = {t: k + 1 for k, t in enumerate(tags)}
    coords = [(c * nodes[t][0] - s * nodes[t][1], s * nodes[t][0] + c * nodes[t][1], nodes[t][2]) for t in tags]
    renumber = lambda cells: [[number[a] for a in cell] for cell in cells]
    return coords, renumber(tets), {n: renumber(g) for n, g in groups.items()}


def main():
    args = sys.argv[1:]
    degrees = float(args[1]) if args[0] == "--turn" else None
    quarter, out = args[-2], args[-1]
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    nodes, tets, groups = read(quarter)
    if degrees is None:
        coords, cells, parts = mirrored(nodes, tets, groups)
    else:
        coords, cells, parts = turned(nodes, tets, groups, degrees)
    write(out, coords, cells, parts)
    gmsh.finalize()
    print(f"{quarter}: {len(nodes)} nodes -> {out}: {len(coords)} nodes, {len(cells)} tetrahedra")


if __name__ == "__main__":
    main()

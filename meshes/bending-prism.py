"""The prism [0,2]×[-0.5,0.5]×[-0.5,0.5] in structured tetrahedra for the pure-bending study:
faces x0 (x = 0), x1 (x = 2) and the lateral faces "sides"; n cells across the section, 2n
along x. Writes bending-prism-n4.msh, -n8.msh and -n16.msh: python3 bending-prism.py
(needs Gmsh's Python API: pip install gmsh)."""

import gmsh

for n in (4, 8, 16):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.model.add(f"prism-{n}")
    gmsh.model.occ.addBox(0, -0.5, -0.5, 2, 1, 1, 1)
    gmsh.model.occ.synchronize()
    for _, curve in gmsh.model.getEntities(1):
        x0, _, _, x1, _, _ = gmsh.model.getBoundingBox(1, curve)
        gmsh.model.mesh.setTransfiniteCurve(curve, (2 * n if x1 - x0 > 1 else n) + 1)
    for _, surface in gmsh.model.getEntities(2):
        gmsh.model.mesh.setTransfiniteSurface(surface)
    gmsh.model.mesh.setTransfiniteVolume(1)
    faces = {"x0": [], "x1": [], "sides": []}
    for _, surface in gmsh.model.getEntities(2):
        x0, _, _, x1, _, _ = gmsh.model.getBoundingBox(2, surface)
        faces["x0" if x1 < 1e-3 else "x1" if x0 > 2 - 1e-3 else "sides"].append(surface)
    for name, tags in faces.items():
        gmsh.model.addPhysicalGroup(2, tags, name=name)
    gmsh.model.addPhysicalGroup(3, [1], name="body")
    gmsh.model.mesh.generate(3)
    gmsh.write(f"bending-prism-n{n}.msh")
    gmsh.finalize()

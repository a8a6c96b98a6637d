#!/usr/bin/env python3
"""The peer of `strata layers` in the speed table (scripts/speed_table.sh): a unit sphere's
surface meshed by Gmsh, and Gmsh 4.8's own boundary layer on it.

  gmsh_peer.py sphere TRIANGLES OUT.msh
      write a unit sphere meshed by Gmsh with about TRIANGLES triangles (one discrete surface,
      normals out) to OUT.msh; prints the triangle count.
  gmsh_peer.py extrude IN.msh LAYERS FIRST GROWTH OUT.msh
      Gmsh's extrudeBoundaryLayer on IN.msh's one surface (LAYERS layers of prisms from FIRST at
      GROWTH, no smoothing, no checks), then generate(3) and OUT.msh written, as a user of Gmsh
      would; prints "SECONDS PRISMS" for that whole work (reading the surface excluded).

Gmsh 4.8 extrudes discrete surfaces only when every wall triangle is in one closed surface
(../shared/docs/PLATFORM.md), which is what `sphere` writes.
"""
import math
import sys
import time

import gmsh


def sphere(triangles, out):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("sphere")
    gmsh.model.occ.addSphere(0, 0, 0, 1)
    gmsh.model.occ.synchronize()
    # An equilateral triangle of side h covers sqrt(3)/4 h^2 of the sphere's 4 pi.
    h = math.sqrt(4 * math.pi / (triangles * math.sqrt(3) / 4))
    gmsh.option.setNumber("Mesh.MeshSizeMin", h)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.model.mesh.generate(2)
    # One discrete surface holding every triangle, so that extrudeBoundaryLayer takes it.
    _, _, nodes = gmsh.model.mesh.getElements(2)
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    tris = nodes[0]
    gmsh.model.add("discrete")
    s = gmsh.model.addDiscreteEntity(2)
    gmsh.model.mesh.addNodes(2, s, node_tags, coords)
    gmsh.model.mesh.addElementsByType(s, 2, [], tris)
    gmsh.model.addPhysicalGroup(2, [s], 1)
    gmsh.model.setPhysicalName(2, 1, "sphere")
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(out)
    print(len(tris) // 3)
    gmsh.finalize()


def extrude(surface, layers, first, growth, out):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.merge(surface)
    start = time.perf_counter()
    heights, total = [], 0.0
    for k in range(layers):
        total += first * growth**k
        heights.append(total)
    gmsh.model.geo.extrudeBoundaryLayer(gmsh.model.getEntities(2), [1] * layers, heights, True)
    gmsh.model.geo.synchronize()
    gmsh.model.mesh.generate(3)
    gmsh.write(out)
    seconds = time.perf_counter() - start
    types, tags, _ = gmsh.model.mesh.getElements(3)
    prisms = sum(len(t) for ty, t in zip(types, tags) if ty == 6)
    print(f"{seconds:.3f} {prisms}")
    gmsh.finalize()


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "sphere":
        sphere(int(sys.argv[2]), sys.argv[3])
    elif len(sys.argv) == 7 and sys.argv[1] == "extrude":
        extrude(sys.argv[2], int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5]), sys.argv[6])
    else:
        sys.exit(__doc__)

"""gmsh model of the ironing die: a half disc below its centre (plane strain).

The die of radius R is centred at (x_c, y_c); it occupies the half disc
y ≤ y_c.  Facet tags: 1 the arc (contact), 2 the flat top y = y_c (loaded).
Element size h along the arc, growing to R/4 at the top.  Lengths in mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import gmsh
from mpi4py import MPI

from .model import distributed_model

if TYPE_CHECKING:
    from dolfinx.mesh import Mesh, MeshTags

__all__ = ["ARC", "TOP", "die_body"]

ARC, TOP = 1, 2


def _build(R: float, xc: float, yc: float, h: float) -> None:
    occ = gmsh.model.occ
    disc = occ.addDisk(xc, yc, 0, R, R)
    box = occ.addRectangle(xc - R, yc - R, 0, 2 * R, R)
    occ.intersect([(2, disc)], [(2, box)])
    occ.synchronize()
    arc: list[int]
    top: list[int]
    arc, top = [], []
    for dim, tag in gmsh.model.getEntities(1):
        _, y, _ = occ.getCenterOfMass(dim, tag)
        (top if abs(y - yc) < 1e-8 * R else arc).append(tag)
    gmsh.model.addPhysicalGroup(2, [t for _, t in gmsh.model.getEntities(2)], 1)
    gmsh.model.addPhysicalGroup(1, arc, ARC)
    gmsh.model.addPhysicalGroup(1, top, TOP)
    f = gmsh.model.mesh.field
    d = f.add("Distance")
    f.setNumbers(d, "CurvesList", arc)
    t = f.add("Threshold")
    f.setNumber(t, "InField", d)
    f.setNumber(t, "SizeMin", h)
    f.setNumber(t, "SizeMax", R / 4)
    f.setNumber(t, "DistMin", 0.0)
    f.setNumber(t, "DistMax", R)
    f.setAsBackgroundMesh(t)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.model.mesh.generate(2)


def die_body(
    R: float, xc: float, yc: float, h: float, comm: MPI.Comm = MPI.COMM_WORLD
) -> tuple[Mesh, MeshTags]:
    """Build the die and return ``(mesh, facet_tags)`` (built on rank 0, distributed)."""
    data = distributed_model("ironing_die", lambda: _build(R, xc, yc, h), comm, 2)
    assert data.facet_tags is not None      # the model tags its boundary
    return data.mesh, data.facet_tags

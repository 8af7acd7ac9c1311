"""gmsh model of the circular cross-section of an O-ring seal (axisymmetric, chapter §8.1).

Mesh coordinates (r, z) = (X₀, X₁): r the distance from the rod axis, z the
axial position (the air side is z > 0, the sealed side z < 0).  The disc of
radius ``a`` centred at (r_c, z_c) is split at the polar angles φ (measured from
the +r direction) into three boundary arcs:

* LUBRICATED (tag 1): 135° ≤ φ ≤ 225°, the inner arc facing the rod (Γ_l);
* SEALED (tag 2): 225° ≤ φ ≤ 315°, the arc facing the sealed side, loaded by p_s;
* HOUSING (tag 3): −45° ≤ φ ≤ 135°, the arc facing the groove bottom and the
  air-side groove wall.

Mesh density ``n`` (1, 2, 4, 8, …): element size h_l/n on Γ_l and h_b/n far from
it (a Distance/Threshold size field).  The boundary has vertices at
φ = 0°, 90°, 180° (the first points touching groove bottom, air-side wall and
rod).  Cell tag 1.  Lengths in mm.

The boundary groups carry the names of :data:`GROUP_NAMES` (lubricated, sealed,
housing), the names the case ``ehl-oring`` reads from a user's mesh
(``mesh_file``); :func:`write_oring_section` writes the built section as such a
mesh, a template for one's own.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import gmsh
from dolfinx.io import gmsh as gmshio
from mpi4py import MPI

if TYPE_CHECKING:
    import os

    from dolfinx.mesh import Mesh, MeshTags

__all__ = ["GROUP_NAMES", "HOUSING", "LUBRICATED", "SEALED", "oring_section",
           "write_oring_section"]

LUBRICATED, SEALED, HOUSING = 1, 2, 3
#: names of the boundary groups (physical names in the gmsh model and a written .msh)
GROUP_NAMES = {LUBRICATED: "lubricated", SEALED: "sealed", HOUSING: "housing"}


def _build(r_c: float, z_c: float, a: float, h_l: float, h_b: float) -> None:
    geo = gmsh.model.geo
    c = geo.addPoint(r_c, z_c, 0)
    angles = (-45, 0, 45, 90, 135, 180, 225, 270)   # vertices at the initial contact points
    pts = {k: geo.addPoint(r_c + a * math.cos(math.radians(k)),
                           z_c + a * math.sin(math.radians(k)), 0) for k in angles}
    order = angles[4:] + angles[:4] + (angles[4],)   # 135 → 180 → … → 90 → 135
    arcs = {k0: geo.addCircleArc(pts[k0], c, pts[k1]) for k0, k1 in zip(order[:-1], order[1:])}
    lub = [arcs[135], arcs[180]]
    sealed = [arcs[225], arcs[270]]
    housing = [arcs[-45], arcs[0], arcs[45], arcs[90]]
    loop = geo.addCurveLoop([arcs[k] for k in order[:-1]])
    surf = geo.addPlaneSurface([loop])
    geo.synchronize()
    gmsh.model.addPhysicalGroup(2, [surf], 1, name="ring")
    for tag, curves in ((LUBRICATED, lub), (SEALED, sealed), (HOUSING, housing)):
        gmsh.model.addPhysicalGroup(1, curves, tag, name=GROUP_NAMES[tag])
    f = gmsh.model.mesh.field
    d = f.add("Distance")
    f.setNumbers(d, "CurvesList", lub)
    f.setNumber(d, "Sampling", 200)
    t = f.add("Threshold")
    f.setNumber(t, "InField", d)
    f.setNumber(t, "SizeMin", h_l)
    f.setNumber(t, "SizeMax", h_b)
    f.setNumber(t, "DistMin", 0.1 * a)
    f.setNumber(t, "DistMax", 0.8 * a)
    f.setAsBackgroundMesh(t)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.Smoothing", 5)
    gmsh.model.mesh.generate(2)


def oring_section(
    r_c: float, z_c: float, a: float, n: float = 1, h_l: float = 0.1, h_b: float = 0.4,
    comm: MPI.Comm = MPI.COMM_WORLD,
) -> tuple[Mesh, MeshTags, MeshTags]:
    """Build the O-ring cross-section and return ``(mesh, cell_tags, facet_tags)``.

    Args:
        r_c: radial position of the centre of the cross-section (mm).
        z_c: axial position of the centre (mm).
        a: radius of the cross-section (mm).
        n: mesh density (element sizes divided by n).
        h_l: element size on the lubricated arc at density 1 (mm).
        h_b: element size in the bulk at density 1 (mm).
        comm: MPI communicator; the model is built on rank 0 and distributed.
    """
    if not (a > 0 and r_c > a and n > 0):
        raise ValueError("need a > 0, r_c > a (ring off the axis) and n > 0")
    initialized = gmsh.isInitialized()
    if not initialized:
        gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("oring")
    if comm.rank == 0:
        _build(r_c, z_c, a, h_l / n, h_b / n)
    data = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=2)
    gmsh.model.remove()
    if not initialized:
        gmsh.finalize()
    # the model tags its cells and its boundary
    assert data.cell_tags is not None and data.facet_tags is not None
    return data.mesh, data.cell_tags, data.facet_tags


def write_oring_section(
    path: str | os.PathLike[str], r_c: float, z_c: float, a: float, n: float = 1,
    h_l: float = 0.1, h_b: float = 0.4,
) -> str | os.PathLike[str]:
    """Write the cross-section of :func:`oring_section` to the gmsh file ``path`` (one process).

    The physical groups are named (:data:`GROUP_NAMES`), so the file is a valid
    ``mesh_file`` of the case ``ehl-oring`` (which moves it to the rod itself).
    Arguments as for :func:`oring_section`; returns ``path``.
    """
    if not (a > 0 and n > 0):
        raise ValueError("need a > 0 and n > 0")
    initialized = gmsh.isInitialized()
    if not initialized:
        gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("oring")
    _build(r_c, z_c, a, h_l / n, h_b / n)
    gmsh.write(str(path))
    gmsh.model.remove()
    if not initialized:
        gmsh.finalize()
    return path

"""gmsh models of a lubricated roller pair: a half cylinder or a block, both sides of the axis.

A soft-EHL line contact is not symmetric (the film has an inlet and an outlet),
so, unlike :mod:`meshes.hertz`, both sides of the contact point (the origin)
are modelled:

* cylinder above the origin (``below=False``): the half disc of radius R centred
  at (0, R) with y ≤ R, its flat face y = R;
* cylinder below (``below=True``): the half disc centred at (0, −R) with y ≥ −R;
* block (``block`` = B): the rectangle [−B, B] × [−B, 0].

The contact-side boundary is cut at x = ±x_l: the part |x| ≤ x_l is the
lubricated boundary, the rest free.  Refined to h_fine within r_fine of the
origin.  Facet tags: 1 lubricated, 2 loaded (the flat face or the block's
bottom), 5 free.  Lengths in mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import gmsh
from mpi4py import MPI

from .hertz import FREE, LOADED
from .model import distributed_model
from .sizing import point_refinement

__all__ = ["LUBRICATED", "ROLLER_NAMES", "roller"]

LUBRICATED = 1
if TYPE_CHECKING:
    from dolfinx.mesh import Mesh, MeshTags

ROLLER_NAMES = {"lubricated": LUBRICATED, "loaded": LOADED, "free": FREE}


def _build(
    R: float, x_l: float, h_fine: float, h_coarse: float, r_fine: float, below: bool,
    block: float | None,
) -> None:
    occ = gmsh.model.occ
    s = -1.0 if below else 1.0
    if block is not None:
        occ.addRectangle(-block, -block, 0, 2 * block, block)
        y_load, size = -block, block
    else:
        disc = occ.addDisk(0, s * R, 0, R, R)
        box = occ.addRectangle(-R, min(0.0, s * R), 0, 2 * R, R)
        occ.intersect([(2, disc)], [(2, box)])
        y_load, size = s * R, R
    occ.synchronize()
    cuts = [occ.addLine(occ.addPoint(x, -s * size, 0), occ.addPoint(x, s * size, 0))
            for x in (-x_l, x_l)]
    occ.fragment(gmsh.model.getEntities(2), [(1, c) for c in cuts])
    occ.synchronize()
    for d, t in gmsh.model.getEntities(1):
        if not len(gmsh.model.getAdjacencies(d, t)[0]):
            occ.remove([(d, t)], recursive=True)
    occ.synchronize()
    lub, loaded, free = [], [], []
    for dim, tag in gmsh.model.getEntities(1):
        if len(gmsh.model.getAdjacencies(dim, tag)[0]) != 1:
            continue
        x, y, _ = occ.getCenterOfMass(dim, tag)
        if abs(y - y_load) < 1e-8 * size:
            loaded.append(tag)
        elif abs(x) < x_l and (block is None or abs(y) < 1e-8 * size):
            lub.append(tag)
        else:
            free.append(tag)
    gmsh.model.addPhysicalGroup(2, [t for _, t in gmsh.model.getEntities(2)], 1)
    gmsh.model.addPhysicalGroup(1, lub, LUBRICATED)
    gmsh.model.addPhysicalGroup(1, loaded, LOADED)
    gmsh.model.addPhysicalGroup(1, free, FREE)
    p0 = occ.addPoint(0, 0, 0)
    occ.synchronize()
    point_refinement(h_fine, h_coarse, r_fine, size, p0)
    gmsh.model.mesh.generate(2)


def roller(
    R: float, x_l: float, h_fine: float, h_coarse: float, r_fine: float,
    comm: MPI.Comm = MPI.COMM_WORLD, below: bool = False, block: float | None = None,
) -> tuple[Mesh, MeshTags]:
    """Build the roller (or block) and return ``(mesh, facet_tags)``; see the module docstring.

    Args:
        R: radius (mm); unused for a block.
        x_l: half length of the lubricated boundary (mm), x_l < R.
        h_fine: element size near the origin (mm).
        h_coarse: element size far from it (mm).
        r_fine: radius of the refined zone (mm), at least x_l.
        comm: MPI communicator (built on rank 0 and distributed).
        below: a cylinder below the origin (the counter roller).
        block: None, or the half width B (mm) of a block below the origin.
    """
    data = distributed_model("roller", lambda: _build(R, x_l, h_fine, h_coarse, r_fine,
                                                      below, block), comm, 2)
    assert data.facet_tags is not None      # the model tags its boundary
    return data.mesh, data.facet_tags

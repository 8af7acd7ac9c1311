"""gmsh model of the quarter ball of the ball-on-flat wear problem (chapter §5.2).

The ball of radius R is centred at (0, 0, R) and touches the rigid plane z = 0
at the origin.  The model is the lower hemisphere z ≤ R cut by the vertical
symmetry plane y = 0 that contains the sliding direction x, i.e. the region
x² + y² + (z − R)² ≤ R², y ≥ 0, z ≤ R (a quarter of the ball, half of its
contact zone).  The mesh is refined around the initial contact point: element
size ``h_fine`` within ``r_fine`` of the origin, growing to ``h_coarse`` over a
distance 0.6 R.

Facet tags: 1 spherical surface (potential contact), 2 mid-plane z = R
(loaded), 4 symmetry plane y = 0 (the numbering follows :mod:`meshes.hertz`).
Lengths in mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import gmsh
from dolfinx.io import gmsh as gmshio
from mpi4py import MPI

from .sizing import point_refinement

__all__ = ["CONTACT", "LOADED", "NAMES", "SYMMETRY_Y", "quarter_ball"]

if TYPE_CHECKING:
    from dolfinx.mesh import Mesh, MeshTags

CONTACT, LOADED, SYMMETRY_Y = 1, 2, 4
NAMES = {"contact": CONTACT, "loaded": LOADED, "symmetry_y": SYMMETRY_Y}  # of a Body


def _build(R: float, h_fine: float, h_coarse: float, r_fine: float) -> None:
    occ = gmsh.model.occ
    ball = occ.addSphere(0, 0, R, R)
    box = occ.addBox(-R, 0, 0, 2 * R, R, R)
    occ.intersect([(3, ball)], [(3, box)])
    occ.synchronize()
    tags: dict[int, list[int]] = {CONTACT: [], LOADED: [], SYMMETRY_Y: []}
    for dim, tag in gmsh.model.getEntities(2):
        _, y, z = occ.getCenterOfMass(dim, tag)
        if abs(y) < 1e-8 * R:
            tags[SYMMETRY_Y].append(tag)
        elif abs(z - R) < 1e-8 * R:
            tags[LOADED].append(tag)
        else:
            tags[CONTACT].append(tag)
    vol = [t for _, t in gmsh.model.getEntities(3)]
    gmsh.model.addPhysicalGroup(3, vol, 1)
    for k, v in tags.items():
        gmsh.model.addPhysicalGroup(2, v, k)
    # the lowest point (0, 0, 0) is not a geometric vertex of the OCC sphere: embed it
    p0 = [t for _, t in gmsh.model.getEntities(0)
          if sum(abs(c) for c in gmsh.model.getValue(0, t, [])) < 1e-8 * R]
    if not p0:
        p0 = [occ.addPoint(0, 0, 0)]
        occ.synchronize()
        gmsh.model.mesh.embed(0, p0, 2, tags[CONTACT][0])
    point_refinement(h_fine, h_coarse, r_fine, R, p0[0])
    gmsh.model.mesh.generate(3)


def quarter_ball(
    R: float, h_fine: float, h_coarse: float, r_fine: float, comm: MPI.Comm = MPI.COMM_WORLD
) -> tuple[Mesh, MeshTags]:
    """Build the quarter ball and return ``(mesh, facet_tags)``.

    Args:
        R: ball radius (mm).
        h_fine: element size within ``r_fine`` of the lowest point (mm).
        h_coarse: element size far from it (mm).
        r_fine: radius of the refined zone (mm); choose it above the final scar radius.
        comm: MPI communicator; the model is built on rank 0 and distributed.
    """
    if not 0 < h_fine <= h_coarse:
        raise ValueError("need 0 < h_fine <= h_coarse")
    if not 0 < r_fine < R:
        raise ValueError("need 0 < r_fine < R")
    initialized = gmsh.isInitialized()
    if not initialized:
        gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("wear_ball")
    if comm.rank == 0:
        _build(R, h_fine, h_coarse, r_fine)
    data = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=3)
    gmsh.model.remove()
    if not initialized:
        gmsh.finalize()
    assert data.facet_tags is not None      # the model tags its boundary
    return data.mesh, data.facet_tags

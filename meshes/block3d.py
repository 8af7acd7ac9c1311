"""A 3D elastic block — a half-space model — with a refined contact patch (gmsh, tetrahedra).

The block's top face z = 0 is the potential contact surface; the contact point
is the origin, where the mesh is refined (size ``h_fine`` within ``r_fine`` of
it, growing to ``h_coarse`` over 0.6 ``L``).  A half-space is modelled by a
block several contact radii deep and wide: the displacement of a Hertz contact
decays like 1/r, so the approach (rigid-body displacement of the far field)
converges slowly with the block's size, the pressure and the contact radius fast.

* ``quarter=True``: the quarter [0, L] × [0, L] × [−H, 0] of a block symmetric
  about x = 0 and y = 0 (the planes tagged ``symmetry_x``, ``symmetry_y``:
  hold u_x and u_y there); forces computed on it are a quarter of the full
  block's.
* ``quarter=False``: the full block [−L, L] × [−L, L] × [−H, 0] (the origin
  embedded in the top face); ``symmetry_x``, ``symmetry_y`` are then empty and
  the four lateral faces are ``sides``.
* ``half=True`` (with ``quarter=False``): the half [−L, L] × [0, L] × [−H, 0]
  of a block symmetric about y = 0 (``symmetry_y``; two boxes x ≤ 0, x ≥ 0 sharing
  a face, so that the origin is a vertex), e.g. under a ball sliding along x.

Facet tags (:data:`NAMES`, for :class:`tribofx.body.Body`): 1 ``top`` (z = 0),
2 ``bottom`` (z = −H, e.g. held), 3 ``symmetry_x`` (x = 0), 4 ``symmetry_y``
(y = 0), 5 ``sides`` (the far lateral faces, traction free or held).  Lengths
in mm.  For a ball on it, :func:`meshes.hertz.hertz_body` (dim 3) gives the
quarter sphere touching the origin from above.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import gmsh
from mpi4py import MPI

from .model import distributed_model
from .sizing import point_refinement

if TYPE_CHECKING:
    from dolfinx.mesh import Mesh, MeshTags

__all__ = ["BOTTOM", "NAMES", "SIDES", "SYMMETRY_X", "SYMMETRY_Y", "TOP", "contact_block"]

TOP, BOTTOM, SYMMETRY_X, SYMMETRY_Y, SIDES = 1, 2, 3, 4, 5
NAMES = {"top": TOP, "bottom": BOTTOM, "symmetry_x": SYMMETRY_X, "symmetry_y": SYMMETRY_Y,
         "sides": SIDES}


def _build(
    L: float, H: float, h_fine: float, h_coarse: float, r_fine: float, quarter: bool,
    half: bool = False,
) -> None:
    occ = gmsh.model.occ
    x0 = 0.0 if quarter else -L
    if half:     # two boxes x ≤ 0, x ≥ 0 sharing a face: the origin is a vertex
        occ.fragment([(3, occ.addBox(-L, 0.0, -H, L, L, H))],
                     [(3, occ.addBox(0.0, 0.0, -H, L, L, H))])
    else:
        occ.addBox(x0, x0, -H, L - x0, L - x0, H)
    origin = None if quarter or half else occ.addPoint(0.0, 0.0, 0.0)
    occ.synchronize()
    tol = 1e-8 * L
    tags: dict[int, list[int]] = {k: [] for k in NAMES.values()}
    for dim, tag in gmsh.model.getEntities(2):
        if len(gmsh.model.getAdjacencies(dim, tag)[0]) > 1:
            continue             # the face the two halves share
        x, y, z = occ.getCenterOfMass(dim, tag)
        if abs(z) < tol:
            tags[TOP].append(tag)
        elif abs(z + H) < tol:
            tags[BOTTOM].append(tag)
        elif quarter and abs(x) < tol:
            tags[SYMMETRY_X].append(tag)
        elif (quarter or half) and abs(y) < tol:
            tags[SYMMETRY_Y].append(tag)
        else:
            tags[SIDES].append(tag)
    if origin is not None:
        gmsh.model.mesh.embed(0, [origin], 2, tags[TOP][0])
    else:
        origin = next(t for _, t in gmsh.model.getEntities(0)
                      if sum(abs(c) for c in gmsh.model.getValue(0, t, [])) < tol)
    gmsh.model.addPhysicalGroup(3, [t for _, t in gmsh.model.getEntities(3)], 1)
    for k, v in tags.items():
        if v:
            gmsh.model.addPhysicalGroup(2, v, k)
    point_refinement(h_fine, h_coarse, r_fine, L, origin)
    gmsh.model.mesh.generate(3)


def contact_block(
    L: float, H: float, h_fine: float, h_coarse: float, r_fine: float,
    comm: MPI.Comm = MPI.COMM_WORLD, quarter: bool = True, half: bool = False,
) -> tuple[Mesh, MeshTags]:
    """Build the block and return ``(mesh, facet_tags)`` (see the module docstring).

    Args:
        L: half-width (mm): the block spans [0, L] (quarter) or [−L, L] in x and y.
        H: depth (mm): z ∈ [−H, 0].
        h_fine: element size within ``r_fine`` of the origin (mm).
        h_coarse: element size far from it (mm).
        r_fine: radius of the refined patch (mm); choose it above the contact radius.
        comm: MPI communicator; the model is built on rank 0 and distributed.
        quarter: the quarter model with two symmetry planes (default) or the full block.
        half: with ``quarter=False``, the half model y ≥ 0 (one symmetry plane).
    """
    if not (0 < h_fine <= h_coarse and 0 < r_fine < L and H > 0):
        raise ValueError("contact_block needs 0 < h_fine <= h_coarse, 0 < r_fine < L, H > 0")
    if quarter and half:
        raise ValueError("contact_block: half=True is the half model; give quarter=False")
    data = distributed_model("contact_block", lambda: _build(L, H, h_fine, h_coarse, r_fine,
                                                             quarter, half), comm, 3)
    assert data.facet_tags is not None      # the model tags its boundary
    return data.mesh, data.facet_tags

"""gmsh models of the Hertz problem: an elastic cylinder (2D) or sphere (3D) on a plane.

Both are symmetry-reduced and refined towards the initial contact point, which
lies at the origin; the rigid plane is y = 0 (2D) or z = 0 (3D).

* 2D (plane strain): quarter disc x ≥ 0 of the cylinder of radius R centred at
  (0, R), cut at its centre plane y = R.
* 3D: quarter of the hemisphere x, y ≥ 0 of the sphere of radius R centred at
  (0, 0, R), cut at its equator plane z = R.

Facet tags: 1 potential contact surface, 2 loaded flat face, 3 symmetry x = 0,
4 symmetry y = 0 (3D only); with ``cap`` = L the contact surface is only the cap
within the distance L of the axis (its rim exactly on the circle x = L, or
x² + y² = L²), the rest of the curved surface 5 (free).  Lengths in mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import gmsh
from mpi4py import MPI

from .model import distributed_model
from .sizing import point_refinement

if TYPE_CHECKING:
    from dolfinx.mesh import Mesh, MeshTags

__all__ = ["AXIS", "AXISYMMETRIC_NAMES", "CONTACT", "FREE", "LOADED", "NAMES", "SYMMETRY_X",
           "SYMMETRY_Y", "hertz_body", "sphere_section"]

CONTACT, LOADED, SYMMETRY_X, SYMMETRY_Y, FREE = 1, 2, 3, 4, 5
NAMES = {"contact": CONTACT, "loaded": LOADED, "symmetry_x": SYMMETRY_X,
         "symmetry_y": SYMMETRY_Y}
#: the axis of the meridian section of :func:`sphere_section` (the 2D tag SYMMETRY_X)
AXIS = SYMMETRY_X
#: boundary names of :func:`sphere_section` for an axisymmetric :class:`tribofx.body.Body`
AXISYMMETRIC_NAMES = {"contact": CONTACT, "loaded": LOADED, "axis": AXIS}


def _split_cap(dim: int, R: float, cap: float) -> float:
    """Cut the body at the cap's rim (z or y = R − √(R² − L²)) so the cap is a surface of its own.

    The cut is a segment (2D) or a quarter disc (3D) of the body's section there;
    pieces of it outside the body are removed.
    """
    occ = gmsh.model.occ
    z = R - (R * R - cap * cap) ** 0.5
    if dim == 2:
        tool = occ.addLine(occ.addPoint(cap, z, 0), occ.addPoint(cap, R, 0))
    else:
        tool = occ.addDisk(0, 0, z, R, R)
    body = gmsh.model.getEntities(dim)
    occ.fragment(body, [(dim - 1, tool)])
    occ.synchronize()
    for d, t in gmsh.model.getEntities(dim - 1):
        if not len(gmsh.model.getAdjacencies(d, t)[0]):
            occ.remove([(d, t)], recursive=True)
    occ.synchronize()
    return z


def _boundary(dim: int, tag: int) -> bool:
    """Whether entity ``tag`` of dimension dim − 1 bounds one body piece only."""
    return len(gmsh.model.getAdjacencies(dim - 1, tag)[0]) == 1


def _build_2d(
    R: float, h_fine: float, h_coarse: float, r_fine: float, below: bool = False,
    block: float | None = None, cap: float | None = None, depth: float | None = None,
) -> None:
    occ = gmsh.model.occ
    s = -1.0 if below else 1.0
    y_load = s * R
    if block is not None:   # a flat block [0, block] × [−depth, 0] below the contact point
        depth = block if depth is None else depth
        occ.addRectangle(0, -depth, 0, block, depth)
        y_load, R = -depth, block
    else:
        disc = occ.addDisk(0, s * R, 0, R, R)
        box = occ.addRectangle(0, min(0.0, s * R), 0, R, R)
        occ.intersect([(2, disc)], [(2, box)])
    occ.synchronize()
    if cap is not None:
        _split_cap(2, R, cap)
    contact, loaded, sym, free = [], [], [], []
    for dim, tag in gmsh.model.getEntities(1):
        x, y, _ = occ.getCenterOfMass(dim, tag)
        if not _boundary(2, tag):
            continue
        if abs(x) < 1e-8 * R:
            sym.append(tag)
        elif abs(y - y_load) < 1e-8 * R:
            loaded.append(tag)
        elif cap is not None and x > cap:
            free.append(tag)
        elif block is None or abs(y) < 1e-8 * R:
            contact.append(tag)
    surf = [t for _, t in gmsh.model.getEntities(2)]
    gmsh.model.addPhysicalGroup(2, surf, 1)
    gmsh.model.addPhysicalGroup(1, contact, CONTACT)
    gmsh.model.addPhysicalGroup(1, loaded, LOADED)
    gmsh.model.addPhysicalGroup(1, sym, SYMMETRY_X)
    if free:
        gmsh.model.addPhysicalGroup(1, free, FREE)
    p0 = [t for _, t in gmsh.model.getEntities(0)
          if sum(abs(c) for c in gmsh.model.getValue(0, t, [])) < 1e-8 * R]
    if not p0:
        p0 = [occ.addPoint(0, 0, 0)]
        occ.synchronize()
    point_refinement(h_fine, h_coarse, r_fine, R, p0[0])
    gmsh.model.mesh.generate(2)


def _build_3d(
    R: float, h_fine: float, h_coarse: float, r_fine: float, cap: float | None = None
) -> None:
    occ = gmsh.model.occ
    ball = occ.addSphere(0, 0, R, R)
    box = occ.addBox(0, 0, 0, R, R, R)
    occ.intersect([(3, ball)], [(3, box)])
    occ.synchronize()
    z_cap = _split_cap(3, R, cap) if cap is not None else None
    tags: dict[int, list[int]] = {CONTACT: [], LOADED: [], SYMMETRY_X: [], SYMMETRY_Y: [],
                                  FREE: []}
    for dim, tag in gmsh.model.getEntities(2):
        x, y, z = occ.getCenterOfMass(dim, tag)
        if not _boundary(3, tag):
            continue
        if abs(x) < 1e-8 * R:
            tags[SYMMETRY_X].append(tag)
        elif abs(y) < 1e-8 * R:
            tags[SYMMETRY_Y].append(tag)
        elif abs(z - R) < 1e-8 * R:
            tags[LOADED].append(tag)
        elif z_cap is not None and z > z_cap:
            tags[FREE].append(tag)
        else:
            tags[CONTACT].append(tag)
    vol = [t for _, t in gmsh.model.getEntities(3)]
    gmsh.model.addPhysicalGroup(3, vol, 1)
    for k, v in tags.items():
        if v:
            gmsh.model.addPhysicalGroup(2, v, k)
    p0 = [t for _, t in gmsh.model.getEntities(0)
          if sum(abs(c) for c in gmsh.model.getValue(0, t, [])) < 1e-8 * R]
    point_refinement(h_fine, h_coarse, r_fine, R, p0[0])
    gmsh.model.mesh.generate(3)


def hertz_body(
    dim: int, R: float, h_fine: float, h_coarse: float, r_fine: float,
    comm: MPI.Comm = MPI.COMM_WORLD, below: bool = False, block: float | None = None,
    cap: float | None = None, depth: float | None = None,
) -> tuple[Mesh, MeshTags]:
    """Build the symmetry-reduced Hertz body and return ``(mesh, facet_tags)``.

    Args:
        dim: 2 (plane-strain cylinder) or 3 (sphere).
        R: radius (mm).
        h_fine: element size within ``r_fine`` of the initial contact point (mm).
        h_coarse: element size far from it (mm).
        r_fine: radius of the refined zone (mm); choose it above the contact size.
        comm: MPI communicator; the model is built on rank 0 and distributed.
        below: 2D only: the cylinder under the contact point (centre (0, −R),
            loaded face y = −R), the counterpart of a two-cylinder contact.
        block: 2D only: instead a flat block [0, block] × [−depth, 0] (contact
            face y = 0, loaded face y = −depth, the right side free).
        depth: the block's depth (default ``block``: a square).
        cap: None, or the radius L < R of the contact cap (tag CONTACT; the rest of
            the curved surface FREE), e.g. the end of a lubricated film.
    """
    if dim not in (2, 3):
        raise ValueError(f"dim must be 2 or 3, got {dim}")
    def build() -> None:
        if dim == 2:
            _build_2d(R, h_fine, h_coarse, r_fine, below, block, cap, depth)
        else:
            _build_3d(R, h_fine, h_coarse, r_fine, cap)

    data = distributed_model(f"hertz{dim}d", build, comm, dim)
    assert data.facet_tags is not None      # the model tags its boundary
    return data.mesh, data.facet_tags


def sphere_section(
    R: float, h_fine: float, h_coarse: float, r_fine: float, comm: MPI.Comm = MPI.COMM_WORLD
) -> tuple[Mesh, MeshTags]:
    """Meridian section of the lower hemisphere of a sphere: an axisymmetric body.

    The quarter disc x ≥ 0 of radius R centred at (0, R), cut at the equator
    y = R: in an axisymmetric :class:`tribofx.body.Body` (``kind="axisymmetric"``)
    x is the radius r and y the axial coordinate, so the mesh is the whole
    hemisphere touching the plane y = 0 at the origin, the axis r = 0 being the
    face ``axis``.  Refined within ``r_fine`` of the origin.  Returns ``(mesh,
    facet_tags)`` with the names :data:`AXISYMMETRIC_NAMES` (``contact`` the
    spherical face, ``loaded`` the equator plane, ``axis``): hold u_r = 0 on
    ``axis`` (symmetry; the contact node on it gets its exact lumped area from
    :class:`tribofx.interfaces.surface.Surface`).  Forces of an axisymmetric
    body are the revolved body's (N, weight 2πr).
    """
    return hertz_body(2, R, h_fine, h_coarse, r_fine, comm)

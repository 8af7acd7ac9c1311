"""gmsh model of the quarter ball of the soft-EHL ball-on-plane case (chapter §8.3).

The ball (radius R, centre (0, 0, R)) touches the rigid plane z = 0 at the
origin.  Only the lower hemisphere z ≤ R of the half y ≥ 0 is meshed (a
quarter of the ball): the sliding direction x lies in the symmetry plane
y = 0, the load is applied at the horizontal mid-plane z = R.  The spherical
surface is split at the height z_cap = R (1 − cos θ_l) into the lubricated
cap (polar angle θ ≤ θ_l about the contact point, boundary on the circle
z = z_cap, exactly) and the free surface.  Tetrahedra have size ``h_fine``
within ``r_fine`` of the contact point and grow to ``h_coarse``; optionally a
finer band follows the edge of the contact zone (``ring``: the trailing-edge
constriction and the side lobes of the film, chapter Figs. 24–25).

Cell tag 1.  Facet tags: 1 lubricated cap Γ_l, 2 free spherical surface,
3 mid-plane z = R (loaded), 4 symmetry plane y = 0.  Lengths in mm.

The boundary groups carry the names of :data:`GROUP_NAMES` (lubricated, free,
midplane, symmetry), the names the case ``ehl-ball`` reads from a user's mesh
(``mesh_file``); :func:`write_quarter_ball` writes the built ball as such a
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

__all__ = ["BALL_NAMES", "FREE", "GROUP_NAMES", "LUBRICATED", "MIDPLANE", "SYMMETRY", "cap_height",
           "quarter_ball", "write_quarter_ball"]

LUBRICATED, FREE, MIDPLANE, SYMMETRY = 1, 2, 3, 4
#: names of the boundary groups (physical names in the gmsh model and a written .msh)
GROUP_NAMES = {LUBRICATED: "lubricated", FREE: "free", MIDPLANE: "midplane",
               SYMMETRY: "symmetry"}
#: the name map of a quarter ball's Body: the lubricated cap and its two symmetry planes
BALL_NAMES = {"lubricated": LUBRICATED, "midplane": MIDPLANE, "symmetry": SYMMETRY}


def cap_height(R: float, theta_l: float) -> float:
    """Height z_cap = R (1 − cos θ_l) (mm) of the boundary circle of the lubricated cap."""
    return R * (1 - math.cos(theta_l))


def _build(
    R: float, theta_l: float, h_fine: float, h_coarse: float, r_fine: float,
    ring: tuple[float, float, float] | None = None,
) -> None:
    occ = gmsh.model.occ
    z_cap = cap_height(R, theta_l)
    ball = occ.addSphere(0, 0, R, R)
    box = occ.addBox(-R, 0, 0, 2 * R, R, R)
    half, _ = occ.intersect([(3, ball)], [(3, box)])
    cut = occ.addBox(-R, 0, 0, 2 * R, R, z_cap)
    low, _ = occ.intersect(half, [(3, cut)], removeObject=False)
    occ.cut(half, low, removeTool=False)
    occ.removeAllDuplicates()
    occ.synchronize()
    tol = 1e-8 * R
    tags: dict[int, list[int]] = {LUBRICATED: [], FREE: [], MIDPLANE: [], SYMMETRY: []}
    for dim, tag in gmsh.model.getEntities(2):
        x, y, z = occ.getCenterOfMass(dim, tag)
        if abs(y) < tol:
            tags[SYMMETRY].append(tag)
        elif abs(z - R) < tol:
            tags[MIDPLANE].append(tag)
        elif abs(z - z_cap) < tol:
            continue                     # interior disc z = z_cap (splits the volume)
        elif z < z_cap:
            tags[LUBRICATED].append(tag)
        else:
            tags[FREE].append(tag)
    vols = [t for _, t in gmsh.model.getEntities(3)]
    gmsh.model.addPhysicalGroup(3, vols, 1, name="ball")
    k: int | str            # a group's tag here, a field option's name below
    for k, v in tags.items():
        gmsh.model.addPhysicalGroup(2, v, k, name=GROUP_NAMES[k])
    p0 = occ.addPoint(0, 0, 0)
    occ.synchronize()
    f = gmsh.model.mesh.field
    d = f.add("Distance")
    f.setNumbers(d, "PointsList", [p0])
    t = f.add("Threshold")
    f.setNumber(t, "InField", d)
    f.setNumber(t, "SizeMin", h_fine)
    f.setNumber(t, "SizeMax", h_coarse)
    f.setNumber(t, "DistMin", r_fine)
    f.setNumber(t, "DistMax", r_fine + 0.5 * R)
    if ring is not None:
        # a band along the circle of horizontal radius ρ on the sphere (the edge of the
        # contact zone): size h_ring within w of the circle, growing linearly to h_fine at
        # 2w; beyond 2w the band does not apply (StopAtDistMax), the other field rules
        rho, h_ring, w = ring
        zr = R - math.sqrt(R**2 - rho**2)
        dist = f.add("MathEval")
        f.setString(dist, "F", f"Sqrt((Sqrt(x*x + y*y) - {rho!r})^2 + (z - {zr!r})^2)")
        band = f.add("Threshold")
        f.setNumber(band, "InField", dist)
        for k, val in (("SizeMin", h_ring), ("SizeMax", h_fine), ("DistMin", w),
                       ("DistMax", 2 * w), ("StopAtDistMax", 1)):
            f.setNumber(band, k, val)
        t0, t = t, f.add("Min")
        f.setNumbers(t, "FieldsList", [t0, band])
    f.setAsBackgroundMesh(t)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.Optimize", 1)
    gmsh.model.mesh.generate(3)


def quarter_ball(
    R: float, theta_l: float, h_fine: float, h_coarse: float, r_fine: float,
    comm: MPI.Comm = MPI.COMM_WORLD, ring: tuple[float, float, float] | None = None,
) -> tuple[Mesh, MeshTags, MeshTags]:
    """Build the quarter ball and return ``(mesh, cell_tags, facet_tags)``.

    Args:
        R: ball radius (mm).
        theta_l: polar angle (rad) of the lubricated cap about the contact point.
        h_fine: element size within ``r_fine`` of the contact point (mm).
        h_coarse: element size far from it (mm).
        r_fine: radius of the refined zone (mm).
        comm: MPI communicator; the model is built on rank 0 and distributed.
        ring: None, or ``(ρ, h_ring, w)``: element size h_ring within w of the
            circle of horizontal radius ρ on the sphere (the edge of a contact
            zone of radius ρ), growing linearly to h_fine at 2w.
    """
    initialized = _start(theta_l)
    if comm.rank == 0:
        _build(R, theta_l, h_fine, h_coarse, r_fine, ring)
    data = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=3)
    gmsh.model.remove()
    if not initialized:
        gmsh.finalize()
    # the model tags its cells and its boundary
    assert data.cell_tags is not None and data.facet_tags is not None
    return data.mesh, data.cell_tags, data.facet_tags


def _start(theta_l: float) -> bool:
    """Check the cap angle, start gmsh (if needed) and a new model; whether it was running."""
    if not 0 < theta_l < 0.5 * math.pi:
        raise ValueError(f"cap angle must be in (0, π/2), got {theta_l}")
    initialized = gmsh.isInitialized()
    if not initialized:
        gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("quarter_ball")
    return initialized


def write_quarter_ball(
    path: str | os.PathLike[str], R: float, theta_l: float, h_fine: float, h_coarse: float,
    r_fine: float, ring: tuple[float, float, float] | None = None,
) -> str | os.PathLike[str]:
    """Write the quarter ball of :func:`quarter_ball` to the gmsh file ``path`` (one process).

    The physical groups are named (:data:`GROUP_NAMES`), so the file is a valid
    ``mesh_file`` of the case ``ehl-ball``.  Arguments as for
    :func:`quarter_ball`; returns ``path``.
    """
    initialized = _start(theta_l)
    _build(R, theta_l, h_fine, h_coarse, r_fine, ring)
    gmsh.write(str(path))
    gmsh.model.remove()
    if not initialized:
        gmsh.finalize()
    return path

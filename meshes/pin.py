"""gmsh model of the 2D (plane-strain) pin of the pin-on-flat wear example (chapter §4.4).

The pin occupies −W/2 ≤ x ≤ W/2 below its top face y = H; its tip is a circular
arc of radius R through the lowest point (0, 0), i.e. the bottom boundary is
y = R − √(R² − x²).  ``R = inf`` (or 0) gives the flat-ended punch.  The mesh is
a structured (transfinite) n × n triangulation, refined by the caller through n.

Facet tags: 1 tip (potential contact surface), 2 top (loaded), 3 sides
x = ±W/2 (laterally constrained).  Lengths in mm.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import gmsh
from dolfinx.io import gmsh as gmshio
from mpi4py import MPI

if TYPE_CHECKING:
    from dolfinx.mesh import Mesh, MeshTags

__all__ = ["CONTACT", "NAMES", "SIDES", "TOP", "pin_body", "tip_height"]

CONTACT, TOP, SIDES = 1, 2, 3
NAMES = {"contact": CONTACT, "top": TOP, "sides": SIDES}  # boundary names of a Body


def tip_height(x: float, R: float) -> float:
    """Height of the undeformed tip above its lowest point at abscissa x (mm)."""
    if not R or math.isinf(R):
        return 0.0
    return R - math.sqrt(R * R - x * x)


def _build(W: float, H: float, R: float, n: int) -> None:
    geo = gmsh.model.geo
    s = tip_height(W / 2, R)
    p1 = geo.addPoint(-W / 2, s, 0)
    p2 = geo.addPoint(W / 2, s, 0)
    p3 = geo.addPoint(W / 2, H, 0)
    p4 = geo.addPoint(-W / 2, H, 0)
    if s > 0:
        pc = geo.addPoint(0, R, 0)
        bottom = geo.addCircleArc(p1, pc, p2)
    else:
        bottom = geo.addLine(p1, p2)
    right = geo.addLine(p2, p3)
    top = geo.addLine(p3, p4)
    left = geo.addLine(p4, p1)
    loop = geo.addCurveLoop([bottom, right, top, left])
    surf = geo.addPlaneSurface([loop])
    geo.synchronize()
    for c in (bottom, right, top, left):
        gmsh.model.mesh.setTransfiniteCurve(c, n + 1)
    gmsh.model.mesh.setTransfiniteSurface(surf, "Alternate")
    gmsh.model.addPhysicalGroup(2, [surf], 1)
    gmsh.model.addPhysicalGroup(1, [bottom], CONTACT)
    gmsh.model.addPhysicalGroup(1, [top], TOP)
    gmsh.model.addPhysicalGroup(1, [left, right], SIDES)
    gmsh.model.mesh.generate(2)


def pin_body(
    W: float, H: float, R: float, n: int, comm: MPI.Comm = MPI.COMM_WORLD
) -> tuple[Mesh, MeshTags]:
    """Build the pin and return ``(mesh, facet_tags)``.

    Args:
        W: pin width (mm).
        H: pin height above the tip's lowest point (mm).
        R: tip radius (mm), ≥ W/2; ``math.inf`` or 0 for a flat end.
        n: elements per side of the structured mesh (n × n squares, each split in two).
        comm: MPI communicator; the model is built on rank 0 and distributed.
    """
    if R and not math.isinf(R) and R < W / 2:
        raise ValueError(f"tip radius {R} mm below half the pin width {W / 2} mm")
    if tip_height(W / 2, R) >= H:
        raise ValueError("pin height must exceed the tip height")
    initialized = gmsh.isInitialized()
    if not initialized:
        gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("pin")
    if comm.rank == 0:
        _build(W, H, R, n)
    data = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=2)
    gmsh.model.remove()
    if not initialized:
        gmsh.finalize()
    assert data.facet_tags is not None      # the model tags its boundary
    return data.mesh, data.facet_tags

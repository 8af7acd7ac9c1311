"""gmsh model of a coated elastic layer bonded to a rigid substrate (plane strain).

The layer occupies −L ≤ X ≤ L, −H ≤ Y ≤ 0; a coating of thickness t_c forms
its top −t_c ≤ Y ≤ 0 (t_c = 0: no coating).  The top surface is split at
X = ±x_l: the middle part |X| ≤ x_l is the lubricated boundary Γ_l.  Elements
have size ``h_fine`` along Γ_l and grow to ``h_coarse`` away from it.

Cell tags: 1 layer, 2 coating.  Facet tags: 1 lubricated Γ_l, 2 free top,
3 bottom (bonded to the substrate), 4 lateral sides.  Lengths in mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import gmsh
from dolfinx.io import gmsh as gmshio
from mpi4py import MPI

if TYPE_CHECKING:
    from dolfinx.mesh import Mesh, MeshTags

__all__ = ["BOTTOM", "COATING", "FREE_TOP", "LAYER", "LUBRICATED", "SIDES", "coated_layer"]

LAYER, COATING = 1, 2
LUBRICATED, FREE_TOP, BOTTOM, SIDES = 1, 2, 3, 4


def _build(L: float, H: float, t_c: float, x_l: float, h_fine: float, h_coarse: float) -> None:
    geo = gmsh.model.geo
    P = {}
    coords = {"bl": (-L, -H), "br": (L, -H), "tr": (L, 0), "tlr": (x_l, 0),
              "tll": (-x_l, 0), "tl": (-L, 0)}
    if t_c > 0:
        coords.update({"cr": (L, -t_c), "cl": (-L, -t_c)})
    for k, (x, y) in coords.items():
        P[k] = geo.addPoint(x, y, 0)
    top = [geo.addLine(P["tr"], P["tlr"]), geo.addLine(P["tlr"], P["tll"]),
           geo.addLine(P["tll"], P["tl"])]
    bottom = geo.addLine(P["bl"], P["br"])
    if t_c > 0:
        right_l, right_c = geo.addLine(P["br"], P["cr"]), geo.addLine(P["cr"], P["tr"])
        left_c, left_l = geo.addLine(P["tl"], P["cl"]), geo.addLine(P["cl"], P["bl"])
        interface = geo.addLine(P["cr"], P["cl"])
        layer = geo.addPlaneSurface([geo.addCurveLoop([bottom, right_l, interface, left_l])])
        coat = geo.addPlaneSurface([geo.addCurveLoop([-interface, right_c, *top, left_c])])
        sides = [right_l, right_c, left_c, left_l]
    else:
        right, left = geo.addLine(P["br"], P["tr"]), geo.addLine(P["tl"], P["bl"])
        layer = geo.addPlaneSurface([geo.addCurveLoop([bottom, right, *top, left])])
        coat = None
        sides = [right, left]
    geo.synchronize()
    gmsh.model.addPhysicalGroup(2, [layer], LAYER)
    if coat is not None:
        gmsh.model.addPhysicalGroup(2, [coat], COATING)
    gmsh.model.addPhysicalGroup(1, [top[1]], LUBRICATED)
    gmsh.model.addPhysicalGroup(1, [top[0], top[2]], FREE_TOP)
    gmsh.model.addPhysicalGroup(1, [bottom], BOTTOM)
    gmsh.model.addPhysicalGroup(1, sides, SIDES)
    f = gmsh.model.mesh.field
    dist = f.add("Distance")
    f.setNumbers(dist, "CurvesList", [top[1]])
    f.setNumber(dist, "Sampling", max(100, int(4 * x_l / h_fine)))
    thr = f.add("Threshold")
    f.setNumber(thr, "InField", dist)
    f.setNumber(thr, "SizeMin", h_fine)
    f.setNumber(thr, "SizeMax", h_coarse)
    f.setNumber(thr, "DistMin", 2 * max(t_c, h_fine))
    f.setNumber(thr, "DistMax", 0.5 * H + x_l)
    f.setAsBackgroundMesh(thr)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.model.mesh.generate(2)


def coated_layer(
    L: float, H: float, t_c: float, x_l: float, h_fine: float, h_coarse: float,
    comm: MPI.Comm = MPI.COMM_WORLD,
) -> tuple[Mesh, MeshTags, MeshTags]:
    """Build the coated layer and return ``(mesh, cell_tags, facet_tags)``.

    Args:
        L: half width of the layer (mm).
        H: total thickness, coating included (mm).
        t_c: coating thickness (mm), 0 ≤ t_c < H.
        x_l: half length of the lubricated boundary Γ_l (mm), x_l < L.
        h_fine: element size along Γ_l (mm).
        h_coarse: element size far from Γ_l (mm).
        comm: MPI communicator; the model is built on rank 0 and distributed.
    """
    if not (0 <= t_c < H and 0 < x_l < L and 0 < h_fine <= h_coarse):
        raise ValueError(f"inconsistent layer geometry L={L}, H={H}, t_c={t_c}, x_l={x_l}, "
                         f"h_fine={h_fine}, h_coarse={h_coarse}")
    initialized = gmsh.isInitialized()
    if not initialized:
        gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("coated_layer")
    if comm.rank == 0:
        _build(L, H, t_c, x_l, h_fine, h_coarse)
    data = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=2)
    gmsh.model.remove()
    if not initialized:
        gmsh.finalize()
    # the model tags its cells and its boundary
    assert data.cell_tags is not None and data.facet_tags is not None
    return data.mesh, data.cell_tags, data.facet_tags

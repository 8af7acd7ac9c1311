"""Rigid countersurfaces given as surface meshes (for the closest-point kernel).

Returns plain arrays ``(nodes, facets, cell_type)`` in the kernel's packing:
``nodes`` (nv, gdim) float64, ``facets`` (nf, k) int32 in basix node ordering,
facet normals oriented towards the deformable body.  Lengths in mm.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import gmsh
import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["cap_surface_mesh", "plane_surface_mesh"]


def plane_surface_mesh(
    gdim: int, extent: tuple[float, float], size: float, height: float = 0.0
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int32], str]:
    """Mesh of the rigid plane {x_gdim = height} with normal +e_gdim.

    Args:
        gdim: 2 (a segment along x on y = height) or 3 (a square on z = height).
        extent: (lo, hi) of the covered coordinate range in x (and y in 3D), mm.
        size: target element size (mm).
        height: position of the plane (mm).
    """
    lo, hi = extent
    initialized = gmsh.isInitialized()
    if not initialized:
        gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("plane")
    occ = gmsh.model.occ
    if gdim == 2:
        p0, p1 = occ.addPoint(lo, height, 0, size), occ.addPoint(hi, height, 0, size)
        occ.addLine(p0, p1)
    else:
        occ.addRectangle(lo, lo, height, hi - lo, hi - lo)
    occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", size)
    gmsh.model.mesh.generate(gdim - 1)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    nodes = coords.reshape(-1, 3)[:, :gdim]
    index = {int(t): i for i, t in enumerate(tags)}
    etype = 1 if gdim == 2 else 2
    _, enodes = gmsh.model.mesh.getElementsByType(etype)
    facets = np.array([index[int(t)] for t in enodes], dtype=np.int32).reshape(-1, gdim)
    gmsh.model.remove()
    if not initialized:
        gmsh.finalize()
    # orient: 2D normal (t_y, -t_x) must be +y  -> segments run in -x direction;
    # 3D normal t1 x t2 must be +z.
    x = nodes[facets]
    if gdim == 2:
        flip = (x[:, 1, 0] - x[:, 0, 0]) > 0
    else:
        t1, t2 = x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]
        flip = np.cross(t1, t2)[:, 2] < 0
    facets[flip] = facets[flip][:, ::-1] if gdim == 2 else facets[flip][:, [0, 2, 1]]
    cell_type = "interval" if gdim == 2 else "triangle"
    return np.ascontiguousarray(nodes, dtype=np.float64), facets, cell_type


def cap_surface_mesh(
    radius: float, centre: Sequence[float], extent: tuple[float, float], n: int,
    quadratic: bool = True,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int32], str]:
    """Structured mesh of the sphere cap {|x − centre| = radius, z > centre_z} over a square.

    Every node lies on the sphere; the facets are biquadratic (``quadrilateral9``,
    curved: the kernel's curvature terms and third derivatives are exercised) or
    bilinear (``quadrilateral``), oriented with the outward normal (+z at the top).

    Args:
        radius: sphere radius (mm).
        centre: (3,) its centre (mm); the cap is the part above it.
        extent: (lo, hi) of the covered x and y range (mm), inside the sphere's
            silhouette.
        n: facets per side.
        quadratic: quadrilateral9 (True) or quadrilateral facets.
    """
    lo, hi = extent
    cx, cy, cz = np.asarray(centre, dtype=float)
    if max(np.hypot(lo - cx, lo - cy), np.hypot(hi - cx, hi - cy)) >= radius:
        raise ValueError("the square extent reaches beyond the sphere")
    m = 2 * n + 1 if quadratic else n + 1
    xs = np.linspace(lo, hi, m)
    X, Y = np.meshgrid(xs, xs, indexing="ij")
    Z = cz + np.sqrt(radius**2 - (X - cx) ** 2 - (Y - cy) ** 2)
    nodes = np.c_[X.ravel(), Y.ravel(), Z.ravel()]
    s = 2 if quadratic else 1
    facets = []
    for a in range(n):
        for b in range(n):
            i, j = s * a, s * b
            # v0, v1 (along x), v2 (along y), v3: t_x × t_y points up, outward
            f = [i * m + j, (i + s) * m + j, i * m + j + s, (i + s) * m + j + s]
            if quadratic:   # edge nodes of (v0,v1), (v0,v2), (v1,v3), (v2,v3), the centre
                f += [(i + 1) * m + j, i * m + j + 1, (i + 2) * m + j + 1,
                      (i + 1) * m + j + 2, (i + 1) * m + j + 1]
            facets.append(f)
    return (np.ascontiguousarray(nodes), np.array(facets, dtype=np.int32),
            "quadrilateral9" if quadratic else "quadrilateral")

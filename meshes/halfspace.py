"""Extruded hexahedral block for the rigid ball–elastic half-space wear problem (chapter §5.3).

The half-space near the contact is the block x ∈ [−L_x, L_x], y ∈ [0, L_y],
z ∈ [−H, 0] (surface z = 0, sliding along x, symmetry plane y = 0).  It is the
tensor product of three graded 1D grids, each with a uniform fine part of
spacing h near the contact (|x| ≤ l_x, y ≤ l_y, z ≥ −l_z) and a geometrically
coarsening part beyond.  The cross-section mesh (y, z) is the same tensor
product without x, so every 3D vertex (x_i, y_j, z_k) sits over the 2D vertex
(y_j, z_k): :func:`prolongation` returns the extrusion matrix P that copies a
P1 field of the cross-section to every x layer.

Facet tags (3D): TOP (z = 0, potential contact), BOTTOM (z = −H), SYM (y = 0),
FAR (y = L_y), ENDS (x = ±L_x).  Cross-section (2D, coordinates (y, z)): TOP,
BOTTOM, SYM, FAR.  Lengths in mm.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import numpy as np
from dolfinx import mesh as dmesh

if TYPE_CHECKING:
    import numpy.typing as npt
    from mpi4py import MPI

    # a boundary rule: (tag, marker of the points x (gdim × n) on that boundary)
    Rule = tuple[int, Callable[[npt.NDArray[np.float64]], npt.NDArray[np.bool_]]]

__all__ = ["BOTTOM", "ENDS", "FAR", "NAMES", "SECTION_NAMES", "SYM", "TOP", "cross_section",
           "graded_grid", "halfspace_block", "prolongation"]

TOP, BOTTOM, SYM, FAR, ENDS = 1, 2, 3, 4, 5
#: boundary names of the block (:class:`tribofx.body.Body` ``names``) and of the cross-section
NAMES = {"top": TOP, "bottom": BOTTOM, "sym": SYM, "far": FAR, "ends": ENDS}
SECTION_NAMES = {"top": TOP, "bottom": BOTTOM, "sym": SYM, "far": FAR}


def graded_grid(length: float, fine: float, h: float, n_coarse: int) -> npt.NDArray[np.float64]:
    """Nodes 0 = s_0 < … < s_n = ``length``: uniform spacing ≈ h on [0, fine], then geometric.

    The coarse part has ``n_coarse`` elements whose sizes grow by a constant
    ratio from h (bisection on the ratio), so the grid is smooth at s = fine.
    """
    if not 0 < fine < length or n_coarse < 1:
        raise ValueError("need 0 < fine < length and n_coarse >= 1")
    nf = max(1, int(round(fine / h)))
    s = list(np.linspace(0.0, fine, nf + 1))
    rest, hf = length - fine, fine / nf
    if rest <= n_coarse * hf:  # uniform is already coarse enough
        s += list(fine + np.linspace(0.0, rest, n_coarse + 1)[1:])
    else:
        lo, hi = 1.0, 10.0
        for _ in range(100):
            q = 0.5 * (lo + hi)
            total = hf * (q ** np.arange(1, n_coarse + 1)).sum()
            lo, hi = (q, hi) if total < rest else (lo, q)
        steps = hf * q ** np.arange(1, n_coarse + 1)
        s += list(fine + np.cumsum(steps * rest / steps.sum()))
    return np.asarray(s)


def _map(msh: dmesh.Mesh, grids: Sequence[npt.NDArray[np.float64]]) -> None:
    """Map a mesh on the index box [0, n_0] × … to the graded coordinates ``grids``."""
    x = msh.geometry.x
    for d, g in enumerate(grids):
        x[:, d] = np.interp(x[:, d], np.arange(len(g)), g)


def _tags(msh: dmesh.Mesh, rules: Sequence[Rule]) -> dmesh.MeshTags:
    fdim = msh.topology.dim - 1
    # lists of the rules' arrays, then their concatenation
    facets: list[npt.NDArray[np.int32]] | npt.NDArray[np.int32]
    values: list[npt.NDArray[np.int32]] | npt.NDArray[np.int32]
    facets, values = [], []
    for tag, rule in rules:
        f = dmesh.locate_entities_boundary(msh, fdim, rule)
        facets.append(f)
        values.append(np.full(len(f), tag, dtype=np.int32))
    facets = np.concatenate(facets)
    values = np.concatenate(values)
    order = np.argsort(facets)
    facets, idx = np.unique(facets[order], return_index=True)
    return dmesh.meshtags(msh, fdim, facets.astype(np.int32), values[order][idx])


def grids(
    Lx: float, Ly: float, H: float, h: float, lx: float, ly: float, lz: float,
    nc: Sequence[int], hx: float | None = None,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Return the graded 1D grids: x over [−L_x, L_x], y over [0, L_y], z over [−H, 0].

    ``h`` is the fine spacing in y and z, ``hx`` (default h) along x; ``nc`` the
    numbers of coarse elements (x per side, y, z).
    """
    gx = graded_grid(Lx, lx, h if hx is None else hx, nc[0])
    gx = np.concatenate([-gx[::-1], gx[1:]])
    gy = graded_grid(Ly, ly, h, nc[1])
    gz = -graded_grid(H, lz, h, nc[2])[::-1]
    return gx, gy, gz


def halfspace_block(
    comm: MPI.Comm, gx: npt.NDArray[np.float64], gy: npt.NDArray[np.float64],
    gz: npt.NDArray[np.float64],
) -> tuple[dmesh.Mesh, dmesh.MeshTags]:
    """Hexahedral block on the tensor grid gx × gy × gz; returns ``(mesh, facet_tags)``."""
    n = [len(gx) - 1, len(gy) - 1, len(gz) - 1]
    msh = dmesh.create_box(comm, [np.zeros(3), np.array(n, dtype=float)], n,
                           dmesh.CellType.hexahedron)
    _map(msh, (gx, gy, gz))
    tol = 1e-9 * (gx[-1] - gx[0])
    ft = _tags(msh, [
        (TOP, lambda x: np.abs(x[2]) < tol),
        (BOTTOM, lambda x: np.abs(x[2] - gz[0]) < tol),
        (SYM, lambda x: np.abs(x[1]) < tol),
        (FAR, lambda x: np.abs(x[1] - gy[-1]) < tol),
        (ENDS, lambda x: np.abs(np.abs(x[0]) - gx[-1]) < tol),
    ])
    return msh, ft


def cross_section(
    comm: MPI.Comm, gy: npt.NDArray[np.float64], gz: npt.NDArray[np.float64]
) -> tuple[dmesh.Mesh, dmesh.MeshTags]:
    """Quadrilateral cross-section mesh on gy × gz (coordinates (y, z)); ``(mesh, facet_tags)``."""
    n = [len(gy) - 1, len(gz) - 1]
    msh = dmesh.create_rectangle(comm, [np.zeros(2), np.array(n, dtype=float)], n,
                                 dmesh.CellType.quadrilateral)
    _map(msh, (gy, gz))
    tol = 1e-9 * gy[-1]
    ft = _tags(msh, [
        (TOP, lambda x: np.abs(x[1]) < tol),
        (BOTTOM, lambda x: np.abs(x[1] - gz[0]) < tol),
        (SYM, lambda x: np.abs(x[0]) < tol),
        (FAR, lambda x: np.abs(x[0] - gy[-1]) < tol),
    ])
    return msh, ft


def prolongation(
    X3: npt.NDArray[np.float64], X2: npt.NDArray[np.float64],
    components: Sequence[tuple[int, int]] | None = None,
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], tuple[int, int]]:
    """Extrusion map (rows, cols, shape) of the 0/1 matrix P: 3D nodal values = P · 2D values.

    ``X3`` (n3 × ≥3) and ``X2`` (n2 × 2) are the node coordinates of the 3D and 2D
    P1 spaces (block dofs); the 3D node (x, y, z) takes the value of the 2D node
    (y, z), so P has one unit entry per row: P[rows[i], cols[i]] = 1.  With
    ``components`` = [(c3, c2), …] the spaces are vector valued (blocked, bs3 = 3,
    bs2 = 2) and component c2 of the 2D field goes to component c3 of the 3D
    field (the other 3D components have empty rows).  Every 3D node must sit over a
    2D node (structured extrusion), else ValueError.
    """
    scale = max(np.ptp(X2[:, 0]), np.ptp(X2[:, 1]), 1e-300)
    key2 = {(round(y / scale, 9), round(z / scale, 9)): j for j, (y, z) in enumerate(X2[:, :2])}
    try:
        cols = np.array([key2[(round(y / scale, 9), round(z / scale, 9))]
                         for y, z in X3[:, 1:3]], dtype=np.int64)
    except KeyError:
        raise ValueError("3D node without a cross-section node: not an extrusion") from None
    n3, n2 = len(X3), len(X2)
    rows = np.arange(n3, dtype=np.int64)
    if components is None:
        return rows, cols, (n3, n2)
    r = np.concatenate([3 * rows + c3 for c3, _ in components])
    c = np.concatenate([2 * cols + c2 for _, c2 in components])
    return r, c, (3 * n3, 2 * n2)

"""A structured rectangular block (plane strain) with its four sides tagged.

``block_mesh(comm, (x0, y0), (x1, y1), nx, ny)`` returns ``(mesh, facet_tags)``
of the rectangle [x0, x1] × [y0, y1], nx × ny squares each split in four
triangles (crossed diagonals), with the facet tags of :data:`NAMES`: 1 top,
2 bottom, 3 sides (x = x0 and x = x1).  Lengths in mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from dolfinx import mesh
from mpi4py import MPI

if TYPE_CHECKING:
    import numpy.typing as npt
    from dolfinx.mesh import Mesh, MeshTags

__all__ = ["BOTTOM", "NAMES", "SIDES", "TOP", "block_mesh"]

TOP, BOTTOM, SIDES = 1, 2, 3
NAMES = {"top": TOP, "bottom": BOTTOM, "sides": SIDES}


def block_mesh(
    comm: MPI.Comm | None, lower: tuple[float, float], upper: tuple[float, float], nx: int,
    ny: int,
) -> tuple[Mesh, MeshTags]:
    """Rectangle [lower, upper] with nx × ny crossed squares; returns ``(mesh, facet_tags)``."""
    (x0, y0), (x1, y1) = lower, upper
    msh = mesh.create_rectangle(comm if comm is not None else MPI.COMM_WORLD,
                                [[x0, y0], [x1, y1]], [nx, ny],
                                diagonal=mesh.DiagonalType.crossed)
    fdim = msh.topology.dim - 1
    parts = [(TOP, lambda x: np.isclose(x[1], y1)), (BOTTOM, lambda x: np.isclose(x[1], y0)),
             (SIDES, lambda x: np.isclose(x[0], x0) | np.isclose(x[0], x1))]
    ents: list[npt.NDArray[np.int32]]
    vals: list[npt.NDArray[np.int32]]
    ents, vals = [], []
    for tag, where in parts:
        e = mesh.locate_entities_boundary(msh, fdim, where)
        if tag == SIDES:     # corner facets belong to the top or the bottom
            e = np.setdiff1d(e, np.concatenate(ents))
        ents.append(e)
        vals.append(np.full(len(e), tag, np.int32))
    e, v = np.concatenate(ents), np.concatenate(vals)
    order = np.argsort(e)
    return msh, mesh.meshtags(msh, fdim, e[order], v[order])

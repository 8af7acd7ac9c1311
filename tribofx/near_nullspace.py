"""Rigid-body near-nullspace of the bulk unknowns, for algebraic multigrid.

Smoothed-aggregation AMG (GAMG) builds its coarse spaces from the kernel of the
elasticity operator; the translations and rotations of each displacement-like
field, in the layout of the fieldsplit's bulk block, are that kernel.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, cast

import numpy as np
import numpy.typing as npt
from petsc4py import PETSc

if TYPE_CHECKING:
    from dolfinx import fem

__all__ = ["near_nullspace", "orthonormalise", "rigid_body_modes"]


def rigid_body_modes(V: fem.FunctionSpace) -> npt.NDArray[np.float64]:
    """Rigid-body modes of the vector space ``V`` (2D: 3, 3D: 6), on its owned dofs.

    Returns an array (modes, owned dofs · bs) in the space's blocked layout:
    translations e_i, rotations e_i × (x − x̄), with x the dof coordinates.
    """
    gdim = V.mesh.geometry.dim
    n = V.dofmap.index_map.size_local
    x = V.tabulate_dof_coordinates()[:n, :gdim]
    comm = V.mesh.comm
    centre = comm.allreduce(x.sum(axis=0)) / max(comm.allreduce(n), 1)
    x = x - centre
    modes = []
    for i in range(gdim):
        m = np.zeros((n, gdim))
        m[:, i] = 1.0
        modes.append(m)
    pairs = [(0, 1)] if gdim == 2 else [(0, 1), (1, 2), (2, 0)]
    for i, j in pairs:
        m = np.zeros((n, gdim))
        m[:, i], m[:, j] = -x[:, j], x[:, i]
        modes.append(m)
    return np.array([m.ravel() for m in modes])


def near_nullspace(spaces: Sequence[fem.FunctionSpace], sizes: Sequence[int],
                   comm: PETSc.Comm) -> PETSc.NullSpace:
    """PETSc near-nullspace of the bulk block: the rigid-body modes of each space.

    Args:
        spaces: the vector function spaces of the bulk unknowns, in block order.
        sizes: owned sizes (dofs · bs) of those unknowns on this rank.
        comm: communicator of the bulk block.

    Returns a ``PETSc.NullSpace`` of orthonormal vectors of length ``sum(sizes)``
    (owned), each mode nonzero on one unknown's rows only.
    """
    vecs = []
    for j, V in enumerate(spaces):
        for mode in rigid_body_modes(V):
            arr = np.zeros(sum(sizes))
            s = sum(sizes[:j])
            arr[s:s + sizes[j]] = mode
            v = PETSc.Vec().createMPI((sum(sizes), PETSc.DECIDE), comm=comm)
            v.setArray(arr)  # type: ignore[arg-type]  # petsc4py stub: Sequence, not ndarray
            vecs.append(v)
    # MatNullSpaceCreate needs an orthonormal basis
    return PETSc.NullSpace().create(vectors=orthonormalise(vecs), comm=comm)


def orthonormalise(vecs: Sequence[PETSc.Vec]) -> list[PETSc.Vec]:
    """Orthonormalise PETSc vectors in place by modified Gram–Schmidt.

    Returns the orthonormal vectors (a nearly dependent vector, norm below 1e-12
    after projection, is dropped).
    """
    out: list[PETSc.Vec] = []
    for v in vecs:
        for q in out:
            v.axpy(-v.dot(q), q)
        n = cast(float, v.norm())   # the 2-norm (the stub's tuple is NORM_1_AND_2's)
        if n > 1e-12:
            v.scale(1.0 / n)
            out.append(v)
    return out

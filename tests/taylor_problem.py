"""Taylor test of a :class:`tribofx.problem.Problem`'s assembled Jacobian (public API only).

For a direction d, the remainder r(ε) = ‖R(x + ε d) − R(x) − ε J(x) d‖ of the
problem's own residual and Jacobian (:meth:`Problem.assemble`,
:meth:`Problem.residual_at`) must decay like ε² when J is the exact derivative.
Unlike :func:`taylor.problem_taylor_orders` (directions as Functions, copied by
``dolfinx.fem.petsc.assign``), the directions are the owned arrays of the
problem's own layout, so a :class:`tribofx.reduced.ReducedProblem` with
replicated unknowns (owned by rank 0) is tested on several ranks too.
"""

import numpy as np
from petsc4py import PETSc

__all__ = ["block_vector", "owned_arrays", "taylor_orders"]


def _replicated(problem, f):
    return f.function_space.mesh.comm.size == 1 and problem.snes.comm.size > 1


def owned_arrays(problem, functions=None):
    """Owned entries of each unknown (a replicated unknown is owned by rank 0)."""
    out = []
    for ui, f in zip(problem.u, functions or problem.u):
        V = ui.function_space
        if _replicated(problem, ui):
            n = len(f.x.array) if problem.snes.comm.rank == 0 else 0
        else:
            n = V.dofmap.index_map.size_local * V.dofmap.index_map_bs
        out.append(np.asarray(f.x.array[:n] if hasattr(f, "x") else f[:n]))
    return out


def block_vector(problem, arrays):
    """PETSc vector of the problem's layout from the owned arrays of each unknown."""
    x = problem.snes.getFunction()[0].duplicate()
    x.setArray(np.concatenate(arrays))
    return x


def taylor_orders(problem, direction, eps0=1e-3, n=4):
    """Orders log₂(r(ε)/r(ε/2)) at the current unknowns along ``direction`` (owned arrays).

    Returns (orders, remainders relative to ε₀‖J d‖); the unknowns are restored.
    """
    saved = [ui.x.array.copy() for ui in problem.u]
    b0, A = problem.assemble()
    b0 = b0.copy()
    x0 = block_vector(problem, owned_arrays(problem))
    d = block_vector(problem, direction)
    Ad = A.createVecLeft()
    A.mult(d, Ad)
    rem = []
    for k in range(n):
        eps = eps0 * 2.0**-k
        x = x0.copy()
        x.axpy(eps, d)
        r = problem.residual_at(x)
        r.axpy(-1.0, b0)
        r.axpy(-eps, Ad)
        rem.append(r.norm(PETSc.NormType.NORM_2))
        for v in (x, r):
            v.destroy()
    for ui, a in zip(problem.u, saved):
        ui.x.array[:] = a
    problem.refresh()
    rem = np.array(rem)
    return np.log2(rem[:-1] / rem[1:]), rem / (eps0 * Ad.norm())

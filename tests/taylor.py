"""Taylor tests of residuals against their assembled Jacobians.

For a direction d, the remainder r(ε) = ‖R(u + ε d) − R(u) − ε J(u) d‖ must decay
like ε² when J is the exact derivative of R; the observed orders
log₂(r(ε)/r(ε/2)) are returned with the remainders relative to the linear term
ε₀‖J d‖.

* :func:`problem_taylor_orders` — a :class:`tribofx.problem.Problem` at its
  current unknowns, through its public ``assemble()`` and ``residual_at(x)``
  (so every component's ``refresh`` — e.g. the kernel projection onto a meshed
  countersurface — runs at each perturbed state, as in Newton's iteration);
* :func:`taylor_orders` — bare residual forms (no components).
"""

import dolfinx.fem.petsc as fem_petsc
import numpy as np

from tribofx.newton import BlockNewton


def problem_taylor_orders(problem, directions, eps0=1e-3, n=4):
    """Observed orders and relative remainders of ``problem`` along ``directions``.

    ``directions``: one ``fem.Function`` per unknown of ``problem.u`` (same order).
    The unknowns are restored afterwards.
    """
    base = [f.x.array.copy() for f in problem.u]
    b0, A = problem.assemble()
    b0 = b0.copy()
    x0 = b0.duplicate()
    fem_petsc.assign(problem.u, x0)
    d = b0.duplicate()
    fem_petsc.assign(directions, d)
    Ad = d.duplicate()
    A.mult(d, Ad)
    rem = []
    for k in range(n):
        eps = eps0 * 2.0**-k
        x = x0.copy()
        x.axpy(eps, d)
        r = problem.residual_at(x)
        r.axpy(-1.0, b0)
        r.axpy(-eps, Ad)
        rem.append(r.norm())
        r.destroy()
        x.destroy()
    for f, b in zip(problem.u, base):
        f.x.array[:] = b
    problem.refresh()
    rem = np.array(rem)
    return np.log2(rem[:-1] / rem[1:]), rem / (eps0 * Ad.norm())


def taylor_orders(F, u, directions, entity_maps=None, pre_evaluate=None,
                  eps0=1e-3, n=4):
    """Observed orders and relative remainders of the residual forms ``F`` in ``u``."""
    solver = BlockNewton(F, u, entity_maps=entity_maps, pre_evaluate=pre_evaluate)
    u = solver.u
    base = [f.x.array.copy() for f in u]
    b0, A = solver.assemble()
    b0 = b0.copy()
    d = solver.x.duplicate()
    fem_petsc.assign(directions, d)
    Ad = d.duplicate()
    A.mult(d, Ad)
    rem = []
    for k in range(n):
        eps = eps0 * 2.0**-k
        for f, b, df in zip(u, base, directions):
            f.x.array[:] = b + eps * df.x.array
        fem_petsc.assign(u, solver.x)
        solver._residual()
        r = solver.b.copy()
        r.axpy(-1.0, b0)
        r.axpy(-eps, Ad)
        rem.append(r.norm())
    for f, b in zip(u, base):
        f.x.array[:] = b
    rem = np.array(rem)
    return np.log2(rem[:-1] / rem[1:]), rem / (eps0 * Ad.norm())

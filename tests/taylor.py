"""Taylor test of a block residual against its assembled Jacobian.

Returns the observed orders and the remainders relative to the linear term ε₀‖J d‖.

For a direction d, the remainder r(ε) = ‖R(u + ε d) − R(u) − ε J(u) d‖ must decay
like ε² when J is the exact derivative of R; the observed orders are returned.
"""

import dolfinx.fem.petsc as fem_petsc
import numpy as np

from tribofx.newton import BlockNewton


def taylor_orders(F, u, directions, entity_maps=None, pre_evaluate=None,
                  eps0=1e-3, n=4):
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

"""The exact tangent of the mixed (u, p) solid, per block, in plane strain, 3D and axisymmetry.

The mixed formulation (``Body(formulation="mixed")``: a P1 volumetric stress p
beside u, the perturbed-Lagrangian energy of ``forms/hyperelastic.py``,
Brezzi–Pitkäranta-stabilised) is the O-ring's default; its tangent is
``ufl.derivative`` of the residual, and this checks it block by block
(:func:`tribofx.testing.block_taylor_orders`: a wrong column of the p block cannot
hide below the stiff u block), at a compressed, sheared state of a nearly
incompressible block (κ = 1000 μ: the regime of the O-ring).  Reference: second
order of the Taylor remainder, or remainders at the round-off floor that do not
decay at first order (:func:`tribofx.testing.exact_tangent`).
"""

import numpy as np
import pytest
import ufl
from dolfinx import mesh
from mpi4py import MPI

from tribofx.body import Body
from tribofx.problem import Problem
from tribofx.testing import block_taylor_orders, exact_tangent, owned_arrays

MU = 1.0          # MPa
KAPPA = 1000.0    # MPa: nearly incompressible, as the O-ring (κ = 1000 G)


def _tags(msh, where):
    fdim = msh.topology.dim - 1
    parts = []
    for tag, w in where.items():
        f = mesh.locate_entities_boundary(msh, fdim, w)
        parts.append((f, np.full(len(f), tag, np.int32)))
    idx = np.concatenate([p[0] for p in parts])
    val = np.concatenate([p[1] for p in parts])
    idx, first = np.unique(idx, return_index=True)
    return mesh.meshtags(msh, fdim, idx, val[first])


def _body(kind, law):
    comm = MPI.COMM_WORLD
    if kind == "3d":
        msh = mesh.create_box(comm, [[1, 0, 0], [2, 1, 1]], [3, 3, 3])
    else:
        msh = mesh.create_rectangle(comm, [[1, 0], [2, 1]], [4, 4])   # off the axis
    top = msh.geometry.dim - 1
    ft = _tags(msh, {1: lambda x: np.isclose(x[top], 0), 2: lambda x: np.isclose(x[top], 1)})
    mat = ({"mu": MU, "lmbda": KAPPA - 2 * MU / 3} if law == "neo-hookean"
           else {"mu1": 0.6 * MU / 2, "mu2": 0.4 * MU / 2, "kappa": KAPPA})
    body = Body(msh, ft, {"bottom": 1, "top": 2}, kind, (law, mat), formulation="mixed",
                name=f"mixed_{kind}")
    body.add_dirichlet("bottom", [0.0] * msh.geometry.dim)
    gdim = msh.geometry.dim
    shear = [0.0] * gdim
    shear[0] = 0.1 * MU
    body.add_traction("top", ufl.as_vector(shear))
    body.add_follower_pressure("top", 0.2 * MU)
    return body


@pytest.mark.mpi
@pytest.mark.parametrize("kind, law", [("plane_strain", "neo-hookean"), ("3d", "neo-hookean"),
                                       ("axisymmetric", "mooney-rivlin")])
def test_mixed_solid_tangent_is_exact_per_block(kind, law):
    body = _body(kind, law)
    problem = Problem([body], name=f"mixed_tangent_{kind}")
    problem.solve()
    # a finite deformation: the top moved by a few per cent of the block
    u = body.u.x.array
    assert MPI.COMM_WORLD.allreduce(float(np.max(np.abs(u), initial=0.0)), op=MPI.MAX) > 0.02
    rng = np.random.default_rng(MPI.COMM_WORLD.rank)
    scale = {0: 1e-2, 1: 1e-2 * MU}
    dirs = owned_arrays(problem, [scale[k] * rng.standard_normal(len(f.x.array))
                                  for k, f in enumerate(problem.u)])
    out = block_taylor_orders(problem, dirs, eps0=1.0)
    assert len(out) == 2                     # u and the volumetric stress p
    for name, (orders, rem, floor) in out.items():
        print(kind, name, orders, rem, floor)
        assert exact_tangent(orders, rem, floor), (kind, name, orders, rem)

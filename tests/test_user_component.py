"""A researcher's own component, written against the documented protocol only
(:class:`tribofx.protocols.Component`, docs/architecture.md "Write your own
component"): a nonlinear elastic foundation (Winkler springs, force per area
k u_n + k₃ u_n³ against the normal displacement) under the bottom of a block.

References: the protocol check; the exact solution of a plane-strain block with
free sides on a linear foundation (uniform uniaxial stress: the bottom sinks by
q/k, the top by q/k + q H (1 − ν²)/E, exact for P1 since the strain is uniform);
the Taylor test of the nonlinear foundation with :mod:`tribofx.testing`; its
parameters restored by ``restore()``.
"""

import numpy as np
import pytest
import ufl
from dolfinx import fem, mesh
from mpi4py import MPI

from tribofx.body import Body
from tribofx.problem import Problem
from tribofx.protocols import Component, ComponentBase
from tribofx.testing import block_taylor_orders, exact_tangent, owned_arrays

E, NU, H, Q = 10.0, 0.3, 1.0, 0.05


class Foundation(ComponentBase):
    """Winkler springs under boundary ``name`` of ``body``: T = −(k u·N + k₃ (u·N)³) N."""

    def __init__(self, body, name, k, k3=0.0):
        self.body = body
        msh = body.mesh
        self.k, self.k3 = fem.Constant(msh, float(k)), fem.Constant(msh, float(k3))
        self.ds = body.ds(body.tag(name))
        self.N = ufl.FacetNormal(msh)

    # -- the protocol --------------------------------------------------------------
    def unknowns(self):
        return []                          # it adds rows to the body's unknown only

    def contributions(self):
        un = ufl.dot(self.body.u, self.N)
        work = (self.k * un + self.k3 * un**3) * ufl.dot(self.body.v, self.N) * self.ds
        return [(self.body.u, work)]

    def tolerances(self):
        return {}                          # the body's momentum test covers its rows

    def state_fields(self):
        return [self.k, self.k3]



def _block(k3=0.0, material="linear"):
    comm = MPI.COMM_WORLD
    msh = mesh.create_rectangle(comm, [[0, 0], [2, H]], [8, 4])
    fdim = 1
    tags = []
    for tag, where in ((1, lambda x: np.isclose(x[1], 0)), (2, lambda x: np.isclose(x[1], H)),
                       (3, lambda x: np.isclose(x[0], 0))):
        f = mesh.locate_entities_boundary(msh, fdim, where)
        tags.append((f, np.full(len(f), tag, np.int32)))
    idx = np.concatenate([t[0] for t in tags])
    val = np.concatenate([t[1] for t in tags])
    order = np.argsort(idx)
    ft = mesh.meshtags(msh, fdim, idx[order], val[order])
    mu, lmbda = E / (2 * (1 + NU)), E * NU / ((1 + NU) * (1 - 2 * NU))
    body = Body(msh, ft, {"bottom": 1, "top": 2, "left": 3}, "plane_strain",
                (material, {"mu": mu, "lmbda": lmbda}))
    body.add_dirichlet("left", 0.0, component=0)          # symmetry: no rigid x-motion
    body.add_traction("top", ufl.as_vector([0.0, -Q]))
    return body, Foundation(body, "bottom", k=20.0, k3=k3)


def test_user_component_follows_the_protocol_and_the_exact_solution():
    body, foundation = _block()
    assert isinstance(foundation, Component) and isinstance(body, Component)
    problem = Problem([body, foundation], name="user_foundation")
    rep = problem.solve()
    # uniaxial stress −Q: the bottom sinks by Q/k, the top by Q/k + Q H (1 − ν²)/E
    X = body.V.tabulate_dof_coordinates()
    uy = body.u.x.array.reshape(-1, 2)[:, 1]
    n = body.V.dofmap.index_map.size_local
    top, bottom = np.isclose(X[:n, 1], H), np.isclose(X[:n, 1], 0)
    exact_b = -Q / 20.0
    exact_t = exact_b - Q * H * (1 - NU**2) / E
    # the Newton test stops at nodal forces of rtol·E·L² ≈ 1e-9 N/mm: with the
    # stiffness ≥ k h ≈ 5 N/mm² per node the displacement error is ≤ 1e-9 mm
    err = max(float(np.max(np.abs(uy[:n][top] - exact_t), initial=0.0)),
              float(np.max(np.abs(uy[:n][bottom] - exact_b), initial=0.0)))
    err = MPI.COMM_WORLD.allreduce(err, op=MPI.MAX)
    print("Newton", rep.iterations, "max error", err)
    assert err < 1e-8


def test_user_component_tangent_and_state():
    body, foundation = _block(k3=3e6, material="neo-hookean")
    problem = Problem([body, foundation], name="user_foundation_nl")
    problem.solve()
    # the cubic spring is in its nonlinear range: k₃ u² ≈ k at the bottom (u ≈ Q/2k)
    uy = body.u.x.array.reshape(-1, 2)[:, 1]
    u_min = MPI.COMM_WORLD.allreduce(float(uy.min(initial=0.0)), op=MPI.MIN)
    assert 3e6 * u_min**2 > 0.3 * 20.0
    state = problem.state()
    foundation.k3.value = 1.0
    problem.restore(state)
    assert float(foundation.k3.value) == 3e6
    rng = np.random.default_rng(0)
    dirs = owned_arrays(problem, [1e-3 * rng.standard_normal(len(f.x.array))
                                  for f in problem.u])
    for name, (orders, rem, floor) in block_taylor_orders(problem, dirs, eps0=1.0).items():
        print(name, orders, rem)
        assert exact_tangent(orders, rem, floor), (name, orders, rem)


def test_a_component_missing_a_method_is_not_one():
    class Half:
        def unknowns(self):
            return []

    assert not isinstance(Half(), Component)
    with pytest.raises(TypeError, match="ComponentBase"):
        Problem([Half()], name="half")

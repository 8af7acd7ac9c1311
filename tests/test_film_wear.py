"""Wear on any interface: a Film, a Contact, or both, drive the shape law (28).

A plane-strain block [0, 1] × [0, 0.5] mm with a shape field; its bottom face is
lubricated against a rigid cylinder (radius 2 mm, clearance 10 µm under the
middle) sliding at U, and (in the combined case) also in contact with it.  The
wear rows are those of :class:`tribofx.interfaces.Wear` with the film's load
(:func:`tribofx.forms.film_traction.film_wear_load`: T_N = −p⁺ j, ‖v_layer − v_counter‖).
"""

import numpy as np
import pytest
from dolfinx import mesh
from mpi4py import MPI

from tribofx.body import Body
from tribofx.interfaces import Contact, Film, FilmScales, Fluid, Penalty, Quadrature, Wear
from tribofx.obstacles import rigid_cylinder
from tribofx.problem import Problem
from tribofx.roughness import Roughness, greenwood_tripp
from tribofx.scheme import IMPLICIT
from tribofx.testing import block_taylor_orders, exact_tangent, smooth_direction

U = 100.0      # mm/s, the cylinder's sliding speed
K = 1e-4       # 1/MPa, Archard coefficient
P0 = 0.05      # MPa, the scale of the film pressure set below
CENTRE = np.array([0.5, -2.01])
SIGMA = 5e-3   # mm, the roughness of the mixed variant


def _block(with_contact, rough=False):
    comm = MPI.COMM_WORLD
    msh = mesh.create_rectangle(comm, [[0, 0], [1, 0.5]], [8, 3])
    fdim = 1
    parts = [(1, lambda x: np.isclose(x[1], 0)), (2, lambda x: np.isclose(x[1], 0.5)),
             (3, lambda x: np.isclose(x[0], 0) | np.isclose(x[0], 1))]
    ents, vals = [], []
    for tag, where in parts:
        e = np.setdiff1d(mesh.locate_entities_boundary(msh, fdim, where),
                         np.concatenate(ents) if ents else [])
        ents.append(e)
        vals.append(np.full(len(e), tag, dtype=np.int32))
    e, v = np.concatenate(ents), np.concatenate(vals)
    order = np.argsort(e)
    ft = mesh.meshtags(msh, fdim, e[order].astype(np.int32), v[order])
    body = Body(msh, ft, {"bottom": 1, "top": 2, "sides": 3}, "plane_strain",
                ("neo-hookean", {"mu": 1.0, "lmbda": 1.5}), shape=True, aux=(3.0, 0.3))
    body.add_dirichlet("top", np.zeros(2))
    body.add_shape_dirichlet("top", 0)
    body.add_shape_dirichlet("top", 1)
    body.add_shape_dirichlet("sides", 0)
    # rough: σ = 5 µm against the 10 µm clearance (H ≈ 2 mid-face): average flow,
    # asperity pressure and boundary friction all active, the wear driven by p_a
    roughness = Roughness(SIGMA, asperity=greenwood_tripp(2.0, SIGMA), mu_b=0.2) \
        if rough else None
    film = Film(body, "bottom", rigid_cylinder(CENTRE, 2.0), Fluid(1e-8),
                scales=FilmScales(pressure=P0, film=0.01, speed=U), cavitation=Penalty(1e-6),
                quadrature=Quadrature(degree=2), roughness=roughness, V_counter=(U, 0.0))
    film.add_pressure_bc(lambda X: np.isclose(X[0], 0) | np.isclose(X[0], 1))
    drivers = [film]
    if with_contact:
        drivers.append(Contact(body, "bottom", rigid_cylinder(CENTRE, 2.0), rho_n=10.0))
    wear = Wear(drivers if with_contact else film, K, speed=U, scheme=IMPLICIT)
    return body, film, drivers, wear


def _state(body, film, wear, dt):
    """A smooth state off every kink: p > 0 inside, u, w ≠ w_n, ζ; Δt > 0."""
    film.p.interpolate(lambda x: P0 * (0.2 + np.sin(np.pi * x[0])))
    film.p.x.array[np.isclose(film.Q.tabulate_dof_coordinates()[:, 0], 0)
                   | np.isclose(film.Q.tabulate_dof_coordinates()[:, 0], 1)] = 0.0
    body.u.interpolate(lambda x: np.array([1e-3 * np.sin(x[0]) * (0.5 - x[1]),
                                           2e-3 * np.cos(x[0]) * (0.5 - x[1])]))
    body.w.interpolate(lambda x: np.array([0.0 * x[0], -1e-3 * np.cos(x[0]) * (0.5 - x[1])]))
    wear.zeta.interpolate(lambda x: 0.1 + 0.0 * x[0])
    wear.dt.value = dt


@pytest.mark.mpi
@pytest.mark.parametrize("with_contact,rough", [(False, False), (True, False), (False, True)])
def test_film_driven_wear_tangent_taylor(with_contact, rough):
    """The monolithic (u, u_s, p, g, [λ_N], w, ζ) step with wear driven by the film (and a
    contact): every block's columns exact (Taylor order 2 or round-off,
    :func:`tribofx.testing.exact_tangent`), the film load's dependence on u (j, the
    layer velocity) and p (p⁺) included.  ``rough``: the lubricated wear step of mixed
    lubrication — average flow, asperity traction and the wear by p_a(h),
    whose h depends on u and w."""
    body, film, drivers, wear = _block(with_contact, rough)
    problem = Problem([body, *drivers, wear], name="film_wear_taylor")
    _state(body, film, wear, dt=10.0)
    if with_contact:
        drivers[1].lam_n.interpolate(lambda x: -0.02 - 0.0 * x[0])   # all pressed, off λ_N = 0
    problem.refresh()
    dirs = [smooth_direction(f, 1e-3 * (P0 if f is film.p else 1.0), 5 + i)
            for i, f in enumerate(problem.u)]
    dirs[problem.u.index(film.p)].x.array[film.p.x.array == 0] = 0.0    # the p = 0 rows
    for name, (orders, rem, floor) in block_taylor_orders(problem, dirs, eps0=1e-3).items():
        print(with_contact, name, "orders", orders, "remainders", rem, "floor", floor)
        assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)


@pytest.mark.mpi
@pytest.mark.parametrize("with_contact", [False, True])
def test_film_driven_wear_rate_is_archard_at_the_nodes(with_contact):
    """On the undeformed, unworn block (u = w = 0: j = 1) the worn-volume rate ∫ Ẇ dS of
    the vertex rule is Σ_i ω_i k (p_i ‖v_i‖ + |λ_i| U) over the nodes of the bottom face
    (ω_i the lumped lengths, h/2 at the ends, h inside), recomputed here in NumPy from
    the nodal p and λ_N: equal to round-off (1e-12 relative).  The film's sliding speed
    is the cylinder's velocity U e_x projected on its own tangent at the closest point,
    ‖v_i‖ = U |ν_y| with ν = (X_i − c)/|X_i − c| (eq. 42); the contact's is the Wear's U."""
    body, film, drivers, wear = _block(with_contact)
    film.p.interpolate(lambda x: P0 * np.sin(np.pi * x[0]) ** 2)
    if with_contact:
        drivers[1].lam_n.interpolate(lambda x: -0.03 * (1 + x[0]))
    rate = wear.wear_rate_integral()
    # by hand: nodes of the bottom face, their lumped lengths
    X = film.Q.tabulate_dof_coordinates()[:, 0]
    n_own = film.Q.dofmap.index_map.size_local
    h = 1.0 / 8
    omega = np.where(np.isclose(X, 0) | np.isclose(X, 1), h / 2, h)
    p = P0 * np.sin(np.pi * X) ** 2
    lam = 0.03 * (1 + X) if with_contact else 0.0 * X
    nu_y = -CENTRE[1] / np.hypot(X - CENTRE[0], -CENTRE[1])
    local = float(np.sum((omega * K * (p * U * nu_y + lam * U))[:n_own]))
    by_hand = MPI.COMM_WORLD.allreduce(local, op=MPI.SUM)
    print("rate", rate, "by hand", by_hand)
    assert rate == pytest.approx(by_hand, rel=1e-12)


def test_wear_refuses_interfaces_on_other_boundaries():
    """A Wear on a film and a contact of different boundaries is a one-line ValueError."""
    body, film, _, _ = _block(False)
    other = Contact(body, "top", rigid_cylinder(CENTRE, 2.0), rho_n=10.0)
    with pytest.raises(ValueError, match="same boundary"):
        Wear([film, other], K, speed=U)


@pytest.mark.mpi
def test_film_driven_wear_shape_outputs():
    """The worn-shape outputs of a film-driven Wear (its Surface, not a contact's nodal
    data): at w = 0 the depth is 0 at every node of the bottom face (all ranks), and a
    prescribed uniform shape change −d N̂ (d = 1e-3 mm, w_y = d on y = 0) gives depth d
    exactly (vertex-rule nodal normals of a flat face)."""
    body, film, _, wear = _block(False)
    assert wear.max_depth() == 0.0
    d = 1e-3
    body.w.interpolate(lambda x: np.array([0.0 * x[0], d * (1 - x[1] / 0.5)]))
    shape = wear.gather_shape(root_only=False)
    assert np.allclose(shape["depth"], d, rtol=0, atol=1e-15)
    assert len(shape["X_hat"]) == 9          # the 8 + 1 nodes of the bottom face

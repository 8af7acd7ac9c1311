"""The film between two deformable bodies (TwoBodyFilm): kernel, tangent, balance, rigid limit.

The pair: an elastic roller (R = 10 mm, centre (0, R + h₀)) over an elastic block,
both rolling/sliding, the block pushed up by δ; a film of viscosity μ = 1e-7 MPa·s
(0.1 Pa·s) between them (p = 0 at both ends, no cavitation term).
"""

import numpy as np
import pytest
from mpi4py import MPI
from tribofx.forms.hyperelastic import lame_parameters
from tribofx.meshes.roller import ROLLER_NAMES, roller

from tribofx.body import Body
from tribofx.interfaces import Film, FilmScales, Fluid, Quadrature, TwoBodyFilm
from tribofx.motions import Rolling, Sliding
from tribofx.obstacles import rigid_plane
from tribofx.problem import Problem
from tribofx.testing import block_taylor_orders, exact_tangent, owned_arrays
from tribofx.two_body import film_node_residuals
from tribofx.two_body_film_ref import film_node_residuals as film_node_residuals_ref

R, X_L, H0, MU = 10.0, 3.0, 0.01, 1e-7


def _body(msh, ft, E, name):
    mu, lmbda = lame_parameters(E, 0.45)
    return Body(msh, ft, ROLLER_NAMES, "plane_strain",
                ("neo-hookean", {"mu": mu, "lmbda": lmbda}), name=name)


def roller_on_block(comm=MPI.COMM_WORLD, E2=10.0, U1=1000.0, U2=1000.0, h_fine=0.2,
                    rigid=False, **film_kw):
    """Roller (E1 = 10 MPa) over a block (E2); a TwoBodyFilm, or the rigid plane's Film.

    ``rigid``: True: no block; the roller's Film against the rigid plane y = δ
    sliding with U2, on the roller's own surface (S_1 = γ_l, alpha=1), the vertex
    rule; None: the block, with the vertex rule too.
    Returns (bodies, film, problem, push) with push the block's (or plane's) lift δ.
    """
    m1, f1 = roller(R, X_L, h_fine, 3.0, X_L, comm)
    m1.geometry.x[:, 1] += H0
    upper = _body(m1, f1, 10.0, "upper")
    upper.add_dirichlet("loaded", np.zeros(2))
    kw = dict(scales=FilmScales(pressure=0.1, film=H0, speed=U1), **film_kw)
    if rigid:
        film = Film(upper, "lubricated", rigid_plane([0, 0], [0, 1]), Fluid(MU), alpha=1,
                    V_counter=[U2, 0.0], quadrature=Quadrature("vertex"),
                    motion=(Rolling((0, R + H0), R), _constant(upper, U1)), **kw)
        bodies, push = [upper], film.counterpart.offset
    else:
        m2, f2 = roller(R, X_L + 1.0, h_fine, 3.0, X_L + 1.0, comm, block=10.0)
        lower = _body(m2, f2, E2, "lower")
        push = lower.add_dirichlet("loaded", np.zeros(2))
        if rigid is None:
            kw["quadrature"] = Quadrature("vertex")
        film = TwoBodyFilm(upper, "lubricated", lower, "lubricated", Fluid(MU),
                           motion1=Rolling((0, R + H0), R), U1=U1, motion2=Sliding((1, 0)),
                           U2=U2, **kw)
        bodies = [upper, lower]
    film.add_pressure_bc()
    return bodies, film, Problem([*bodies, film], name="roller_on_block"), push


def _constant(body, value):
    from dolfinx import fem

    return fem.Constant(body.mesh, float(value))


def _loaded(delta=0.01, **kw):
    bodies, film, problem, push = roller_on_block(**kw)
    for d in (0.0, delta):
        push.value[:] = [0.0, d]
        rep = problem.solve()
    return bodies, film, problem, rep


@pytest.mark.parametrize("dim", [2, 3])
def test_kernel_matches_its_numpy_twin(dim):
    """C++ residuals and dual-number tangents = the NumPy twin's (complex step) to round-off.

    Both evaluate the same few products of O(1) numbers: agreement to 1e-12 of the
    largest entry (a few ε_mach per operation, ≤ 20 operations; in 3D the metric's
    2 × 2 inverse adds a few more).  3D: the master triangle in place of the segment.
    """
    rng = np.random.default_rng(3)
    n = 50
    if dim == 2:
        q = rng.normal(size=(n, 11))
        q[:, 2:4] += [-1.0, 0.0]
        q[:, 4:6] += [1.0, 0.0]             # segments of length ≈ 2
        data = rng.normal(size=(n, 7))
    else:
        q = 0.3 * rng.normal(size=(n, 19))
        q[:, 3:6] += [-1.0, -1.0, 0.0]      # triangles of sides ≈ 2
        q[:, 6:9] += [1.0, -1.0, 0.0]
        q[:, 9:12] += [0.0, 1.0, 0.0]
        q[:, 12:19] = rng.normal(size=(n, 7))
        data = rng.normal(size=(n, 16))
    w, w_c = rng.random(n) + 0.1, rng.random(n) + 0.1
    r, J = film_node_residuals(q, data, w, w_c, 3.0, 0.5)
    r_ref, J_ref = film_node_residuals_ref(q, data, w, w_c, 3.0, 0.5)
    assert np.max(np.abs(r - r_ref)) <= 1e-12 * np.max(np.abs(r_ref))
    assert np.max(np.abs(J - J_ref)) <= 1e-12 * np.max(np.abs(J_ref))


def test_tangent_exact_in_every_block():
    """Taylor remainders O(ε²) along each unknown alone: slave, master, film and nodal columns.

    Rolling and sliding (U1 = 1000, U2 = 400 mm/s); directions of 1e-6 of each
    unknown's scale (mm, MPa, mm/s) keep the pairing of every node.
    """
    bodies, film, problem, _ = _loaded(U2=400.0)
    rng = np.random.default_rng(5)
    scale = {"gap": 1e-6, "counter_velocity": 1e-3, "pressure": 1e-4}
    dirs = []
    for f in problem.u:
        s = next((v for k, v in scale.items() if k in f.name), 1e-6)
        dirs.append(s * rng.standard_normal(len(f.x.array)))
    out = block_taylor_orders(problem, owned_arrays(problem, dirs), eps0=1.0, n=4)
    for name, (orders, rem, floor) in out.items():
        assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)


def test_newton_converges_quadratically():
    """The last corrections of the pressure fall at order ≥ 1.8 (exact tangent)."""
    _, film, _, rep = _loaded(U2=400.0)
    orders = rep.increment_orders(film.p.name, floor=1e-12)
    assert len(orders) >= 1 and orders[-1] > 1.8, rep.increments


def test_each_body_balances_the_film():
    """Support reaction + film force = 0 on each body, and the forces are opposite.

    The reactions come from the bodies' own rows (internal work), so this checks
    that the kernel puts the film's nodal forces on the right rows of both bodies.
    Bound: the residual tolerance of the momentum rows summed over the support's
    dofs (each row below atol).
    """
    (upper, lower), film, _, _ = _loaded(U2=400.0)
    on_slave, on_master = film.forces()
    assert on_slave[1] > 0.01                                # the film carries the roller
    for body, f in ((upper, on_slave), (lower, on_master)):
        atol = body.tolerances()[body.u].atol
        bound = 2 * body.V.dofmap.index_map.size_global * atol
        for c in range(2):
            assert abs(body.reaction("loaded", c) + f[c]) < bound
    # the same nodal tractions summed twice: round-off of the largest component
    assert np.allclose(on_slave, -on_master, rtol=0, atol=1e-13 * np.abs(on_slave).max())


def test_rigid_master_reproduces_the_rigid_film():
    """A block of E2 = 1e9 MPa sliding at U2 gives the film of the rigid plane (Film, S_1).

    Both on the roller's surface (alpha = 1) with the vertex rule: the same rows
    at the nodes, the gap and plane velocity from the kernel against the analytic
    plane.  The block yields p L/E2 ~ 1e-10 mm against h ~ 3e-2 mm: agreement to
    1e-6 (relative), the solver tolerance being 1e-10.
    """
    vals = []
    for rigid in (None, True):
        _, film, _, _ = _loaded(E2=1e9, U2=400.0, rigid=rigid)
        prof = film.profile(everywhere=True)
        vals.append(np.r_[film.force(), prof["h"].min(), prof["p"].max()])
    assert np.allclose(vals[0], vals[1], rtol=1e-6, atol=0), vals


@pytest.mark.mpi
def test_parallel_matches_serial():
    """Film force, thinnest film and peak pressure: 2 ranks = 1 (round-off)."""
    if MPI.COMM_WORLD.size < 2:
        pytest.skip("compares COMM_WORLD with COMM_SELF: run under mpiexec -n 2")
    out = []
    for comm in (MPI.COMM_SELF, MPI.COMM_WORLD):
        bodies, film, problem, push = roller_on_block(comm, U2=400.0)
        for d in (0.0, 0.01):
            push.value[:] = [0.0, d]
            problem.solve()
        prof = film.profile(everywhere=True)
        out.append(np.r_[film.force(), prof["h"].min(), prof["p"].max()])
    # solver tolerance 1e-10 relative: the partitions differ by round-off only
    assert np.allclose(out[0], out[1], rtol=1e-6, atol=0), out

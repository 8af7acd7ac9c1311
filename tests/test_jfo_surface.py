"""Mass-conserving JFO cavitation on a lubricated surface in 3D (issue "Soft on soft", item 2).

The reference is the JFO film on a curve, which tribofx has solved and tested since the
chapter's §8 cases (``tests/test_ehl.py``): a soft layer (neo-Hookean, E = 1 MPa, ν = 0.45,
1 mm thick on a rigid base) slides at U = 50 mm/s under a rigid cylinder (R = 10 mm) set at
a gap of 5 µm, a lubricant of μ = 10 mPa·s (soft-EHL: the pressure, a few kPa, deflects
the layer by about the gap).  The same layer is modelled as a 3D slab one element wide
(0.05 mm, u_y = 0 on both faces: plane strain; its film sees no flux through the faces
because v̄ has no component across them), meshed with the same vertices, so the two films
have the same nodes along x.

Two inlets: flooded (an open end supplied with a 0.2 mm layer, more than the gap there:
the Robin leak returns the excess, :meth:`Film.add_inflow`) and starved (the inlet's void
fraction λ = 0.95: the film arrives cavitated and reforms before the contact).

Error estimate of the comparison: the reference q∞ is the 2D layer at nx = 240
elements along Γ_l (and 32 across; its own error e_ref is estimated by |q(120) − q(240)|).
The 2D layer's error at nx = 60 is then e_2D = |q_2D(60) − q∞|.  The slab's P1
tetrahedra and its surface's triangles have errors of their own, of the same order: the
slab at nx = 60 is asked to be as accurate as the layer within a factor 2,
|q_3D(60) − q∞| ≤ 2 e_2D + 3 e_ref.  (Two levels alone do not estimate these errors:
the layer's h_min converges non-monotonically, |q(60) − q(120)| = 3e-7 mm against
|q(60) − q(240)| = 8e-6 mm in the starved case.)  Front positions (the rupture, the
reformation) are nodal: equal to within one element.  The oil's books close to the
solver's tolerance: the transport rows tested by δp = 1 are the fluxes through ∂S
(:meth:`ReynoldsFilm.surface_books`), so supplied + entered = out + leak to the sum of
the converged rows (each below the stopping tolerance atol of a nodal flux).
"""

import numpy as np
import pytest
import ufl
from dolfinx import fem
from dolfinx import mesh as dmesh
from mpi4py import MPI
from tribofx.forms.hyperelastic import lame_parameters

from tribofx.body import Body
from tribofx.interfaces import JFO, Film, FilmScales, Fluid
from tribofx.obstacles import rigid_cylinder
from tribofx.problem import Problem
from tribofx.testing import block_taylor_orders, exact_tangent, oil_books

L, H, R, E, NU, MU, U, H0 = 1.5, 1.0, 10.0, 1.0, 0.45, 1e-8, 50.0, 5e-3
WIDTH = 0.05          # the slab's width (mm)
NY = 8                # elements across the layer at nx = 60 (uniform refinement)
SUPPLY = 0.2          # flooded: the open inlet's layer (mm), above the gap there (0.117)
VOID = 0.95           # starved: the inlet's void fraction


def slab(comm, dim, nx, inlet):
    """The layer (dim 2) or its slab (dim 3) under the cylinder; returns (film, problem).

    nx elements along Γ_l, nx/7.5 across the layer (8 at nx = 60).
    """
    ny = round(nx * NY / 60)
    if dim == 2:
        msh = dmesh.create_rectangle(comm, [[-L, -H], [L, 0]], [nx, ny], dmesh.CellType.triangle)
    else:
        msh = dmesh.create_box(comm, [[-L, 0, -H], [L, WIDTH, 0]], [nx, 1, ny],
                               dmesh.CellType.tetrahedron)
    z, fdim = dim - 1, dim - 1
    marks = [(1, lambda x: np.isclose(x[z], 0)), (2, lambda x: np.isclose(x[z], -H))]
    if dim == 3:
        marks.append((3, lambda x: np.isclose(x[1], 0) | np.isclose(x[1], WIDTH)))
    facets = [dmesh.locate_entities_boundary(msh, fdim, f) for _, f in marks]
    values = np.concatenate([np.full(len(f), t, np.int32) for (t, _), f in zip(marks, facets)])
    facets = np.concatenate(facets)
    order = np.argsort(facets)
    ft = dmesh.meshtags(msh, fdim, facets[order], values[order])
    lame = dict(zip(("mu", "lmbda"), lame_parameters(E, NU)))
    names = {"top": 1, "bottom": 2} | ({"side": 3} if dim == 3 else {})
    body = Body(msh, ft, names, "3d" if dim == 3 else "plane_strain", ("neo-hookean", lame),
                velocity=U * np.eye(dim)[0])
    body.add_dirichlet("bottom", np.zeros(dim))
    if dim == 3:
        body.add_dirichlet("side", 0.0, component=1)
    center = (R + H0) * np.eye(dim)[z]
    p_s = 6 * MU * U * np.sqrt(2 * R * H0) / H0**2       # the hydrodynamic pressure scale
    film = Film(body, "top", rigid_cylinder(center, R, None if dim == 2 else (0, 1, 0)),
                Fluid(MU), scales=FilmScales(pressure=p_s, film=H0, speed=U), cavitation=JFO(),
                require_open=True)
    at_inlet = lambda X: np.isclose(X[0], -L)            # noqa: E731
    if inlet == "flooded":
        film.add_inflow(lambda X: np.isclose(np.abs(X[0]), L), SUPPLY)
    else:
        film.add_inlet(at_inlet, void=VOID)
    film.jfo_initial_guess(downstream=np.eye(dim)[0])
    problem = Problem([body, film], name=f"slab{dim}", max_it=60)
    return film, problem


def _sum(film, expr):
    return film.sub.comm.allreduce(fem.assemble_scalar(fem.form(expr * film.dx)), op=MPI.SUM)


def measures(film, dim):
    """Per unit width: load (N/mm), p_max, h_min, void volume ∫λ (mm), outflow (mm²/s), fronts."""
    w = WIDTH if dim == 3 else 1.0
    prof = film.profile(everywhere=True)
    X, p, lam = prof["X"][:, 0], prof["p"], prof["lam"]
    x_peak = X[np.argmax(p)]
    dry = lam > 1e-6
    if dim == 3:
        out = film.surface_books()["out"]
    else:
        out = film.consistent_fluxes(lambda X: np.isclose(X[0], -L))[1]
    return {"W": film.force()[dim - 1] / w, "p_max": float(p.max()), "h_min": film.min_film(),
            "void": _sum(film, film.lam) / w, "out": out / w,
            "rupture": float(X[(X > x_peak) & dry].min()),
            "reformation": float(X[(X < x_peak) & ~dry].min())}


# the starved inlet (22 s of solves) runs in the slow set: the flooded one has the
# same rows, a cavity, its rupture and reformation, and the open end's supply
@pytest.fixture(scope="module", params=["flooded", pytest.param("starved", marks=pytest.mark.slow)])
def films(request):
    out = {}
    for dim, nx in ((2, 60), (2, 120), (2, 240), (3, 60)):
        film, problem = slab(MPI.COMM_WORLD, dim, nx, request.param)
        report = problem.solve()
        out[dim, nx] = (film, problem, measures(film, dim), report)
    return request.param, out


def test_slab_reproduces_the_line_film(films):
    """The 3D film on the slab's face = the film on the layer's curve, within the mesh error."""
    inlet, runs = films
    q2, q3, q_120, q_ref = (runs[k][2] for k in ((2, 60), (3, 60), (2, 120), (2, 240)))
    print(inlet, "\n 2D(60) ", q2, "\n 3D(60) ", q3, "\n 2D(120)", q_120, "\n 2D(240)", q_ref)
    for key in ("W", "p_max", "h_min", "void", "out"):
        e_2d, e_ref = abs(q2[key] - q_ref[key]), abs(q_120[key] - q_ref[key])
        e_3d = abs(q3[key] - q_ref[key])
        print(f"{key}: 3D error {e_3d:.3g}, 2D error {e_2d:.3g} (ratio {e_3d / e_2d:.2f}), "
              f"reference's {e_ref:.2g}")
        assert e_3d <= 2 * e_2d + 3 * e_ref, (key, q3[key], q2[key], q_ref[key])
    dx = 2 * L / 60
    for key in ("rupture", "reformation"):
        assert abs(q3[key] - q2[key]) <= dx * (1 + 1e-9), (key, q3[key], q2[key])
    if inlet == "starved":
        # the film arrives cavitated and reforms upstream of the pressure peak
        assert q2["reformation"] > -L + dx and q3["reformation"] > -L + dx


def test_books_close_on_the_surface(films):
    """supplied + entered = out + leak: to the sum of the converged nodal rows."""
    inlet, runs = films
    film, problem = runs[3, 60][:2]
    books, imbalance, bound = oil_books(film)
    print(inlet, books, "imbalance", imbalance, "bound", bound)
    assert books["out"] > 0 and books["supplied"] + books["entered"] > 0
    assert abs(imbalance) <= bound


@pytest.mark.mpi
def test_surface_jfo_taylor():
    """3D JFO film (u, u_s, p, g, λ): the exact tangent of every block, away from the kinks.

    State: full film (λ < 0 small, p > 0) upstream of x = 0.3, cavitated (p < 0, λ > 0)
    downstream, so that min(p/p_c, λ) and min(λ, 1) sit on smooth branches at every node
    and a perturbation of 1e-2 of the scales never crosses a kink; a supplied open inlet
    and outlet (the leak and the supply's min(v_n, 0) on their smooth branches).
    """
    film, problem = slab(MPI.COMM_WORLD, 3, 16, "flooded")
    body = film.body
    body.u.interpolate(lambda x: np.array([4e-4 * np.sin(x[0]) * (1 + x[2]),
                                           0 * x[0], -6e-4 * np.exp(-x[0] ** 2) * (1 + x[2])]))
    film.u_s.interpolate(lambda x: np.array([3e-4 * np.cos(x[0]), 0 * x[0],
                                             -5e-4 * np.exp(-x[0] ** 2)]))
    p_c = float(film.p_c.value)
    film.p.interpolate(lambda x: np.where(x[0] < 0.3, 0.5 * p_c * (1.2 - (x[0] / L) ** 2),
                                          -0.3 * p_c))
    film.lam.interpolate(lambda x: np.where(x[0] < 0.3, -0.3, 0.2 + 0.1 * np.sin(x[0])))
    film.g.x.array[:] = 0.01 * p_c
    rng = np.random.default_rng(7 + MPI.COMM_WORLD.rank)
    dirs = []
    for f, c in zip(problem.u, [1e-4, 1e-4, 1e-2 * p_c, 1e-2 * p_c, 1e-2]):
        d = fem.Function(f.function_space)
        d.x.array[:] = c * rng.uniform(-1, 1, d.x.array.shape)
        d.x.scatter_forward()
        dirs.append(d)
    for name, (orders, rem, floor) in block_taylor_orders(problem, dirs, eps0=1e-2).items():
        print("surface jfo", name, orders, rem)
        assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)


@pytest.mark.mpi
def test_slab_on_two_ranks_equals_serial():
    """The starved slab's measures on 2 ranks = on one (COMM_SELF), to 1e-8 relative.

    The solver tolerance (rtol 1e-10 of the flux scale) bounds the difference of the two
    converged states; 1e-8 leaves the round-off of the distributed sums.
    """
    comm = MPI.COMM_WORLD
    if comm.size == 1:
        pytest.skip("compares COMM_WORLD with COMM_SELF: run under mpiexec -n 2")
    res = []
    for c in (comm, MPI.COMM_SELF):
        film, problem = slab(c, 3, 30, "starved")
        problem.solve()
        res.append(measures(film, 3))
    print(res)
    for key in res[0]:
        assert abs(res[0][key] - res[1][key]) <= 1e-8 * max(abs(res[1][key]), 1e-12), key


def test_ufl_conormal_of_a_surface_is_in_its_plane():
    """∮ n·X dL = 2 × area and ∮ n_z dL = 0 on the slab's face (the divergence theorem).

    :func:`tribofx.forms.jfo.boundary_speed` takes the outward conormal n of ∂Γ_l
    (in the plane of Γ_l) from UFL's FacetNormal of the facet submesh, a manifold.
    """
    film, _ = slab(MPI.COMM_WORLD, 3, 8, "flooded")
    edges = film.boundary_facets()
    tags = dmesh.meshtags(film.sub, 1, edges, np.ones(len(edges), np.int32))
    ds = ufl.Measure("ds", film.sub, subdomain_data=tags, subdomain_id=1)
    n, X = ufl.FacetNormal(film.sub), ufl.SpatialCoordinate(film.sub)
    comm = film.sub.comm
    flux = comm.allreduce(fem.assemble_scalar(fem.form(ufl.dot(n, X) * ds)), op=MPI.SUM)
    normal = comm.allreduce(fem.assemble_scalar(fem.form(n[2] * ds)), op=MPI.SUM)
    print("closed-curve integrals", flux, normal)
    assert abs(flux - 2 * (2 * L * WIDTH)) <= 1e-12 and abs(normal) <= 1e-14

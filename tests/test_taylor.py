"""Taylor tests: every residual form against its UFL Jacobian (remainder must decay like ε²)."""

import numpy as np
import pytest
import ufl
from dolfinx import fem, mesh
from mpi4py import MPI
from tribofx.forms import hyperelastic as hf
from tribofx.meshes.obstacles import cap_surface_mesh

from tribofx.body import Body
from tribofx.interfaces import Contact
from tribofx.obstacles import rigid_cylinder, rigid_plane, rigid_sphere, rigid_surface_mesh
from tribofx.problem import Problem
from tribofx.testing import block_taylor_orders, exact_tangent, form_taylor_orders

# remainder orders of an exact Jacobian are 2 up to round-off; 1.8 leaves room for
# the ε-range where round-off starts to show (a wrong tangent gives order 1)
MIN_ORDER = 1.8


def assert_exact_jacobian(orders, rel_rem):
    # a residual that is linear in the unknowns leaves only round-off (≪ 1e-9 of
    # the linear term); otherwise the remainder must decay at second order
    assert rel_rem.max() < 1e-9 or orders.min() > MIN_ORDER, (orders, rel_rem)


def assert_exact_blocks(problem, dirs, eps0, label=""):
    """Each unknown's columns alone (:func:`tribofx.testing.block_taylor_orders`): second
    order, or a block the residual is linear in at its round-off floor."""
    for name, (orders, rem, floor) in block_taylor_orders(problem, dirs, eps0=eps0).items():
        print(label, name, orders, rem, floor)
        assert exact_tangent(orders, rem, floor), (label, name, orders, rem, floor)


def _smooth(f, scale, seed):
    rng = np.random.default_rng(seed)
    c = rng.uniform(-1, 1, (f.function_space.value_size, 3))
    f.interpolate(lambda x: scale * np.array([np.sin(ci[0] + 2 * ci[1] * x[0] + 3 * ci[2] * x[1])
                                              for ci in c]))


def _random(f, scale, seed):
    rng = np.random.default_rng(seed + MPI.COMM_WORLD.rank)
    f.x.array[:] = scale * rng.uniform(-1, 1, f.x.array.shape)
    f.x.scatter_forward()


@pytest.mark.parametrize("kind", ["3d", "plane_strain", "axisymmetric"])
@pytest.mark.parametrize("material", ["neo-hookean", "mooney-rivlin", "linear"])
def test_hyperelastic_jacobian(kind, material):
    comm = MPI.COMM_WORLD
    msh = (mesh.create_unit_cube(comm, 2, 2, 2) if kind == "3d"
           else mesh.create_rectangle(comm, [[0.5, 0], [1.5, 1]], [4, 4]))
    V = fem.functionspace(msh, ("Lagrange", 2, (msh.geometry.dim,)))
    u, du = fem.Function(V), fem.Function(V)
    _smooth(u, 0.1, 1)
    _random(du, 1.0, 2)
    params = ({"mu1": 0.6, "mu2": 0.4, "kappa": 20.0} if material == "mooney-rivlin"
              else {"mu": 1.0, "lmbda": 2.0})
    R = hf.internal_virtual_work(u, ufl.TestFunction(V), kind, material, params,
                                 ufl.Measure("dx", msh, metadata={"quadrature_degree": 4}))
    orders, rem = form_taylor_orders(R, u, du)
    print(kind, material, orders, rem)
    assert_exact_jacobian(orders, rem)


def _arc_mesh(quadratic, n=40):
    """Arc of the circle of radius 2 centred at (0.5, −1.95), counter-clockwise
    (outward normal), as interval or interval3 facets."""
    theta = np.linspace(np.pi / 3, 2 * np.pi / 3, 2 * n + 1 if quadratic else n + 1)
    nodes = np.c_[0.5 + 2 * np.cos(theta), -1.95 + 2 * np.sin(theta)]
    if quadratic:
        facets = np.c_[np.arange(0, 2 * n, 2), np.arange(2, 2 * n + 1, 2),
                       np.arange(1, 2 * n, 2)]
        return nodes, facets.astype(np.int32), "interval3"
    return nodes, np.c_[np.arange(n), np.arange(1, n + 1)].astype(np.int32), "interval"


def _cap_mesh(quadratic, n=6):
    """Cap of the sphere of radius 2 centred at (0.5, 0.5, −1.95) over [−0.3, 1.3]².

    No slave node of the box projects within 0.03 mm of a facet edge, where the
    normal of the piecewise surface jumps (a Taylor step across it would show that
    jump, not the tangent).
    """
    return cap_surface_mesh(2.0, (0.5, 0.5, -1.95), (-0.3, 1.3), n, quadratic)


def _box_problem(shape, friction, slip, gdim=2, kind=None):
    comm = MPI.COMM_WORLD
    if kind == "axisymmetric":  # ring section 0.5 ≤ R ≤ 1.5 (R > 0 for the hoop terms)
        msh = mesh.create_rectangle(comm, [[0.5, 0], [1.5, 0.5]], [6, 3])
    elif gdim == 2:
        msh = mesh.create_rectangle(comm, [[0, 0], [1, 0.5]], [6, 3])
    else:
        msh = mesh.create_box(comm, [[0, 0, 0], [1, 1, 0.5]], [3, 3, 2])
    fdim = gdim - 1
    bot = mesh.locate_entities_boundary(msh, fdim, lambda x: np.isclose(x[gdim - 1], 0))
    ft = mesh.meshtags(msh, fdim, np.sort(bot), np.full(len(bot), 1, dtype=np.int32))
    e = np.eye(gdim)[gdim - 1]

    if shape.startswith("meshed"):
        surface = _arc_mesh if gdim == 2 else _cap_mesh
        counterpart = rigid_surface_mesh(*surface(shape.endswith("quadratic")))
    elif shape == "plane":
        counterpart = rigid_plane(0.05 * e, e)
    else:  # curved countersurfaces below the body, penetrating the bottom face
        centre = 0.5 * np.ones(gdim)
        centre[-1] = -2.0 + 0.05
        if shape == "cylinder" and gdim == 3:
            counterpart = rigid_cylinder(centre, 2.0, axis=(0, 1, 0))
        elif shape == "cylinder":
            counterpart = rigid_cylinder(centre, 2.0)
        else:
            counterpart = rigid_sphere(centre, 2.0)
    V = np.zeros(gdim)
    V[1 if kind == "axisymmetric" else 0] = 1.0   # along the axis of an axisymmetric body
    # linear bulk law: the bulk residual is linear, so the remainder is that of contact alone
    kind = kind or ("3d" if gdim == 3 else "plane_strain")
    body = Body(msh, ft, {"bottom": 1}, kind, ("linear", {"mu": 1.0, "lmbda": 1.5}), velocity=V)
    contact = Contact(body, "bottom", counterpart, rho_n=10.0, friction=friction, rho_t=10.0,
                      slip=slip, V_master=np.zeros(gdim), dtau=0.3)
    return body, contact, Problem([body, contact], name="taylor_contact")


# on 2 ranks (``pytest.mark.mpi``): each projection path once — the analytic plane,
# cylinder and sphere, the meshed countersurfaces through the C++ kernel in 2D and 3D —
# with Lagrangian and Eulerian friction and the friction law; the other combinations
# repeat arithmetic that does not depend on the partition, and run serially
@pytest.mark.parametrize("shape,friction,slip,gdim", [
    ("plane", 0.0, "lagrangian", 2),
    ("plane", 0.4, "lagrangian", 2),
    pytest.param("plane", 0.4, "eulerian", 2, marks=pytest.mark.mpi),
    ("cylinder", 0.4, "lagrangian", 2),
    ("cylinder", 0.4, "eulerian", 2),
    pytest.param("sphere", 0.4, "lagrangian", 3, marks=pytest.mark.mpi),
    ("cylinder", 0.3, "eulerian", 3),
    # countersurfaces given as meshes, through the C++ kernel's derivatives:
    # curved (quadratic) and flat facets, with and without friction
    ("meshed-quadratic", 0.0, "lagrangian", 2),
    ("meshed-quadratic", 0.4, "lagrangian", 2),
    pytest.param("meshed-quadratic", 0.4, "eulerian", 2, marks=pytest.mark.mpi),
    ("meshed-affine", 0.4, "lagrangian", 2),
    ("meshed-affine", 0.4, "eulerian", 2),
    # 3D: a sphere cap of curved (quadrilateral9) and flat (quadrilateral) facets
    ("meshed-quadratic", 0.0, "lagrangian", 3),
    ("meshed-quadratic", 0.4, "lagrangian", 3),
    pytest.param("meshed-quadratic", 0.4, "eulerian", 3, marks=pytest.mark.mpi),
    pytest.param("meshed-affine", 0.4, "lagrangian", 3, marks=pytest.mark.mpi),
    # a friction law μ(p) (pressure-dependent, forms.contact) instead of Coulomb's μ
    ("cylinder", "law", "lagrangian", 2),
    pytest.param("sphere", "law", "eulerian", 3, marks=pytest.mark.mpi),
])
def test_contact_jacobian(shape, friction, slip, gdim, kind=None):
    if friction == "law":
        from tribofx.forms.contact import pressure_dependent_friction

        from tribofx.laws import Law

        friction = Law(pressure_dependent_friction, mu0=0.6, p0=0.1, n=1 / 3)
    body, contact, problem = _box_problem(shape, friction, slip, gdim, kind)
    _smooth(body.u, 0.01, 3)
    # last-step projection shifted so that the Lagrangian slip is finite and sliding
    contact.xbar_n.x.array[:] -= 0.02
    contact.lam_n.x.array[:] = -0.3
    if contact.lam_t is not None:
        _random(contact.lam_t, 0.2, 4)
    dirs = []
    for k, f in enumerate(problem.u):
        d = fem.Function(f.function_space)
        _random(d, 1.0, 10 + k)
        dirs.append(d)
    assert_exact_blocks(problem, dirs, 1e-4, (shape, friction, slip, gdim))


@pytest.mark.mpi
def test_axisymmetric_contact_jacobian():
    # axisymmetric body (2πR-weighted contact and hoop stretch) on a rigid cylinder
    # section, with Lagrangian friction
    test_contact_jacobian("cylinder", 0.4, "lagrangian", 2, kind="axisymmetric")


@pytest.mark.mpi
@pytest.mark.parametrize("cavitation,supg,viscosity,density,supply", [
    ("none", True, "constant", "incompressible", False),
    ("penalty", True, "constant", "incompressible", False),
    ("jfo", False, "constant", "incompressible", False),
    ("jfo", True, "constant", "incompressible", False),
    # the inlet as an open end supplied with lubricant (weak inflow and leak)
    ("jfo", True, "constant", "incompressible", True),
    # a pressure-dependent viscosity μ(p) in every row (Barus, Roelands; p⁺ inside)
    ("none", True, "barus", "incompressible", False),
    ("penalty", True, "roelands", "incompressible", False),
    ("jfo", True, "barus", "incompressible", False),
    # the compressible equation (Dowson–Higginson ρ(p)), with μ(p) too
    ("none", True, "constant", "dowson-higginson", False),
    ("penalty", True, "barus", "dowson-higginson", False)])
def test_rigid_film_jacobian(cavitation, supg, viscosity, density, supply):
    """RigidFilm (Reynolds between rigid surfaces, §6.6): pressure, SUPG and the
    penalty or JFO (p, λ) rows at a state away from the kinks of min(·, ·), with a
    constant or a pressure-dependent viscosity; ``supply``: the JFO inlet as an open
    end (:meth:`~tribofx.interfaces.reynolds_film.ReynoldsFilm.add_inflow`)."""
    from tribofx.cases.film_setup import rigid_film
    from tribofx.laws import named_density, named_viscosity

    R, h0 = 10.0, 1e-3
    # the state's |p| ~ scale: 200 MPa where the density's pressure dependence must show
    # ((b − 1) p/(a + p) ≈ 0.08), α p ~ 0.4 for the viscosity
    scale = 0.2 if density == "incompressible" else 200.0
    mu = named_viscosity(viscosity, 1e-9, alpha=0.4 / scale)
    film, problem = rigid_film(MPI.COMM_WORLD, -0.5, 0.5, 40, 1,
                               lambda x: h0 + x**2 / (2 * R), 500.0, mu,
                               cavitation=cavitation, supg=supg, p_c=0.1,
                               eps=1e-3 if cavitation == "penalty" else None, h_ref=h0,
                               density=named_density(density), lam_in=0.5 * supply,
                               supply=supply)
    # p, λ of both signs (both branches of min()), the Dirichlet values held: a state
    # off its conditions makes DOLFINx's lifting add J(x)(g − x) to the residual, a
    # term whose derivative is not in J
    dirs = []
    for k, f in enumerate(problem.u):
        _random(f, scale if f is film.p else 0.2, 20 + k)
        d = fem.Function(f.function_space)
        _random(d, 1.0, 30 + k)
        fixed = problem.global_rows(f)[0] < 0       # Dirichlet dofs: p = 0, λ = λ_in = 0
        f.x.array[fixed] = 0.0
        d.x.array[fixed] = 0.0
        dirs.append(d)
    assert_exact_blocks(problem, dirs, 1e-6 * scale / 0.2,
                        (cavitation, supg, viscosity, density, supply))


@pytest.mark.mpi
def test_axisymmetric_contact_with_a_node_on_the_axis():
    """A meridian section touching the axis (R = 0) pressed on a plane: the contact node
    on the axis carries its exact lumped area ∫ φ 2πR dS, so its multiplier column is
    not empty (it was: the vertex rule gave it 2π·0), the Jacobian is exact there, and
    the post-processing (hoop stretch u_R/R → ∂u_R/∂R on the axis) has no NaN."""
    comm = MPI.COMM_WORLD
    msh = mesh.create_rectangle(comm, [[0, 0], [1, 0.5]], [6, 3])
    bot = mesh.locate_entities_boundary(msh, 1, lambda x: np.isclose(x[1], 0))
    ft = mesh.meshtags(msh, 1, np.sort(bot), np.full(len(bot), 1, dtype=np.int32))
    body = Body(msh, ft, {"bottom": 1}, "axisymmetric",
                ("neo-hookean", {"mu": 1.0, "lmbda": 1.5}))
    contact = Contact(body, "bottom", rigid_plane([0.0, 0.05], [0.0, 1.0]), rho_n=10.0)
    problem = Problem([body, contact], name="taylor_axis")
    # u_R = 0 on the axis, for the state and the direction (a body of revolution)
    axis = fem.locate_dofs_geometrical(body.V, lambda x: np.isclose(x[0], 0.0))
    _smooth(body.u, 0.01, 5)
    body.u.x.array[2 * axis] = 0.0
    contact.lam_n.x.array[:] = -0.3
    on_axis = np.flatnonzero(np.isclose(contact.X_sub[:, 0], 0.0))
    on_axis = on_axis[on_axis < contact.surface.n_own]
    # the exact lumped area of the axis node: 2π ∫₀ʰ (1 − R/h) R dR = π h²/3, h = 1/6
    w = contact.surface.weight.x.array[on_axis] * (1 / 12)   # ω_k times ∫ φ_k dS = h/2
    assert np.allclose(w, np.pi * (1 / 6) ** 2 / 3, rtol=1e-12)
    b, A = problem.assemble()
    if len(on_axis):
        col = int(problem.block_start(1) + on_axis[0])
        rows = [i for i in range(*A.getOwnershipRange()) if abs(A.getValue(i, col)) > 0
                and i != col]
        assert rows, "the axis node's multiplier column is empty"
    dirs = []
    for k, f in enumerate(problem.u):
        d = fem.Function(f.function_space)
        _random(d, 1.0, 40 + k)
        if f is body.u:
            d.x.array[2 * axis] = 0.0
        dirs.append(d)
    assert_exact_blocks(problem, dirs, 1e-4, "axis")
    assert np.all(np.isfinite(contact.nodal_data()["p"]))


@pytest.mark.mpi
def test_bordered_force_control_tangent():
    # the border of the force control of wear-ball-flat (tribofx.bordered): ∂R/∂δ of
    # every row (u, λ_N, λ_T and the wear rows w, ζ of a step in progress), ∂G/∂x and
    # ∂G/∂δ of the contact force, at an iterate off the solution (flat 10 % further in)
    from tribofx.cases import wear_ball_flat
    from tribofx.params import resolve
    from tribofx.references import hertz
    from tribofx.testing import border_taylor_orders, smooth_direction

    v = resolve(wear_ball_flat.Params, {"scheme": "implicit", "T": "100", "dt": "100"})
    stepper = wear_ball_flat.build(v).stepper
    control = stepper.hold
    control.solve(guess=hertz(v.F, v.R, v.E, v.nu).delta)
    for w in stepper.wears:
        w.begin_step(50.0)
    control.parameter.set(1.1 * control.parameter.get())
    problem = stepper.problem
    # unit steps of the unknowns' scales: 1 mm of u and w, 1 GPa of the tractions;
    # ε₀ = 1e-6 keeps the active set (δ moves by 1e-6 mm, 2.5e-4 of the approach)
    dirs = [smooth_direction(f, 1.0 if "displacement" in f.name or "shape_change" in f.name
                             else 1e3, 20 + k) for k, f in enumerate(problem.u)]
    out = border_taylor_orders(control.border, dirs, eps0=1e-6)
    for key, (orders, rem) in out.items():
        print(key, orders, rem)
        # exact derivatives: second-order remainders, or round-off where the force and
        # the residual are linear in the step (the plane's gap within one active set)
        assert_exact_jacobian(orders, rem)
    for w in stepper.wears:
        w.end_step()

"""Checks of the wear groove of a rigid ball sliding on an elastic half-space (§5.3).

References: Hertz contact of a rigid sphere (initial step), the discrete area
balance of the shape update (28) with the path average (1/L) ∫ Ẇ dx, the
geometry of a groove that conforms to the ball (b² = 2 R d) and the uniform
path-integrated pressure of a groove sinking as a rigid body, quadratic
convergence of the monolithic Newton, and equilibrium of every solved state (the
vertical force of the solved contact multipliers against the prescribed bottom load).
"""

import math

import numpy as np
import pytest
import ufl
from dolfinx import fem
from mpi4py import MPI
from petsc4py import PETSc
from tribofx.meshes import halfspace as hs

from tribofx.cases.wear_groove import WearBallHalfspaceCase, hertz_sphere
from tribofx.groove_problem import GrooveProblem
from tribofx.params import resolve

CASE = WearBallHalfspaceCase
serial = pytest.mark.skipif(MPI.COMM_WORLD.size > 1, reason="serial-only case")


def _values(**over):
    v = resolve(CASE.params, {k: str(x) for k, x in over.items()})
    return CASE.resolved(v)


def _orders(res):
    r = np.asarray(res)
    r = r[r > 1e-13 * max(r)]  # below this the residual is at round-off
    lr = np.log(r)
    return (lr[2:] - lr[1:-1]) / (lr[1:-1] - lr[:-2])


def _vertical_contact_force(prob, R):
    """Vertical push (N, > 0 downwards: λ < 0, n_z < 0) of the ball on the block, solved fields.

    Computed here, not by the library: the ball is the sphere of radius R about
    (0, 0, R) (fixed; the block moves), x = X + u, n = (x − c)/|x − c|, g = |x − c| − R.
    Returns (F_λ, F_T): ∫ λ n_z dS from the solved multiplier λ and ∫ T_N n_z dS from
    the augmented traction T_N = min(λ + ρ_N g, 0), both with the nodal (vertex) rule
    of the contact terms.
    """
    x = ufl.SpatialCoordinate(prob.mesh) + prob.u
    d = x - ufl.as_vector([0.0, 0.0, R])
    r = ufl.sqrt(ufl.dot(d, d))
    nz = d[2] / r
    T = ufl.min_value(prob.lam_n + prob.settings.rho_n * (r - R), 0.0)
    return tuple(MPI.COMM_WORLD.allreduce(fem.assemble_scalar(
        fem.form(f * nz * prob.dsc, entity_maps=[prob.emap])), op=MPI.SUM)
        for f in (prob.lam_n, T))


def _check_equilibrium(prob, v, forces, r_final):
    """Vertical equilibrium of a solved state against the bottom load F/2 of the half model.

    Σ over all z rows of the momentum residual (no z Dirichlet condition) is
    ∫ P : Grad e_z (= 0) + ∫ T_N n_z dS − F/2, and the Newton iteration stopped at
    ‖b‖ = r_final, so by Cauchy–Schwarz |F_T − F/2| ≤ √n_z r_final (n_z = n_u/3
    rows).  The multiplier rows are (1/ρ_N)(λ − T_N) w, so F_λ differs from F_T
    by at most ρ_N √n_λ r_final (ρ_N = E/h = 8·10⁶ MPa/mm makes this bound loose).
    Assembly round-off: 100 ε per nodal force, n_λ nodes.
    """
    sizes = prob.global_sizes()
    F_lam, F_T = forces
    round_off = 100 * np.finfo(float).eps * sizes["l"] * 0.5 * v["F"]
    d_T = math.sqrt(sizes["u"] / 3) * r_final + round_off
    d_lam = d_T + prob.settings.rho_n * math.sqrt(sizes["l"]) * r_final
    print(f"F/2 = {0.5 * v['F']}: F_T = {F_T!r} (bound {d_T:.2e}), F_λ = {F_lam!r} "
          f"(bound {d_lam:.2e}), residual {r_final:.2e}")
    assert abs(F_T - 0.5 * v["F"]) <= d_T
    assert abs(F_lam - 0.5 * v["F"]) <= d_lam


@pytest.fixture(scope="module")
def implicit_run():
    """Default mesh (small-deformation set), initial contact and two implicit steps of 50 s."""
    if MPI.COMM_WORLD.size > 1:
        pytest.skip("serial-only case")
    v = _values()
    prob, info = CASE.build(v)
    rep0 = CASE.initial_contact(prob, info)
    init = {"extent": prob.contact_extent(), "pmax": float(prob.surface_data()["p"].max()),
            "vertical": _vertical_contact_force(prob, v["R"]), "X": prob.surface_data()["X"],
            "active": prob.surface_data()["active"], "report": rep0}
    steps = []
    for _ in range(2):
        a0 = prob.groove_area()
        reps = prob.step(50.0)
        steps.append({"dA": prob.groove_area() - a0, "rate": prob.averaged_rate_integral(),
                      "vertical": _vertical_contact_force(prob, v["R"]), "reports": reps})
    return prob, info, v, init, steps


@serial
def test_initial_step_matches_hertz(implicit_run):
    prob, info, v, init, _ = implicit_run
    a, p0 = info["a"], info["p0"]
    X, act = init["X"], init["active"]
    # the Hertz radius lies between the last active node and the first inactive one
    # on each axis (mesh-based bracket, node spacing h = 0.45 a at the contact)
    for axis in (0, 1):
        on_axis = np.abs(X[:, 1 - axis]) < 1e-12
        r = np.abs(X[on_axis, axis])
        last_active = r[act[on_axis]].max()
        first_inactive = r[~act[on_axis]].min()
        print(f"axis {axis}: last active {last_active:.4f}, first inactive "
              f"{first_inactive:.4f}, Hertz a = {a:.4f} mm")
        assert last_active <= a <= first_inactive
    # peak nodal pressure vs p0 = 3F/(2πa²): 5 % for nodal multipliers at h = 0.45 a
    # on a finite block (measured 0.45 %)
    print("p_max", init["pmax"], "p0", p0)
    assert init["pmax"] == pytest.approx(p0, rel=0.05)
    # equilibrium of the solved state: the contact carries the bottom load F/2 of
    # the half model (vertical force from the solved fields, Newton-tolerance bound)
    _check_equilibrium(prob, v, init["vertical"], init["report"].residuals[-1])


@serial
def test_groove_area_balance(implicit_run):
    _, _, v, _, steps = implicit_run
    # the groove cross-section area grows by Δt (1/L) ∫∫ k p ‖v_T‖ dA at t_{n+1}
    # (implicit): the mid-step Nanson normal makes this a discrete identity,
    # so it holds to the Newton tolerance
    for s in steps:
        print("dA", s["dA"], "Δt rate", 50.0 * s["rate"])
        assert s["dA"] > 0
        assert s["dA"] == pytest.approx(50.0 * s["rate"], rel=1e-8)
        # global Archard balance of the full groove: (2/L) ∫∫ k p ‖v_T‖ dA = k F V / L;
        # 1 % for ‖v_T‖ = |((I + Grad u) V)_T| ≠ V (surface strain ~ p/E < 1 %) and
        # |λ| ≠ its vertical component on the curved ball (measured 0.1 %)
        assert 2 * s["rate"] == pytest.approx(v["k"] * v["F"] * v["V"] / v["L"], rel=0.01)


@serial
def test_monolithic_newton_quadratic(implicit_run):
    *_, steps = implicit_run
    for s in steps:
        res = s["reports"][0].residuals
        print("residuals", ["%.2e" % x for x in res], "orders", _orders(res))
        # exact tangent of (u, λ, w₂, ζ) incl. the extrusion couplings: once the active
        # set is settled the observed order is ≈ 2 (semismooth Newton; measured 2.6–2.8);
        # the last order above the solver floor is asserted (an early ratio can be large
        # before the set settles; residuals below 1e-8 of the first are at the
        # Newton tolerance, where the ratio measures round-off)
        r = np.asarray(res)
        assert _orders(r[r > 1e-8 * r.max()])[-1] > 1.8


@serial
def test_monolithic_tangent_taylor(implicit_run):
    prob, *_ = implicit_run
    saved = prob.state()
    prob.dt = 50.0
    rng = np.random.default_rng(1)
    scale = {"u": 1e-4, "l": 10.0, "w": 1e-4, "z": 1e3}  # mm, MPa, mm, multiplier units
    blocks = ("u", "l", "w", "z")
    x0 = np.concatenate([prob.fn[b].x.array for b in blocks])
    bc = np.concatenate([prob._bc[b] for b in blocks])
    all_orders = []
    try:
        R0 = prob.residual()
        K = prob.jacobian()
        # a direction in all unknowns, and one in the cross-section shape only
        # (exercises the extrusion couplings J_{u w₃} P and Pᵀ J_{r w₃} P alone)
        for only_w in (False, True):
            d = np.concatenate([scale[b] * rng.standard_normal(len(prob.fn[b].x.array))
                                * (1.0 if (b == "w" or not only_w) else 0.0) for b in blocks])
            d[bc] = 0.0
            Kd = K.createVecLeft()
            K.mult(PETSc.Vec().createWithArray(d), Kd)
            Kd = Kd.array.copy()
            rem = []
            for eps in (1e-3, 5e-4, 2.5e-4, 1.25e-4):
                prob._set(blocks, x0 + eps * d)
                rem.append(np.linalg.norm(prob.residual() - R0 - eps * Kd))
            orders = np.log2(np.array(rem[:-1]) / np.array(rem[1:]))
            print("Taylor remainders", rem, "orders", orders)
            all_orders.append(orders)
    finally:
        prob.dt = 0.0
        prob.restore(saved)
    orders = np.concatenate(all_orders)
    # exact derivative of (u, λ, w₂, ζ) incl. J_{u w₃} P and (Δt/L) Pᵀ J_r: the
    # remainder decays like ε² (an inexact coupling block would leave order 1)
    assert np.all(orders > 1.8)


@serial
def test_worn_state_equilibrium(implicit_run):
    prob, _, v, _, steps = implicit_run
    # the coupled (u, λ, w₂, ζ) solve of each implicit step: the worn block is in
    # vertical equilibrium with the bottom load (the residual norm of the monolithic
    # Newton bounds the u rows too)
    for s in steps:
        _check_equilibrium(prob, v, s["vertical"], s["reports"][0].residuals[-1])
    # the shape unknowns (cross-section Ψ and its multiplier) are a small share
    frac = (len(prob.w2.x.array) + len(prob.zeta.x.array)) / (
        len(prob.u.x.array) + len(prob.lam_n.x.array) + len(prob.w2.x.array)
        + len(prob.zeta.x.array))
    print("fraction of Ψ unknowns", frac)
    assert frac < 0.05


@serial
def test_explicit_step_uses_the_old_rate():
    v = _values(scheme="explicit")
    prob, info = CASE.build(v)
    CASE.initial_contact(prob, info)
    rate0 = prob.averaged_rate_integral()
    a0 = prob.groove_area()
    reports = prob.step(1.0)
    # forward Euler: ΔA = Δt (1/L) ∫ Ẇ dA of the converged state at t_n (discrete identity)
    assert prob.groove_area() - a0 == pytest.approx(1.0 * rate0, rel=1e-8)
    # the contact problem was re-solved on the new shape: equilibrium with F/2 again,
    # from the solved fields (reports: shape update, then the contact solve)
    _check_equilibrium(prob, v, _vertical_contact_force(prob, v["R"]),
                       reports[-1].residuals[-1])


def _small_run(comm):
    """Initial contact and one implicit step of 50 s on a coarse block (h = 0.9 a).

    Returns (full groove area, max wear depth, worn top-line profile, contact force,
    contact extent (x, y), Newton iterations) — identical on every rank.
    """
    v = _values()
    a, _, delta = hertz_sphere(v["E"], v["nu"], v["R"], v["F"])
    h = 0.9 * a
    gx, gy, gz = hs.grids(27 * a, 27 * a, 27 * a, h, 1.8 * a, 5.4 * a, 1.8 * a, (3, 3, 4),
                          hx=h / 2)
    msh, ft = hs.halfspace_block(comm, gx, gy, gz)
    sec, sft = hs.cross_section(MPI.COMM_SELF, gy, gz)
    prob = GrooveProblem(msh, ft, sec, sft, v["E"], v["nu"], v["R"], v["F"], v["V"], v["L"],
                         v["k"], h)
    rep0 = CASE.initial_contact(prob, {"delta": delta})
    rep1 = prob.step(50.0)[0]
    lp = prob.line_profile()
    return {"area": 2 * prob.groove_area(), "depth": float(lp["depth"].max()),
            "profile": lp["worn"], "force": prob.contact_force(),
            "extent": np.array(prob.contact_extent()),
            "iterations": (rep0.iterations, rep1.iterations),
            "owned_u": prob.comm.allgather(prob._nown["u"])}


@pytest.mark.mpi
def test_two_ranks_match_serial():
    if MPI.COMM_WORLD.size != 2:
        pytest.skip("needs mpiexec -n 2")
    par = _small_run(MPI.COMM_WORLD)
    # the block is really distributed, the cross-section unknowns sit on rank 0
    assert min(par["owned_u"]) > 0
    # reference: the same problem on one process (rank 0, COMM_SELF)
    ref = _small_run(MPI.COMM_SELF) if MPI.COMM_WORLD.rank == 0 else None
    ref = MPI.COMM_WORLD.bcast(ref, root=0)
    print("2 ranks", par["area"], par["depth"], "serial", ref["area"], ref["depth"])
    assert par["area"] > 0 and par["depth"] > 0  # the step did wear the surface
    # same discrete problem, different partition: both Newton solves stop at
    # |R| <= 1e-9 |R0|, and the monolithic MUMPS solves differ only by round-off,
    # so 1e-7 relative (measured agreement ~1e-12)
    for key in ("area", "depth", "force"):
        assert par[key] == pytest.approx(ref[key], rel=1e-7)
    scale = np.abs(ref["profile"][:, 1]).max()
    assert np.abs(par["profile"] - ref["profile"]).max() < 1e-7 * scale
    assert np.allclose(par["extent"], ref["extent"], rtol=0, atol=1e-12)  # same active nodes
    assert par["iterations"] == ref["iterations"]


def test_hertz_reference():
    a, p0, delta = hertz_sphere(2e5, 0.3, 5.0, 10.0)
    # closed form, Johnson (1985) eqs. 4.22-4.23 with a rigid ball: F = 4 E* a³ / (3R)
    Es = 2e5 / (1 - 0.09)
    assert 4 * Es * a**3 / (3 * 5.0) == pytest.approx(10.0, rel=1e-12)
    assert p0 * 2 * math.pi * a * a / 3 == pytest.approx(10.0, rel=1e-12)
    assert delta == pytest.approx(a * a / 5.0)
    # independent numbers: the chapter's §5.2 data (R = 5 mm, E = 100 GPa, ν = 0.3,
    # F = 100 N) give a = 0.15 mm and p0 = 2.1 GPa (quoted to two digits there)
    a, p0, _ = hertz_sphere(1e5, 0.3, 5.0, 100.0)
    assert a == pytest.approx(0.15, abs=0.005)
    assert p0 == pytest.approx(2100.0, abs=50.0)


def _long(graded):
    """Implicit run to T = 1000 s with Δt = 100 s (the case default)."""
    v = _values(graded=str(graded), T=1000, dt=100)
    prob, info = CASE.build(v)
    CASE.initial_contact(prob, info)
    for _ in range(10):
        prob.step(100.0)
    return prob, v


@pytest.fixture(scope="module")
def long_homogeneous():
    """Homogeneous half-space to T = 1000 s (shared by the slow tests)."""
    if MPI.COMM_WORLD.size > 1:
        pytest.skip("serial-only case")
    return _long(False)


@serial
@pytest.mark.slow
def test_long_time_groove_follows_the_ball(long_homogeneous):
    prob, v = long_homogeneous
    A = 2 * prob.groove_area()
    d = float(prob.line_profile()["depth"].max())
    b = 3 * A / (4 * d)  # half-width of the parabolic groove z = y²/2R − d of area A = 4bd/3
    print("A", A, "d", d, "b", b, "sqrt(2Rd)", math.sqrt(2 * v["R"] * d))
    # a groove shaped by the rigid ball: b² = 2 R d; 15 % for the elastic edge
    # rounding and the 0.025 mm mesh across a 0.23 mm half-width
    assert b**2 == pytest.approx(2 * v["R"] * d, rel=0.15)
    y, pint = prob.averaged_pressure()
    inner = y < 0.6 * b
    ratio = pint[inner] / pint[0]
    print("∫p dx across the groove / centre", ratio)
    # rigid sinking of a conforming groove: uniform depth rate, i.e. uniform
    # (1/L) ∫ k p dx across it, away from the edges (Fig. 10a); 10 % for the mesh
    assert np.all(np.abs(ratio - 1) < 0.10)


@serial
@pytest.mark.slow
def test_graded_layer_shifts_pressure_to_the_centre(long_homogeneous):
    """FGM layer (Fig. 10b): k and E rise towards the surface, so the groove edges
    (shallow, high k) need less pressure for the common sinking rate.

    Reference: quasi-steady rigid sinking of a conforming groove makes the depth
    rate (1/L) ∫ k p dx uniform across it, i.e. k(d(y)) ∫ p dx = const, with
    k(d) = k_s (1 + α max(1 − d/h_L, 0)) and d(y) the local groove depth.
    """
    out = {}
    for graded in (False, True):
        prob, v = _long(True) if graded else long_homogeneous
        A = 2 * prob.groove_area()
        lp = prob.line_profile()
        d = float(lp["depth"].max())
        b = 3 * A / (4 * d)
        y, pint = prob.averaged_pressure()
        depth = np.interp(y, lp["worn"][:, 0], lp["depth"])
        kf = 1 + v["grade_alpha"] * np.maximum(1 - depth / v["grade_depth"], 0) * graded
        inner = y < 0.8 * b
        uniform = kf[inner] * pint[inner] / (kf[0] * pint[0])
        edge = np.interp(0.8 * b, y, pint) / pint[0]
        print("graded" if graded else "homogeneous", "b", b, "k∫p dx / centre", uniform,
              "∫p dx(0.8 b)/centre", edge)
        # 3 % for the mesh (h = 0.025 mm across a 0.23-0.27 mm half-width; measured < 1 %)
        assert np.all(np.abs(uniform - 1) < 0.03)
        out[graded] = edge
    # homogeneous: ∫ p dx flat to the edge (measured 0.98 at 0.8 b); graded: it falls
    # towards the edges by about the edge/centre ratio of k (measured 0.77)
    assert out[True] < out[False] - 0.1

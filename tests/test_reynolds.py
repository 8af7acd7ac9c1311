"""Reynolds equation (chapter §6): inclined slider and cylinder against analytic solutions,
JFO mass conservation, SUPG in the cavitated zone, Newton rate, serial = parallel."""

import math

import numpy as np
import pytest
from mpi4py import MPI

from tribofx.cases import reynolds_cylinder, reynolds_slider
from tribofx.cases.reynolds_cylinder import cylinder_references
from tribofx.output import RunRecord
from tribofx.params import InputError, resolve
from tribofx.problem import NewtonDivergence, convergence_orders


def run_case(case, tmp_path, **overrides):
    values = resolve(case.Params, {k: str(v) for k, v in overrides.items()})
    case.validate(values)
    rec = RunRecord(case.name, values, None, tmp_path,
                    MPI.COMM_WORLD)
    rec.profile = None
    prob = case.run(values, rec)
    return {k: v["value"] for k, v in rec.data["results"].items()}, rec, prob


# ----------------------------------------------------------------------------- slider


@pytest.mark.mpi
def test_slider_matches_analytic(tmp_path):
    res, rec, _ = run_case(reynolds_slider, tmp_path)
    print(res)
    # default P1 mesh of 200 elements: discretisation error O(h²) ≈ 1e-4; 0.5 % required
    assert abs(res["load_rel_error"]) < 5e-3
    assert abs(res["p_max_rel_error"]) < 5e-3
    # the analytic values themselves: W = 6μUL²/(K²h0²)(ln(1+K) − 2K/(2+K)),
    # p_max = 3μULK/(2h0²(1+K)(2+K)); for the defaults p_max = 2.5 MPa exactly
    assert res["analytic_p_max"] == pytest.approx(2.5, rel=1e-12)
    assert res["analytic_load_per_width"] == pytest.approx(600 * (math.log(2) - 2 / 3),
                                                           rel=1e-12)
    # linear problem: one Newton step solves it (residual then at round-off)
    assert rec.data["newton_iterations"] == [[1]]


@pytest.mark.mpi
@pytest.mark.parametrize("n", [20, 200])
def test_slider_peak_position_sub_element(tmp_path, n):
    """x_p_max by the parabolic vertex (tribofx.positions) against x = L(1+K)/(2+K).

    Error bound of the vertex through three nodes of spacing h: h² max|p'''|/(3|p''|)
    from the parabola, plus 2ε/(|p''| h) from nodal errors ε of the FE solution
    (ε measured against the analytic p at the nodes, an independent reference);
    the derivatives are those of the analytic p near the peak (central
    differences).  The node itself is off by up to h/2.
    """
    from tribofx.references import slider_pressure

    res, rec, _ = run_case(reynolds_slider, tmp_path, mesh=n)
    v = rec.data["parameters"]
    K, L, h0, U, mu = (v[k]["value"] for k in ("K", "L", "h0", "U", "mu"))
    xm = res["analytic_x_p_max"]
    h = L / n
    d = 1e-3 * L

    def p(x):
        return slider_pressure(np.asarray(x, dtype=float), K, L, h0, U, mu)

    xs = xm + np.linspace(-h, h, 5)
    p2 = np.abs((p(xs + d) - 2 * p(xs) + p(xs - d)) / d**2).min()
    p3 = np.abs((p(xs + 2 * d) - 2 * p(xs + d) + 2 * p(xs - d) - p(xs - 2 * d))
                / (2 * d**3)).max()
    prof = rec.profile             # on rank 0
    eps = float(np.max(np.abs(prof["p"] - p(prof["x"])))) if prof is not None else None
    eps = MPI.COMM_WORLD.bcast(eps, root=0)
    bound = h**2 * p3 / (3 * p2) + 2 * eps / (p2 * h)
    err = abs(res["x_p_max"] - xm)
    print(f"n = {n}: |x_p_max - x*| = {err:.2e} <= {bound:.2e} (h/2 = {h / 2:.2e})")
    assert err <= bound
    assert bound < 0.5 * h


@pytest.mark.mpi
@pytest.mark.parametrize("degree,rate", [(1, 2.0), (2, 3.0)])
def test_slider_mesh_convergence(tmp_path, degree, rate):
    # smooth solution: L2 error of Lagrange degree k converges as O(h^(k+1))
    errs, loads = [], []
    meshes = (8, 16, 32, 64)
    for n in meshes:
        res, _, _ = run_case(reynolds_slider, tmp_path, mesh=n, degree=degree, K=2.0)
        errs.append(res["pressure_l2_error"])
        loads.append(abs(res["load_rel_error"]))
    rates = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    print("degree", degree, "L2 errors", errs, "rates", rates, "load errors", loads)
    # asymptotic range reached from 16 elements on: within 0.1 of the theoretical rate
    assert np.all(rates[1:] > rate - 0.1)
    assert loads[-1] < loads[0]


def test_slider_bad_input():
    for key, text in (("h0", "0"), ("mu", "-1"), ("K", "-1"), ("K", "-2"), ("degree", "3")):
        with pytest.raises(InputError):
            resolve(reynolds_slider.Params, {key: text})


# ----------------------------------------------------------------------------- cylinder


def test_film_options_are_refused_where_they_are_built():
    """A penalty without a positive ε, a cavitation model given by name and a bare
    viscosity in place of a Fluid are each refused in one line where they are built."""
    from dolfinx import mesh

    from tribofx.interfaces import Fluid, Penalty, RigidFilm

    with pytest.raises(ValueError, match="must be > 0"):
        Penalty(0.0)
    msh = mesh.create_interval(MPI.COMM_WORLD, 8, [0.0, 1.0])
    with pytest.raises(TypeError, match="Penalty"):
        RigidFilm(msh, lambda x: 0.01 + 0.0 * x, 1.0, Fluid(1e-8), cavitation="penalty")
    with pytest.raises(TypeError, match="Fluid"):
        RigidFilm(msh, lambda x: 0.01 + 0.0 * x, 1.0, 1e-8)


def test_cylinder_references_against_closed_form():
    # Independent check of the NumPy-quadrature references: with x = ℓ tan φ,
    # ℓ = √(2Rh0), ∫dx/h² = (ℓ/h0²)∫cos²φ dφ and ∫dx/h³ = (ℓ/h0³)∫cos⁴φ dφ in closed form.
    R, h0, um, mu, x_in, x_out = 10.0, 0.01, 1000.0, 1e-7, -2.0, 2.0
    ell = math.sqrt(2 * R * h0)

    def c2(f):
        return f / 2 + math.sin(2 * f) / 4

    def c4(f):
        return 3 * f / 8 + math.sin(2 * f) / 4 + math.sin(4 * f) / 32

    fi, fo = math.atan(x_in / ell), math.atan(x_out / ell)
    hs_sommerfeld = h0 * (c2(fo) - c2(fi)) / (c4(fo) - c4(fi))

    # Swift–Stieber: cos²φ_r (c2(φ_r) − c2(φ_i)) = c4(φ_r) − c4(φ_i), bisection
    a, b = 0.0, fo
    for _ in range(100):
        m = 0.5 * (a + b)
        g = (c2(m) - c2(fi)) - (c4(m) - c4(fi)) / math.cos(m) ** 2
        a, b = (m, b) if g > 0 else (a, m)
    xr = ell * math.tan(0.5 * (a + b))
    refs = cylinder_references(R, h0, um, mu, x_in, x_out)
    # quadrature on 2·10⁵ intervals: relative errors ≲ 1e-8
    assert refs["half_sommerfeld"]["h_star"] == pytest.approx(hs_sommerfeld, rel=1e-8)
    assert refs["swift_stieber"]["x_rupture"] == pytest.approx(xr, rel=1e-7)
    assert refs["swift_stieber"]["h_star"] == pytest.approx(h0 + xr**2 / (2 * R), rel=1e-8)


def test_cylinder_bad_input():
    for over in ({"x_in": "1.0", "x_out": "0.5"}, {"h0": "0"}, {"mu": "0"},
                 {"cavitation": "jfo", "degree": "2"}, {"cavitation": "penalty",
                                                        "inlet_void": "0.5"},
                 {"cavitation": "jfo", "x_out": "0.1"}):
        with pytest.raises(InputError):
            v = resolve(reynolds_cylinder.Params, over)
            reynolds_cylinder.validate(v)


@pytest.mark.mpi
def test_cylinder_half_sommerfeld_and_penalty(tmp_path):
    none, _, _ = run_case(reynolds_cylinder, tmp_path, cavitation="none")
    pen, rec, _ = run_case(reynolds_cylinder, tmp_path, cavitation="penalty")
    print("none", none)
    print("penalty", pen, rec.data["newton_iterations"])
    # Sommerfeld solution with the negative part cut off (Gümbel): 1 % of half-Sommerfeld
    assert abs(none["load_per_length"] / none["half_sommerfeld_load_per_length"] - 1) < 0.01
    assert abs(none["p_max_rel_error"]) < 0.01
    # penalty p ≥ 0 is the variational inequality: its free boundary satisfies the
    # Swift–Stieber conditions p = p' = 0, so it matches Swift–Stieber (1 %) …
    assert abs(pen["load_per_length"] / pen["swift_stieber_load_per_length"] - 1) < 0.01
    assert abs(pen["p_max_rel_error"]) < 0.01
    # … with negative pressures of relative size ~ penalty (1e-6) times O(10)
    assert pen["p_min"] > -1e-4 * pen["p_max"]
    # rupture point, sub-element estimate (√p fitted over three nodes and extrapolated
    # over ≤ 2Δx, Δx = 0.01 mm): O(Δx²/ℓ) with ℓ = √(2Rh₀) = 0.45 mm, i.e. ~0.1 % of
    # x_r; 1 % (the node alone is off by up to one element, 5 %)
    assert abs(pen["x_rupture"] / pen["swift_stieber_x_rupture"] - 1) < 0.01
    # … but it is not mass conserving: the penalty creates the fluid that the
    # widening gap carries out (outflow ≈ h(x_out) u_m, inflow ≈ h* u_m)
    assert pen["mass_balance_rel_defect"] > 10


@pytest.mark.mpi
def test_cylinder_jfo_swift_stieber_and_mass_balance(tmp_path):
    res, rec, _ = run_case(reynolds_cylinder, tmp_path, cavitation="jfo")
    print(res, rec.data["newton_iterations"])
    # flooded JFO with rupture only = Reynolds (Swift–Stieber) conditions: 1 %
    assert abs(res["load_per_length"] / res["swift_stieber_load_per_length"] - 1) < 0.01
    assert abs(res["p_max_rel_error"]) < 0.01
    assert abs(res["x_rupture"] / res["swift_stieber_x_rupture"] - 1) < 0.01  # sub-element
    # discrete mass conservation: consistent inflow = outflow to solver tolerance
    assert abs(res["flux_in"] - res["flux_out"]) < 1e-9 * abs(res["flux_in"])
    # and both equal h(x_r) u_m of Swift–Stieber to discretisation accuracy (0.1 %)
    assert res["flux_out"] == pytest.approx(res["swift_stieber_flux"], rel=1e-3)


@pytest.mark.mpi
def test_jfo_newton_rate(tmp_path):
    res, rec, _ = run_case(reynolds_cylinder, tmp_path, cavitation="jfo", mesh=800)
    its = rec.data["newton_iterations"][0]
    orders = convergence_orders(rec.data["newton_residuals"])
    print("iterations per mesh level", its, "residuals", rec.data["newton_residuals"],
          "orders", orders)
    # nested iteration: every level converges in a few semismooth Newton steps
    assert max(its) <= 10
    # once the active set is fixed the iteration is Newton's on a smooth problem:
    # the last observed order is (at least) quadratic up to noise
    assert orders[-1] > 1.7


LAM_IN = 0.945  # starved inlet: supplied film (1 − 0.945) h(x_in) = 11.55 µm
DELTA = 1e-6    # δ of the full-film fraction s in the SUPG diffusivity (forms.reynolds default)


def _advection_zone_bound(prof, v, q_in, q_out, r_final):
    """Nodes of the cavitated zones and the bound on |(1 − λ_a) h_a − h*| there (rank 0).

    In a cavitated zone p = 0 (complementarity), the JFO equation is pure advection
    of f = (1 − λ) h, exact solution f = h* (the supplied film), i.e. λ = 1 − h*/h.
    Row a of the SUPG system, with κ = τ v̄/h_e (v̄ the speed), reads A_R = A_L for
    the element quantities A_e = avg_e f − ∫_e f' κ dx (a numerical flux).  With
    κ = ½ − ω, 0 ≤ ω = (1 − 2τ v̄/h_e)/2 ≤ ½ (ω → 0 for pure advection, D → 0), and
    the trapezoid defect e_e = avg_e f − (f_a + f_b)/2 = −(h_e²/12) f''(ξ):

        A_e = f_a + e_e + ∫_e f' ω dx.

    A_1 = q_in/v̄ (inlet row; f_0 = h* by the inlet condition), A_N = q_out/v̄
    (outlet row), and the rows in between are Newton residuals, Σ|b|/v̄ ≤ √N ‖b‖/v̄.
    So at a node a whose chain of rows to the inlet (or outlet) has p = 0:

        |f_a − h*| ≤ E_1 + W_1 + E_e + W_e (+ |q_out − q_in|/v̄ downstream) + √N ‖b‖/v̄,

    E_e = (h_e²/12) max_e |f_h''| (f_h = θ_h h, θ_h = 1 − λ_h linear on the element,
    f_h'' = θ_h h'' + 2 θ_h' h' linear, so its max is at a node) and
    W_e = ω_e h_e max_e |f_h'|, ω_e from D ≤ s h² p_c/(12μ), s ≤ δ/(λ_min + 2δ)
    (p = 0), τ = h_e/√(4v̄² + (12D/h_e)²).  An O(h_e²) bound with no free constant.
    """
    R, h0, um, mu = v.R, v.h0, v.um, v.mu
    _, p_c, _ = reynolds_cylinder.scales(v)
    x, lam, p = prof["x"], prof["lam"], prof["p"]
    h = h0 + x**2 / (2 * R)
    hp = x / R
    hs = (1 - LAM_IN) * (h0 + v.x_in ** 2 / (2 * R))
    f = (1 - lam) * h
    he = np.diff(x)
    th = 1 - lam
    dth = np.diff(th) / he
    fpp = np.maximum(np.abs(th[:-1] / R + 2 * dth * hp[:-1]), np.abs(th[1:] / R + 2 * dth * hp[1:]))
    E = he**2 / 12 * fpp
    hmax = np.maximum(h[:-1], h[1:])
    fp = np.abs(dth) * hmax + np.maximum(th[:-1], th[1:]) * np.maximum(np.abs(hp[:-1]),
                                                                        np.abs(hp[1:]))
    lmin = np.maximum(np.minimum(lam[:-1], lam[1:]), 0.0)
    D = DELTA / (lmin + 2 * DELTA) * hmax**2 * p_c / (12 * mu)
    omega = 0.5 * (1 - 1 / np.sqrt(1 + (6 * D / (um * he)) ** 2))
    W = omega * he * fp
    newton = math.sqrt(len(x)) * r_final / um
    dry = np.abs(p) <= 1e-12 * p.max()     # p = 0: pure advection
    cav = dry & (lam > 1e-12)
    n = len(x)
    # inlet zone: nodes a with p = 0 on nodes 0..a+1 and λ > 0 on a, a+1
    first_wet = int(np.argmin(dry))
    inlet = [a for a in range(1, first_wet - 1) if cav[a] and cav[a + 1]]
    # outlet zone: p = 0 on nodes a..N, λ > 0 on a, a+1
    last_wet = n - 1 - int(np.argmin(dry[::-1]))
    outlet = [a for a in range(last_wet + 1, n - 1) if cav[a] and cav[a + 1]]
    nodes = np.array(inlet + outlet)
    e = nodes  # element (a, a+1)
    bound = E[0] + W[0] + E[e] + W[e] + newton
    bound[len(inlet):] += abs(q_out - q_in) / um
    err = np.abs(f[nodes] - hs)
    pe = um * he[e] / (2 * D[e])
    return nodes, err, bound, h[nodes], pe, hs


def _run_starved(tmp_path, mesh, supg):
    return run_case(reynolds_cylinder, tmp_path, cavitation="jfo", inlet_void=LAM_IN, mesh=mesh,
                    supg=supg)


@pytest.mark.mpi
def test_supg_removes_oscillations_starved_inlet(tmp_path):
    # Starved inlet: the inlet zone is cavitated (p = 0), where λ is transported by the
    # Couette flow — pure advection, the element Péclet number there is ≫ 1 (D → 0) —
    # and jumps to 0 at the reformation point.  Exact λ = 1 − h*/h in both cavitated
    # zones: monotone decrease from λ_in, jump to 0, monotone increase after rupture.
    # Coarse mesh: 100 elements (Δx = 0.04 mm), nested iteration 50 → 100.
    res, rec, _ = _run_starved(tmp_path, 100, True)
    v = resolve(reynolds_cylinder.Params, {"inlet_void": str(LAM_IN), "cavitation": "jfo",
                                      "mesh": "100"})
    dx = (v.x_out - v.x_in) / 100
    r_final = rec.data["newton_residuals"][-1]
    print("SUPG:", rec.data["newton_iterations"], res["load_rel_error"], res["x_reformation"],
          res["swift_stieber_x_reformation"])
    if MPI.COMM_WORLD.rank == 0:
        lam = rec.profile["lam"]
        nodes, err, bound, h, pe, hs = _advection_zone_bound(
            rec.profile, v, res["flux_in"], res["flux_out"], r_final)
        print(f"SUPG: {len(nodes)} advection nodes, element Péclet ≥ {pe.min():.3g}; "
              f"max |f − h*|/bound = {np.max(err / bound):.3f}; max λ error "
              f"{np.max(err / h):.2e} (bound {np.max(bound / h):.2e})")
        # a real advection zone at element Péclet numbers > 1, where the central (Galerkin)
        # scheme oscillates
        assert len(nodes) > 20 and pe.min() > 1
        # (1) λ = 1 − h*/h at every advection node within the O(Δx²) bound above
        assert np.all(err <= bound)
        # (2) no over/undershoot and monotone pieces: λ_h decreases to the first full
        # node, is 0 in the full film, increases after it (round-off 1e-12)
        full = np.nonzero(lam <= 1e-12)[0]
        i0, i1 = full[0], full[-1]
        assert lam.min() > -1e-12 and lam.max() < LAM_IN + 1e-12
        assert np.all(np.diff(lam[: i0 + 1]) <= 1e-12)
        assert np.all(np.diff(lam[i1:]) >= -1e-12)
        assert np.all(np.abs(lam[i0:i1 + 1]) <= 1e-12)
    # reformation node within one element of Swift–Stieber (the nodal λ marks the
    # full film at the first node past the jump)
    assert abs(res["x_reformation"] - res["swift_stieber_x_reformation"]) <= dx
    # mass conserved: q_out − q_in is the sum of the interior rows, ≤ √N ‖b‖
    assert abs(res["flux_out"] - res["flux_in"]) <= math.sqrt(101) * r_final + 1e-14
    # load: P1 with both free boundaries inside elements is O(Δx²); Δx = 0.04 → 0.01
    # (factor 4) must show order 2 — ±0.5 allows the sub-element position of the
    # reformation and rupture points (the constant of Δx²) to differ by a factor 2
    # between the two meshes (measured 1.5 % and 0.10 %, order 1.96)
    fine, _, _ = _run_starved(tmp_path, 400, True)
    order = math.log(abs(res["load_rel_error"]) / abs(fine["load_rel_error"])) / math.log(4)
    print("load errors", res["load_rel_error"], fine["load_rel_error"], "order", order)
    assert abs(order - 2) < 0.5
    # plain Galerkin: the central (odd–even decoupled) scheme of the advective zone has
    # no non-oscillating discrete solution.  Either outcome is asserted explicitly:
    # the semismooth Newton iteration finds no solution (observed), or the solution it
    # finds is non-monotone in a cavitated zone by more than the SUPG error bound.
    try:
        _, grec, _ = _run_starved(tmp_path, 100, False)
        galerkin = "converged"
    except NewtonDivergence as err:
        galerkin = f"diverged: {err}"[:120]
    print("Galerkin:", galerkin)
    if galerkin == "converged":
        if MPI.COMM_WORLD.rank == 0:
            lam_g = grec.profile["lam"]
            full = np.nonzero(lam_g <= 1e-12)[0]
            i0, i1 = (full[0], full[-1]) if len(full) else (len(lam_g) - 1, len(lam_g) - 1)
            wrong = max(np.max(np.diff(lam_g[: i0 + 1]), initial=0.0),
                        np.max(-np.diff(lam_g[i1:]), initial=0.0))
            print("Galerkin: largest wrong-sign increment of λ", wrong)
            assert wrong > np.max(bound / h)
    else:
        assert galerkin.startswith("diverged: Newton did not converge")


@pytest.mark.mpi
def test_serial_and_parallel_agree():
    if MPI.COMM_WORLD.size < 2:
        pytest.skip("compares COMM_WORLD with COMM_SELF: run under mpiexec -n 2")
    # the same problem on COMM_WORLD and, on every rank, on COMM_SELF
    out = {}
    for name, comm in (("world", MPI.COMM_WORLD), ("self", MPI.COMM_SELF)):
        v = resolve(reynolds_cylinder.Params, {"cavitation": "jfo", "mesh": "200"})
        prev = None
        for n in reynolds_cylinder.mesh_levels(v.mesh):
            film, problem = reynolds_cylinder.build(v.replace(mesh=n), comm=comm)
            if prev is not None:
                film.set_from_profile(prev)
            problem.solve()
            prev = comm.bcast(film.profile(), root=0)
        out[name] = (film.integral(film.p), film.consistent_fluxes(), prev["p"].max())
    print(out)
    # identical discrete problem: agreement to the Newton tolerance
    assert out["world"][0] == pytest.approx(out["self"][0], rel=1e-9)
    assert out["world"][1][1] == pytest.approx(out["self"][1][1], rel=1e-9)
    assert out["world"][2] == pytest.approx(out["self"][2], rel=1e-9)


def test_barus_slider_converges_to_the_exact_transform(tmp_path):
    """Rigid slider with Barus viscosity μ₀ e^{αp} at α p_iso,max = 0.6: the exact
    pressure is p = −ln(1 − α p_iso)/α (references.barus_pressure; the reduced pressure
    solves the isoviscous equation).  P1 converges at second order in L2 for this
    smooth solution: the observed orders against the exact p must be nearer 2 than 1
    (a discrete solution converging to another limit would plateau), and the peak
    follows the transform of the isoviscous one (≈ 0.92/α, 1.53 × p_iso,max)."""
    from tribofx.references import slider_reference
    from tribofx.runner import run_case

    p_iso = slider_reference(1.0, 10.0, 0.01, 1000.0, 1e-7)["p_max"]   # the defaults
    alpha = 0.6 / p_iso
    errs = []
    for n in (25, 50, 100):
        s = run_case("reynolds-slider", {"viscosity": "barus", "alpha_p": str(alpha),
                                         "mesh": str(n)}, tmp_path / str(n), progress=False)
        r = {k: v["value"] for k, v in s["results"].items()}
        errs.append(r["pressure_rel_l2_error"])
        print(n, r["p_max"], r["analytic_p_max"], r["pressure_rel_l2_error"])
    assert r["analytic_p_max"] == pytest.approx(-math.log(1 - 0.6) / alpha, rel=1e-12)
    orders = [math.log2(a / b) for a, b in zip(errs[:-1], errs[1:])]
    print("orders", orders)
    assert min(orders) > 1.5


def _compressible_mms_error(n, degree=1):
    """L2 error of the compressible Reynolds forms (Dowson–Higginson) against p_m."""
    import dolfinx.fem.petsc as fp
    import ufl
    from dolfinx import fem, mesh
    from tribofx.forms import fluid
    from tribofx.forms import reynolds as rf

    L, h0, K, mu, ub, P = 10.0, 0.01, 1.0, 1e-7, 500.0, 800.0
    msh = mesh.create_interval(MPI.COMM_WORLD, n, [0.0, L])
    V = fem.functionspace(msh, ("Lagrange", degree))
    x = ufl.SpatialCoordinate(msh)[0]
    h = h0 * (1 + K - K * x / L)
    vbar = ufl.as_vector([ub])
    p_m = P * ufl.sin(ufl.pi * x / L) ** 2          # p = 0 at both ends, up to 800 MPa
    rho = fluid.dowson_higginson_density
    q_m = rf.reynolds_flux(p_m, h, vbar, mu, ufl.grad, rho(p_m))
    p, dp = fem.Function(V), ufl.TestFunction(V)
    dx = ufl.Measure("dx", msh, metadata={"quadrature_degree": 8})
    # weak form −∫ q(p)·∇δp = ∫ div q(p) δp, with the source div q(p_m)
    F = rf.reynolds_residual(p, dp, h, vbar, mu, dx, rho=rho(p)) - ufl.div(q_m) * dp * dx
    ends = mesh.locate_entities_boundary(msh, 0, lambda y: np.isclose(y[0], 0) | np.isclose(
        y[0], L))
    bc = fem.dirichletbc(0.0, fem.locate_dofs_topological(V, 0, ends), V)
    problem = fp.NonlinearProblem(F, p, bcs=[bc], petsc_options_prefix=f"mms{n}_",
                                  petsc_options={"snes_rtol": 1e-12, "snes_atol": 1e-12,
                                                 "ksp_type": "preonly", "pc_type": "lu"})
    problem.solve()
    assert problem.solver.getConvergedReason() > 0
    err = fem.assemble_scalar(fem.form((p - p_m) ** 2 * dx))
    nrm = fem.assemble_scalar(fem.form(p_m ** 2 * dx))
    return math.sqrt(MPI.COMM_WORLD.allreduce(err, op=MPI.SUM)
                     / MPI.COMM_WORLD.allreduce(nrm, op=MPI.SUM))


@pytest.mark.mpi
def test_compressible_reynolds_manufactured_solution():
    """The compressible Reynolds equation div(ρ h³/(12μ) ∇p) = div(ρ h v̄) with the
    Dowson–Higginson density (ρ/ρ₀ from 1 to 1.16 over 0–800 MPa): a manufactured
    p_m = P sin²(πx/L) (the source from p_m) is recovered at the optimal L² rates of
    P1 and P2 (2 and 3; asserted nearer them than the next lower integer)."""
    for degree, expected in ((1, 2), (2, 3)):
        errs = [_compressible_mms_error(n, degree) for n in (16, 32, 64)]
        orders = [math.log2(a / b) for a, b in zip(errs[:-1], errs[1:])]
        print("P", degree, errs, orders)
        assert min(orders) > expected - 0.5, (degree, orders)


def test_dowson_higginson_slider_incompressible_limit(tmp_path):
    """At the slider's 2.5 MPa the Dowson–Higginson density differs from 1 by at most
    (b − 1) p_max/(a + p_max) = 1.4e-3: the compressible pressure is that of the
    incompressible (analytic) slider to this relative order, and not equal to it."""
    from tribofx.runner import run_case

    s0 = run_case("reynolds-slider", {}, tmp_path / "inc", progress=False)
    s1 = run_case("reynolds-slider", {"density": "dowson-higginson"}, tmp_path / "dh",
                  progress=False)
    p0, p1 = s0["results"]["p_max"]["value"], s1["results"]["p_max"]["value"]
    bound = 0.34 * p0 / (590.0 + p0)
    print("p_max incompressible", p0, "Dowson-Higginson", p1, "rel", p1 / p0 - 1, "bound", bound)
    assert 0 < abs(p1 / p0 - 1) < bound


def test_law_parameters_are_state():
    """A law's parameters are Constants in the film's state: restore() resets a changed
    α (a continuation may drive it; a failed step must not keep it), and the pressure
    follows the law the Constant holds (solved again: the Barus slider's peak)."""
    from tribofx.cases.film_setup import rigid_film
    from tribofx.laws import named_viscosity
    from tribofx.references import barus_pressure, slider_reference

    K, L, h0, U, mu = 1.0, 10.0, 0.01, 1000.0, 1e-7
    p_iso = slider_reference(K, L, h0, U, mu)["p_max"]
    film, problem = rigid_film(MPI.COMM_WORLD, 0.0, L, 200, 1,
                               lambda x: h0 * (1 + K - K * x / L), 0.5 * U,
                               named_viscosity("barus", mu, alpha=0.1), h_ref=h0)
    alpha = film.viscosity.constants["alpha"]
    state = problem.state()
    alpha.value = 0.3
    problem.restore(state)
    assert float(alpha.value) == 0.1
    alpha.value = 0.2                     # drive it, as a continuation would
    problem.solve()
    p_max = MPI.COMM_WORLD.allreduce(float(film.p.x.array.max(initial=0.0)), op=MPI.MAX)
    # the largest nodal value of 200 P1 elements: discretisation error O(h²) ≈ 4e-5
    # (test_barus_slider_…: 2.8e-3 at 25 elements / 64) plus the peak between two nodes,
    # ½|p''|(h/2)² ≈ 3e-5 relative (p'' ≈ p_max/(L/3)², h = 0.05 mm): 2e-4 bounds both
    assert p_max == pytest.approx(barus_pressure(p_iso, 0.2), rel=2e-4)


# -- an open end supplied with lubricant (ReynoldsFilm.add_inflow), the O-ring's air end ---
def test_open_end_supply_starved_inlet(tmp_path):
    # The starved inlet as an open end supplied with the content c_in = (1 − λ_in) h(x_in)
    # (weak upwind inflow, Robin leak for p = 0) instead of the Dirichlet λ_in, p = 0.
    # (1) Everything that enters is the supply: q_in = q_out = c_in u_m (the analytic
    # flux 11.55 mm²/s) to solver tolerance (rows ≤ 1e-10 of the Couette flux; 1e-9).
    v = resolve(reynolds_cylinder.Params, {"inlet_void": str(LAM_IN), "cavitation": "jfo"})
    c_in = (1 - LAM_IN) * (v.h0 + v.x_in ** 2 / (2 * v.R))
    res, _, _ = run_case(reynolds_cylinder, tmp_path, cavitation="jfo", inlet_void=LAM_IN,
                         mesh=100, inlet="supply")
    for key in ("flux_in", "flux_out"):
        assert res[key] == pytest.approx(c_in * v.um, rel=1e-9)
    # (2) the same discrete film as the Dirichlet inlet's test above: the reformation node
    # within one element of Swift–Stieber, the load error of order 2 (Δx 0.04 → 0.01)
    dx = (v.x_out - v.x_in) / 100
    assert abs(res["x_reformation"] - res["swift_stieber_x_reformation"]) <= dx
    fine, _, _ = run_case(reynolds_cylinder, tmp_path, cavitation="jfo", inlet_void=LAM_IN,
                          mesh=400, inlet="supply")
    order = math.log(abs(res["load_rel_error"]) / abs(fine["load_rel_error"])) / math.log(4)
    assert abs(order - 2) < 0.5


def test_open_end_flooded_supply_leaks_back(tmp_path):
    # A flooded supply, c_in = h(x_in) = 0.21 mm: the Couette flow brings 210 mm²/s, the
    # film passes the Swift–Stieber flux (12.2 mm²/s) and the rest leaves through the
    # open end by the Robin leak (p ≈ 0 there).  Against the Dirichlet inlet p = 0, λ = 0
    # on the same mesh: the leak leaves p_0 = Δp_e/1000 at the end (Δp_e the last
    # element's pressure drop, ≲ p_max Δx/(x_pmax − x_in) ≈ p_max/50 at 100 elements), a
    # load change ≤ p_0 (x_r − x_in)/load ≲ 1e-4 of the load; the fluxes likewise.
    sup, _, _ = run_case(reynolds_cylinder, tmp_path, cavitation="jfo", mesh=100, inlet="supply")
    dir_, _, _ = run_case(reynolds_cylinder, tmp_path, cavitation="jfo", mesh=100)
    assert abs(sup["load_rel_error"] - dir_["load_rel_error"]) < 1e-4
    assert sup["flux_out"] == pytest.approx(dir_["flux_out"], rel=1e-4)
    assert sup["flux_in"] == pytest.approx(sup["flux_out"], rel=1e-9)   # mass: the leak counted


def test_rigid_film_without_scales_derives_the_wedge_scales():
    """``RigidFilm(scales=None)`` derives its scales from the gap (``FilmScales.hydrodynamic``):
    for the cylinder's gap h₀ + x²/(2R) the least gap is h₀ and the nodes where the gap
    is below 2h₀ span |x| ≤ √(2Rh₀) (to one element, Δx), so the pressure scale is the
    wedge's 6μu_m√(2Rh₀)/h₀².  With them the penalty film (no SUPG: the scales then
    change when Newton stops, not the solution) reaches the film of hand-set scales
    (p_c = 1 MPa, h_ref = 10 µm) to the stopping tolerance (rtol 1e-10 of either's
    scales: 1e-8 of p_max)."""
    from dolfinx import mesh as dmesh

    from tribofx.cases.film_setup import rigid_film
    from tribofx.interfaces import FilmScales, Fluid, Penalty, RigidFilm
    from tribofx.problem import Problem

    R, h0, um, mu, n = 10.0, 1e-3, 1000.0, 1e-7, 400
    x0, x1 = -1.5, 1.0
    gap = lambda x: h0 + x**2 / (2 * R)   # noqa: E731
    given = rigid_film(MPI.COMM_WORLD, x0, x1, n, 1, gap, um, mu, cavitation="penalty",
                       eps=1e-6, p_c=1.0, h_ref=1e-2)
    given.problem.solve()
    film = RigidFilm(dmesh.create_interval(MPI.COMM_WORLD, n, [x0, x1]), gap, um, Fluid(mu),
                     cavitation=Penalty(1e-6))
    film.add_pressure_bc()
    ell, dx = math.sqrt(2 * R * h0), (x1 - x0) / n
    s = film.scale_values()
    assert s["film_scale"] == pytest.approx(h0, rel=1e-12)
    assert s["speed_scale"] == um
    expect = FilmScales.hydrodynamic(mu, um, h0, ell).pressure
    assert abs(s["p_c"] / expect - 1) <= dx / ell
    Problem([film], name="reynolds_derived", max_it=50, max_backtracks=8).solve()
    p_max = MPI.COMM_WORLD.allreduce(float(np.max(given.film.p.x.array)), op=MPI.MAX)
    diff = MPI.COMM_WORLD.allreduce(float(np.max(np.abs(film.p.x.array
                                                        - given.film.p.x.array))), op=MPI.MAX)
    assert diff <= 1e-8 * p_max, diff / p_max

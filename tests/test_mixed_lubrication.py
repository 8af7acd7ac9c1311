"""Mixed lubrication: average flow, asperity contact, their limits and tangent.

References: the Greenwood–Tripp integral by quadrature (tribofx.references_mixed),
the inverse of the asperity law for a flat punch, the smooth film of the chapter.
"""

import math

import numpy as np
import pytest
import ufl
from dolfinx import fem
from mpi4py import MPI
from tribofx.forms import mixed
from tribofx.forms.hyperelastic import lame_parameters
from tribofx.meshes.hertz import NAMES, hertz_body

from tribofx.body import Body
from tribofx.cases import rough_contact
from tribofx.cases import stribeck as stribeck_case
from tribofx.interfaces import Film, FilmScales, Fluid
from tribofx.obstacles import rigid_plane
from tribofx.output import RunRecord
from tribofx.params import resolve
from tribofx.problem import Problem
from tribofx.references import hertz
from tribofx.references_mixed import flat_punch_separation, greenwood_tripp_f52, jgp_load_sharing
from tribofx.roughness import Roughness, greenwood_tripp
from tribofx.testing import block_taylor_orders, exact_tangent, penalty_film_directions


def _eval(fn, x):
    """Value of the UFL function ``fn`` at the number ``x`` (a Constant on a one-cell mesh)."""
    from dolfinx import mesh

    m = mesh.create_unit_interval(MPI.COMM_SELF, 1)
    c = fem.Constant(m, float(x))
    return fem.assemble_scalar(fem.form(fn(c) * ufl.dx(domain=m)))


def test_fit_of_the_greenwood_tripp_integral():
    """The asperity law is Arcoumanis et al.'s fit of F_{5/2}, and errs as that fit does.

    * The UFL law against the published formula 4.4086e-5 (4 − H)^6.804, 0 for H ≥ 4,
      evaluated apart in NumPy (H from 0 to 5, σ = 0.7 µm, KE = 3 MPa): equal to
      round-off, 1e-12 (one power and two products in double precision).
    * The fit's own error against the integral F_{5/2} (``greenwood_tripp_f52``, adaptive
      quadrature exact to 1e-8): the law deviates from the integral by exactly the
      deviation of the published formula, to the quadrature's 1e-8 (−11 % at H = 0,
      −3.5 % at 1, −9 % at 2: the fit's modelling error, which the forms document).
    """
    A, Hc, n = mixed.GT_FIT
    assert (A, Hc, n) == (4.4086e-5, 4.0, 6.804)     # Arcoumanis et al. (1997), as cited
    sigma, KE = 0.7e-3, 3.0
    for H in (0.0, 0.5, 1.0, 2.0, 3.0, 3.9, 4.0, 5.0):
        law = _eval(lambda h: mixed.greenwood_tripp_pressure(h, sigma, KE), H * sigma)
        formula = KE * 4.4086e-5 * max(4.0 - H, 0.0) ** 6.804
        assert law == pytest.approx(formula, rel=1e-12, abs=1e-300), H
    for H in (0.0, 1.0, 2.0):
        fit = _eval(lambda c: mixed.greenwood_tripp_pressure(c, 1.0, 1.0), H)
        published = 4.4086e-5 * (4.0 - H) ** 6.804 / greenwood_tripp_f52(H) - 1
        print(f"H = {H}: fit / F_5/2 - 1 = {fit / greenwood_tripp_f52(H) - 1:+.4f}")
        assert abs(fit / greenwood_tripp_f52(H) - 1 - published) < 1e-8, H
    # the quadrature itself: F_{5/2}(0) = 2^{3/4} Γ(7/4)/√(2π)
    assert greenwood_tripp_f52(0.0) == pytest.approx(2**0.75 * math.gamma(1.75)
                                                     / math.sqrt(2 * math.pi), rel=1e-8)


def test_expected_gap_and_flow_factors_limits():
    """h_T → h and φ_x → 1, Φ_s → 0 far from contact (H = 20): the smooth film's flux."""
    assert _eval(lambda h: mixed.expected_gap(h, 1.0), 20.0) == pytest.approx(20.0, rel=1e-12)
    assert _eval(mixed.patir_cheng_pressure_factor, 20.0) == pytest.approx(1.0, abs=1e-4)
    assert abs(_eval(mixed.patir_cheng_shear_factor, 20.0)) < 1e-2
    # at contact (H = 0) the expected gap is σ/√(2π): the mean of the positive part
    assert _eval(lambda h: mixed.expected_gap(h, 1.0), 0.0) == pytest.approx(
        1 / math.sqrt(2 * math.pi), rel=1e-12)


def stribeck(rough=True, **over):
    """Run the stribeck case with ``over``; return (run, per-speed results)."""
    v = resolve(stribeck_case.Params, {k: str(x) for k, x in over.items()})
    stribeck_case.validate(v)
    rec = RunRecord(stribeck_case.name, {}, {}, ".", MPI.COMM_WORLD)
    run = stribeck_case.run(v, rec, rough=rough)
    return run, {k: r["value"] for k, r in rec.data["results"].items()}


def test_couette_shear_factor_is_the_mean_inverse_gap():
    """φ_f/H (Patir & Cheng 1979) against its definition, by quadrature.

    φ_f/H = (35/96) ∫ (1 − x²)³/(z + x) dx over x ∈ (ε* − z, 1) ∩ (−1, 1), z = H/3,
    ε* = 1/300: the mean of σ/h_T over the polynomial height density, gaps below
    3ε*σ in contact.  Reference: the integral in y = ln(z + x) by the trapezoidal
    rule on 4e5 points (error < 1e-9).  Tolerance: for H > 3 the closed form and its
    series are the integral (1e-8); for H ≤ 3 Patir and Cheng's closed form drops the
    polynomial part's value at the lower limit, |Q(ε*)| ≤ (35/96) ε* max|d(1 − (y −
    z)²)³/dy| ≤ (35/96)(1/300)(1.8) = 2.2e-3 (absolute).
    """
    eps = 1.0 / 300

    def reference(H):
        z = H / 3
        lo = max(eps - z, -1.0)
        if lo >= 1.0:
            return 0.0
        t = np.linspace(np.log(z + lo), np.log(z + 1), 400_001)
        x = np.exp(t) - z
        return 35 / 96 * np.trapezoid((1 - x * x) ** 3, t)

    for H in (-2.9, -2.0, -1.0, -0.3, 0.0, 0.5, 1.0, 2.0, 2.99):
        assert abs(_eval(mixed.patir_cheng_couette_factor, H) - reference(H)) < 2.2e-3, H
    for H in (3.01, 4.0, 9.0, 14.9, 15.1, 30.0, 90.0):
        got, ref = _eval(mixed.patir_cheng_couette_factor, H), reference(H)
        assert abs(got / ref - 1) < 1e-8, (H, got, ref)
    # the smooth film's μ/h far from the roughness: φ_f → 1 (φ_f = 1 + 1/(9z²) + …)
    z = 100.0       # H = 300: the next term, (1/33) z⁻⁴ = 3e-10
    assert _eval(mixed.patir_cheng_couette_factor, 3 * z) * 3 * z == pytest.approx(
        1 + 1 / (9 * z * z), rel=1e-9)


def test_full_film_end_is_the_smooth_film():
    """At λ ≈ 14 the rough film carries W alone and equals the smooth one.

    The flux differs from the smooth film's by 1 − φ_x(H) = 0.9e^{−0.56H} in the
    Poiseuille part and by the shear flow σΦ_s(H)/h = 1.126e^{−0.25H}/H against
    the Couette part, largest where the film is thinnest (H = h_min/σ ≈ 11: 1.7e-3
    and 6e-3); h_T/h − 1 < 1e-27.  Tolerance: their sum at h_min, on h_central,
    h_min and p_max; the asperities (zero above H = 4) carry nothing.
    """
    _, rough = stribeck(speeds="1000")
    _, smooth = stribeck(rough=False, speeds="1000")
    lam = rough["h_min"][0] / 1e-3
    tol = 0.9 * math.exp(-0.56 * lam) + 1.126 * math.exp(-0.25 * lam) / lam
    for k in ("h_central", "h_min", "p_max"):
        assert abs(rough[k][0] / smooth[k][0] - 1) < tol, (k, rough[k], smooth[k], tol)
    assert rough["film_load_fraction"][0] == pytest.approx(1.0, abs=1e-12)


@pytest.mark.slow
def test_stribeck_curve_has_its_three_regimes():
    """Full film, mixed, boundary over five decades of speed (the defaults, 11 speeds).

    Slow (about 75 s, ``--runslow``): the default suite checks the three regimes at three
    speeds (``demos/demo_mixed_lubrication.py``) and the mixed regime against JGP.

    Full film (λ > 3): the film carries W, the friction is the fluid's and falls
    with the speed (Couette μU/h with h ∝ U^0.6: f ∝ U^0.4 at most); its minimum
    lies in the mixed regime, where the asperities carry part of W but the film
    most (0.5 < film share < 1); below it, towards the boundary end, the friction
    rises at every step towards μ_b = 0.1 as the asperities take over, a weighted
    mean of μ_b and the fluid's smaller coefficient, so below μ_b.  (Between
    λ = 3 and the minimum the friction need not fall monotonically: the shear
    factors φ_f + Φ_fs of the rough film grow faster than U falls near H ≈ 1.5.)
    """
    _, r = stribeck()
    lam, f, frac = (np.array(r[k]) for k in ("lambda_ratio", "friction_coefficient",
                                             "film_load_fraction"))
    full = lam > 3
    assert full.sum() >= 2 and np.all(np.diff(f[full]) < 0), (lam, f)
    # λ > 3: h_min/σ > 2.5 here, p_a ≤ K E* A 1.5^6.8 = 7e-4 K E* = 1.3e-4 MPa against
    # the mean pressure W/2a ≈ 0.25 MPa: even over the whole contact < 1e-3 of W
    assert np.all(frac[full] > 1 - 1e-3), frac
    i = int(np.argmin(f))
    assert 0.5 < frac[i] < 1.0, (frac, f)
    assert np.all(np.diff(f[i:]) > 0), f
    assert frac[-1] < 0.5
    assert np.all(f < 0.1)          # below the dry boundary friction μ_b everywhere


def test_mixed_regime_against_the_jgp_load_sharing():
    """The film's share of W against Johnson, Greenwood & Poon's (1972) estimate.

    JGP splits W into a film part W/γ₁, the smooth film of that load on E*/γ₁
    (its h_c from the smooth model's own central film at the same speed, the
    isoviscous-elastic exponents h ∝ W^−0.2 E*^−0.4), and an asperity part W/γ₂
    whose central pressure is Hertz's (:func:`jgp_load_sharing`).  What it leaves
    out: the rough film's flow factors (φ_x(1) ≈ 0.5) and the outlet constriction
    of a soft EHL film (h_min ≈ 0.75 h_c), where p_a is ((4 − H_min)/(4 − H_c))^6.8
    ≈ 1.2–1.5 times its central value here.  Expected agreement: the asperity share
    1 − s within a factor 1.5 of JGP's, i.e. |s − s_JGP| ≤ 0.5 (1 − s_JGP), where
    the asperities carry a part (U = 30 … 1 mm/s, λ = 1.5 … 0.13).  Measured: film
    shares 0.989, 0.947, 0.869, 0.773 against JGP 0.990, 0.942, 0.878, 0.832.
    """
    speeds = "1000,30,10,3,1"
    _, rough = stribeck(speeds=speeds)
    _, smooth = stribeck(rough=False, speeds=speeds)
    v = resolve(stribeck_case.Params, {"speeds": speeds})
    p0 = hertz(v.W, v.R, v.E, v.nu, line=True).p0
    KE, (A, Hc, n) = rough_contact.roughness(v).asperity.parameters["KE"], mixed.GT_FIT

    def p_a(h):
        return KE * A * max(Hc - h / v.sigma, 0.0) ** n

    for i, U in enumerate(rough["speeds"][1:], start=1):
        share, h_c = jgp_load_sharing(smooth["h_central"][i], p0, p_a)
        s = rough["film_load_fraction"][i]
        print(f"U {U}: film share {s:.4f}, JGP {share:.4f}; h_c {rough['h_central'][i]:.3e}"
              f", JGP {h_c:.3e}")
        assert abs(s - share) <= 0.5 * (1 - share), (U, s, share)


@pytest.mark.parametrize("U", [1e-4, 1e-7])
def test_boundary_regime_levels_at_the_boundary_friction(U):
    """Below the mixed regime the asperities carry W and the friction is μ_b, at any speed.

    U = 1e-4 mm/s (0.1 µm/s, below what a tribometer drives) and 1e-7 mm/s, μ_b =
    0.12.  The asperities carry the load less the film's share s_f = ∫p/W (a
    field of its own, the Reynolds pressure), so the friction coefficient is
    μ_b (1 − s_f) up to (relative to μ_b W, a = 1.0 mm, p₀ = 0.32 MPa, E* = 12.5 MPa):
    the film's Poiseuille shear (h/2)|∇p| over the contact ≤ s_f σ/(a μ_b) (3e-5 at
    1e-4 mm/s where s_f ≈ 4e-3), its Couette shear μU·2a/h_T with h_T ≥ 0.4σ (8e-7),
    the regularisation of the friction's direction, 1 − δ_v²/2 with ε_v = δ_v U,
    δ_v = 1e-3 (5e-7), and the tilt of the contact's normal under the friction's
    shear, (μ_b p₀/E*)² ≈ 1e-5: together ≤ 5e-5, asserted within 1e-4.  The film's
    share itself stays below 1 % (the boundary regime).  (A direction regularised
    over a constant slip speed, 1e-3 mm/s, would give 0.012 at 1e-4 mm/s and 1e-5
    at 1e-7 mm/s: the boundary plateau would collapse.)
    The load march reaches W there directly (the first secant slope 1/σ; the
    film's flux tolerance floored at the Poiseuille flux of a σ-thick gap).
    """
    mu_b = 0.12
    _, r = stribeck(speeds=f"{U}", mu_b=mu_b)
    s_f = r["film_load_fraction"][0]
    assert s_f < 1e-2
    assert r["friction_coefficient"][0] == pytest.approx(mu_b * (1 - s_f), rel=1e-4)


@pytest.mark.slow
def test_creeping_rough_cylinder_approaches_hertz():
    """At creeping speed the rough cylinder's contact tends to Hertz's as σ/a → 0.

    The measure is the load-weighted half-width a_eff = 2 (∫p x²/∫p − x̄²)^½ of the
    total pressure p + p_a (a for Hertz's ellipse; robust to the node-to-node
    overshoot of a stiff asperity law, which the peak pressure is not).  With
    σ = 1e-3 and 1e-4 mm (σR/a² = 0.02, 0.002) the deviation from Hertz falls, and
    at σ = 1e-4 it lies within the finite-strain error of Hertz, p₀/E* = 3.6 %.
    Measured 0.7288 and 0.7216 mm against a_H = 0.7125 (+2.3 %, +1.3 %; 3e-4: 0.7236).
    Slow (about 2 min, ``--runslow``).
    """
    dev = []
    for sigma in (1e-3, 1e-4):
        run, _ = stribeck(speeds="1e-6", sigma=sigma)
        pr = run.film.profile(everywhere=True)
        x, p = pr["x"][:, 0], pr["p"] + pr["p_a"]
        W = np.trapezoid(p, x)
        xbar = np.trapezoid(p * x, x) / W
        a_eff = 2 * np.sqrt(np.trapezoid(p * x * x, x) / W - xbar**2)
        v = resolve(stribeck_case.Params, {})
        ref = hertz(v.W, v.R, v.E, v.nu, line=True)
        dev.append(abs(a_eff / ref.a - 1))
    assert dev[1] < dev[0], dev
    assert dev[1] < ref.p0 / ref.E_star, (dev, ref.p0 / ref.E_star)


def test_vanishing_roughness_is_the_smooth_film():
    """σ → 0 (1e-9 mm, no asperities): the smooth film to solver tolerance.

    At H = h/σ ~ 1e7 the flow factors are 1 and 0 to round-off and h_T = h.
    """
    out = []
    for rough in (True, False):
        v = resolve(stribeck_case.Params, {"speeds": "1000", "sigma": "1e-9"})
        run = rough_contact.build(v, "cylinder", 1000.0, rough=rough)
        film = run.film
        film.counterpart.offset.value[1] = -0.01
        run.problem.solve()
        prof = film.profile(everywhere=True)
        out.append(np.r_[film.force(), prof["p"].max()])
    assert np.allclose(out[0], out[1], rtol=1e-8, atol=0), out


@pytest.mark.parametrize("kind", ["plane_strain", "axisymmetric"])
def test_rough_flat_punch_separation(kind):
    """A block pressed on a rough rigid plane at rest: the asperities alone carry p.

    The block ([0, B]² with symmetry at x = 0, or revolved about it: a cylinder of
    radius B) carries a dead uniform traction P on its base towards the plane; with
    no motion the film has no pressure, and the asperity pressure balances P over the
    current top face of width (radius) b: p_a = P B/b, or P B²/b² revolved, so h
    solves p_a = K E* F_{5/2}(h/σ) (:func:`flat_punch_separation`), and the asperity
    force is −P B per unit length, or −P πB² (the revolved body's, N: the weights of
    a surface of revolution).  Solver tolerance 1e-10: h to 1e-6, the force to 1e-8.
    """
    B, E, nu, P, sigma, KE = 2.0, 10.0, 0.3, 0.02, 1e-3, 0.05
    msh, ft = hertz_body(2, B, B / 8, B / 8, B, MPI.COMM_WORLD, block=B)
    axi = kind == "axisymmetric"
    axis = "axis" if axi else "symmetry_x"
    names = {"lubricated": NAMES["contact"], "loaded": NAMES["loaded"],
             axis: NAMES["symmetry_x"]}      # the axis of revolution: the 2D symmetry tag
    mu_s, lm = lame_parameters(E, nu)
    body = Body(msh, ft, names, kind, ("neo-hookean", {"mu": mu_s, "lmbda": lm}),
                name="block")
    body.add_dirichlet(axis, 0.0, component=0)
    body.add_traction("loaded", fem.Constant(msh, np.array([0.0, P])))   # up, to the plane
    h0 = flat_punch_separation(P, sigma, KE)
    film = Film(body, "lubricated", rigid_plane([0.0, h0], [0.0, -1.0]), Fluid(1e-7),
                scales=FilmScales(pressure=P, film=sigma, speed=1.0),
                roughness=Roughness(sigma, asperity=greenwood_tripp(KE, sigma), flow=None))
    film.add_pressure_bc((lambda X: X[0] > B * (1 - 1e-9)) if axi else None)
    Problem([body, film], name="punch").solve()
    prof = film.profile(everywhere=True)
    b = prof["x"][:, 0].max() - prof["x"][:, 0].min()
    m, area = (2, math.pi * B**2) if axi else (1, B)
    h = flat_punch_separation(P * (B / b) ** m, sigma, KE)
    assert np.allclose(prof["h"], h, rtol=1e-6, atol=0), (prof["h"], h)
    assert abs(film.asperity_force()[1] / (P * area) + 1) < 1e-8


def test_rough_film_tangent_is_exact():
    """Taylor test in the mixed regime (λ ≈ 0.8: flow factors and asperities both active).

    The pressure is perturbed only where p > 0.01 p_max: the penalty's min(p, 0) has
    a kink at p = 0 (semismooth), where no tangent is exact.
    """
    run, res = stribeck(speeds="1000,10", mesh=0)
    assert 0.3 < res["lambda_ratio"][-1] < 2.0
    prob = run.problem
    dirs = penalty_film_directions(prob, run.film.p, 11)
    for name, (orders, rem, floor) in block_taylor_orders(prob, dirs, eps0=1.0).items():
        assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)


@pytest.mark.slow
@pytest.mark.mpi
def test_parallel_matches_serial():
    """The mixed film at two speeds (full film, then λ ≈ 0.8): 2 ranks = 1 (secant 1e-7).

    Slow (``--runslow``): the running-in's parity test (``tests/test_wear_lubricated.py``)
    runs the same film through the same speeds (1000 → 10 mm/s), and wears it.
    """
    if MPI.COMM_WORLD.size < 2:
        pytest.skip("run under mpiexec -n 2")
    out = []
    for comm in (MPI.COMM_SELF, MPI.COMM_WORLD):
        v = resolve(stribeck_case.Params, {"speeds": "1000,10"})
        rec = RunRecord(stribeck_case.name, {}, {}, ".", comm)
        stribeck_case.run(v, rec, comm=comm)
        res = rec.data["results"]
        out.append(np.array([res[k]["value"] for k in ("friction_coefficient",
                                                       "film_load_fraction", "h_central",
                                                       "p_max")]))
    # the secant stops within 1e-7 of log W: the states agree to ~1e-6
    assert np.allclose(out[0], out[1], rtol=1e-5, atol=0), out

"""Soft-EHL ball on a rigid plane (chapter §8.3, 3D): Hamrock–Dowson film, finite → linear
limit, exact coupled tangent (Taylor) and quadratic Newton, tangential pressure gradient
against the exact one on the sphere, serial = 2 ranks."""

import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest
import ufl
from dolfinx import fem
from mpi4py import MPI
from tribofx.meshes.ball import cap_height

from tribofx.cases import ehl_ball as Case
from tribofx.params import resolve
from tribofx.problem import convergence_orders
from tribofx.references import hamrock_dowson, hertz
from tribofx.testing import (
    block_taylor_orders,
    exact_tangent,
    newton_is_quadratic,
    oil_books,
    residual_floor,
)


def values(**overrides):
    v = resolve(Case.Params, {k: str(x) for k, x in overrides.items()})
    Case.validate(v)
    return v


def _solve(v):
    run = Case.build(v)
    out = []

    def on_step(W, its):
        out.append(dict(Case.measures(run, v), iterations=its))

    Case.load_sweep(run, v, on_step)
    return run, out


@pytest.fixture(scope="module")
def light_load():
    """W = 2 N (a ≈ 0.18 R), μU = 1e-4 N/mm, element size a/8 near the contact.

    The displacement solid with Gauss points (the case's defaults until the mixed
    solid and the vertex rule replaced them): the configuration the error estimates
    of the tests on this state (first-order mesh convergence, the meshed plane's
    residual equal to the analytic plane's at the Gauss points) were derived for.
    """
    v = values(W=2.0, steps=1, mesh=1, formulation="displacement", quadrature="gauss")
    run, out = _solve(v)
    return v, run, out[-1]


@pytest.mark.mpi
def test_film_matches_hamrock_dowson(light_load):
    """Central and minimum film against the isoviscous-elastic formulas (k = 1).

    The central film converges about linearly in the element size (h_c at
    W = 4 N on meshes 0, 1, 2: 25.1, 30.4, 33.3 µm, observed order 0.9), so it
    is also extrapolated (Richardson, order 1) from meshes 0 and 1.
    """
    v, run, m = light_load
    hc, hm = hamrock_dowson(v.W, v.mu, v.U, v.R, Case.e_star(v))
    m0 = _solve(v.replace(mesh=0))[1][-1]
    h_ext = 2 * m["h_central"] - m0["h_central"]
    d_c, d_m, d_x = m["h_central"] / hc - 1, m["h_min"] / hm - 1, h_ext / hc - 1
    print(f"h_c = {m['h_central']:.5g} mm (HD {hc:.5g}, {100 * d_c:+.1f} %), "
          f"h_min = {m['h_min']:.5g} mm (HD {hm:.5g}, {100 * d_m:+.1f} %), dofs "
          f"{run.problem.num_dofs}; mesh 0: h_c = {m0['h_central']:.5g} mm, "
          f"extrapolated h_c = {h_ext:.5g} mm ({100 * d_x:+.1f} %)")
    # equilibrium of the solved state (not the load controller's own stopping test): the
    # reaction of the held mid-plane, from the bulk stresses, balances the film force
    reaction, bound = _mid_plane_reaction(run), _equilibrium_bound(run, m["W"])
    print(f"mid-plane reaction {reaction!r} N, film force {m['W']!r} N, bound {bound:.2e}")
    assert abs(reaction + m["W"]) <= bound
    # refinement thickens the central film (under-resolved inlet on coarse meshes)
    assert m0["h_central"] < m["h_central"]
    # Hamrock & Dowson fitted their numerical half-space solutions within about
    # ±10–20 %; the ball here is finite-strain (a/R ≈ 0.18), ν = 0.45 not 0.5, the
    # cavitation a penalty: 20 % on h_c (mesh 1 and extrapolated), 25 % on h_min
    # (mesh 1, element size a/8).
    assert abs(d_c) < 0.20
    assert abs(d_x) < 0.20
    assert abs(d_m) < 0.25
    # the minimum film lies downstream (x > 0: the plane moves in +x) of the centre
    assert m["x_h_min"] > 0 and m["h_min"] < m["h_central"]


@pytest.mark.slow
def test_jfo_ball_matches_the_penalty_inlet_and_closes_its_books(light_load):
    """cavitation=jfo (the void fraction on the cap's triangles): the penalty's film, its books.

    The central film is set upstream, where both models have a full film fed by a
    flooded inlet (the penalty's rim p = 0; JFO's rim an open end supplied with more
    than the gap, p = 0 to 1e-3 of the last element's drop): they differ by the
    penalty's violation of p ≥ 0 (ε/ε_ref = 1e-4, 2e-3 of the film in the 2D
    cylinder's test) and the rim's condition: 1 % on h_c and the load.  Downstream
    the penalty's Swift–Stieber rupture conserves no mass and JFO's does: h_min may
    differ.  The oil's books on the cap (supplied + entered = out + leak) close to the
    sum of the converged nodal rows, N × their tolerance.  The supply at the rim of
    more than the central film's flux: λ = 0 at the inflow rim nodes.  Slow (30 s):
    JFO on a surface is checked in the default run by ``tests/test_jfo_surface.py``
    (a slab against the curve) and the receding sphere of ``tests/test_squeeze.py``.
    """
    v_pen, _, m_pen = light_load
    v = v_pen.replace(cavitation="jfo")
    run, out = _solve(v)
    m, film = out[-1], run.film
    books, imbalance, bound = oil_books(film)
    print(f"h_c {m['h_central']:.6g} (penalty {m_pen['h_central']:.6g}), h_min "
          f"{m['h_min']:.6g} ({m_pen['h_min']:.6g}), W {m['W']:.6g} ({m_pen['W']:.6g}); "
          f"books {books}, imbalance {imbalance:.3g} (bound {bound:.3g})")
    assert abs(m["h_central"] / m_pen["h_central"] - 1) <= 0.01
    assert abs(m["W"] / m_pen["W"] - 1) <= 0.01
    assert abs(imbalance) <= bound
    assert books["out"] > 0 and books["supplied"] > books["leak"] > 0
    lam = film.lam.x.array
    assert lam.min() >= -1e-8 and lam.max() < 1.0 and lam.max() > 0.5   # a cavity behind


@pytest.mark.mpi
def test_soft_disc_jfo_matches_its_penalty_inlet_and_closes_its_books():
    """cavitation=jfo between the ball and a disc as soft (PDMS on PDMS: E2 = E, ν2 = ν),
    W = 2 N, mesh 0, the ball at rest on the sliding disc: the two-body film
    (:class:`tribofx.interfaces.TwoBodyFilm` in 3D) with the void fraction on the ball's
    cap, the rim an open end flooded with its gap, the symmetry plane's edges left out
    of the Couette flux (``ReynoldsFilm.add_symmetry``).

    As for the ball on the rigid plane
    (:func:`test_jfo_ball_matches_the_penalty_inlet_and_closes_its_books`): the central
    film and the load are set upstream, where both models have a full film fed by a
    flooded inlet, so they agree within 1 % (the penalty's violation of p ≥ 0, 2e-3 of
    the film, and the rim's condition); the oil's books close to N × the rows'
    tolerance (:func:`tribofx.testing.oil_books`); a cavity forms behind the contact.
    Both with Gauss points (the vertex rule does not converge with JFO; ``auto`` takes
    Gauss for JFO).
    """
    m = {}
    for cav in ("penalty", "jfo"):
        v = values(W=2.0, steps=1, mesh=0, E2=1.19, nu2=0.45, cavitation=cav,
                   quadrature="gauss")
        run, out = _solve(v)
        m[cav] = out[-1]
    film = run.film
    books, imbalance, bound = oil_books(film)
    print({k: (m["jfo"][k], m["penalty"][k]) for k in ("h_central", "h_min", "W")},
          books, imbalance, bound)
    assert abs(m["jfo"]["h_central"] / m["penalty"]["h_central"] - 1) <= 0.01
    assert abs(m["jfo"]["W"] / m["penalty"]["W"] - 1) <= 0.01
    assert abs(imbalance) <= bound
    assert books["out"] > 0 and books["supplied"] > books["leak"] > 0
    lam = film.lam.x.array
    lam_max = MPI.COMM_WORLD.allreduce(float(lam.max(initial=0.0)), op=MPI.MAX)
    lam_min = MPI.COMM_WORLD.allreduce(float(lam.min(initial=1.0)), op=MPI.MIN)
    assert lam_min >= -1e-8 and 0.5 < lam_max < 1.0     # a cavity behind


def test_auto_rule_takes_gauss_points_with_jfo_and_on_mesh_0():
    """``quadrature=auto`` (the default): the vertex rule with the penalty, Gauss points
    with JFO and on mesh 0 (where the mixed solid with the vertex rule stalls at 4 N);
    ``cavitation=jfo quadrature=vertex`` is refused at validation in one line."""
    from tribofx.params import InputError

    assert Case.film_rule(values()) == "vertex"
    assert Case.film_rule(values(cavitation="jfo")) == "gauss"
    assert Case.film_rule(values(mesh=0)) == "gauss"
    assert Case.film_rule(values(mesh=0, quadrature="vertex")) == "vertex"
    with pytest.raises(InputError, match="cavitation=jfo takes quadrature=gauss"):
        values(cavitation="jfo", quadrature="vertex")


@pytest.mark.slow
def test_starved_ball_film_falls_below_the_flooded_one_and_the_supply(light_load):
    """A starved ball (cavitation=jfo, supply c_in = 0.036 mm ≈ h_cff): its film thins.

    The starvation literature's picture (Wedeven, Evans & Cameron 1971; Chevalier,
    Lubrecht, Cann, Colin & Dalmaz, J. Tribol. 120 (1998) 126–133): the flooded film
    h_cff while the inlet meniscus lies far upstream; once the supply runs short the
    central film follows the available layer, below both asymptotes,
    h_c/h_cff = r/(1 + r^γ)^{1/γ} with r = c_in/h_cff.  What mass conservation makes
    exact here: the fluid crossing the centre line (Couette U h_c, the Poiseuille flux
    vanishing with ∂p/∂x at the pressure peak) came in through the rim as U c_in, less
    what flows round the contact, so h_c ≤ c_in up to that Poiseuille part (2 %
    allowed).  At r ≈ 1 the curve gives 1/2^{1/γ}, below 0.9 for every γ < 6.6: the
    film must fall by more than 10 % (measured 0.82).  The reference h_cff is the
    penalty film of the fixture (JFO's flooded one is within 0.3 %, the test above).
    The supply is marched down from the flooded rim in the case's steps
    (:func:`tribofx.cases.ehl_ball.supply_march`, ratios ≤ 1.5).  The march is not robust
    on every step sequence (to c_in = 4 h_cff in 8 steps it stalls at 0.45 mm): near
    the cap's rim λ ≈ 1 − h_c/h_rim ≈ 0.99, and Newton steps to λ ≥ 1, where the
    clamped rows are singular (an admissible line search, ``require_open``, stalls
    there instead).
    """
    v_pen, _, m_pen = light_load
    c_in = 0.036
    v = v_pen.replace(cavitation="jfo", supply=c_in)
    run = Case.build(v)
    inner = Case.load_sweep(run, v)
    Case.supply_march(run, v, inner, v.W)
    m, film = Case.measures(run, v), run.film
    books, imbalance, bound = oil_books(film)
    r, f = c_in / m_pen["h_central"], m["h_central"] / m_pen["h_central"]
    print(f"c_in/h_cff = {r:.3f}: h_c/h_cff = {f:.4f}, h_min {m['h_min']:.5g} mm, "
          f"W {m['W']:.6g}; books {books}, imbalance {imbalance:.3g} (bound {bound:.3g})")
    assert abs(m["W"] / v.W - 1) <= 1e-3
    assert f < 0.9
    assert m["h_central"] <= 1.02 * c_in
    assert abs(imbalance) <= bound


@pytest.mark.slow
def test_stiff_disc_reproduces_the_rigid_plane(light_load):
    """A disc of E2 = 1e4 MPa (10⁴ E) under the ball: the rigid plane's film (W = 2 N, mesh 1).

    The two-body film (:class:`tribofx.interfaces.TwoBodyFilm` in 3D) lives on the
    ball's surface (S = γ_l), the rigid one on the plane (S = P(γ_l)); their metrics
    differ by O((a/R)²), the film's slope over the contact (3.4 % here); the disc
    yields p a/E2 ~ 1e-5 of a against a film of 1e-2 a.  The two-body gap is P1
    between the nodes, where the rigid plane's is exact at the quadrature points: the
    ball's chord sag h_e²/(8R) (h_e = a/8, 0.8 µm) against the film.  Bounds: h_c, p_max
    and the friction coefficient within (a/R)²; h_min, at the outlet constriction,
    within (a/R)² + h_e²/(8R h_min) (7.8 %).  About 1 min: slow (the disc's film is
    checked in the default run by
    :func:`test_soft_disc_in_pure_rolling_matches_hamrock_dowson_of_the_pair`).
    """
    v, _, rigid = light_load
    vd = v.replace(E2=1e4)
    run, out = _solve(vd)
    m = out[-1]
    a = Case.hertz_contact(vd).a
    metric = (a / vd.R) ** 2
    sag = (Case.ball_fine_size(vd)) ** 2 / (8 * vd.R)
    rel = {k: m[k] / rigid[k] - 1 for k in ("h_central", "h_min", "p_max",
                                             "friction_coefficient")}
    print("stiff disc / rigid plane − 1:", rel, "bounds", metric, metric + sag / rigid["h_min"])
    for k in ("h_central", "p_max", "friction_coefficient"):
        assert abs(rel[k]) < metric, k
    assert abs(rel["h_min"]) < metric + sag / rigid["h_min"]


def test_soft_disc_in_pure_rolling_matches_hamrock_dowson_of_the_pair():
    """A disc as soft as the ball (E2 = E, ν2 = ν; PDMS on PDMS), both rolling (SRR = 0).

    Pure rolling is Hamrock–Dowson's own condition: the film against their formulas
    with the composite modulus E* of the pair, in the same bands as the ball on the
    rigid plane (:func:`test_film_matches_hamrock_dowson`: their fit's ±10–20 %, the
    finite strain, ν = 0.45, the penalty cavitation): 20 % on h_c, 25 % on h_min;
    the film thicker than Hamrock–Dowson's for the ball on the rigid plane (the pair
    is twice as compliant: h_c ∝ E*^-0.44).  Two identical bodies in pure rolling
    carry no Couette friction: their surfaces stretch alike (Dundurs' β = 0), so the
    Couette traction μ(v₁ − v₂)/h is left only at O((a/R)²) of the sliding one, which
    is at least μ 2U (πa²/2)/(h_c W/2) (the half contact under the central film; the
    film is thinner at the outlet).  Equilibrium from the fields: the ball's held
    mid-plane and the disc's held support each balance the film force (the bodies'
    own rows; bound as :func:`_equilibrium_bound`, the residual norm of the coupled
    system).
    """
    v = values(W=2.0, steps=1, mesh=1, E2=1.19, nu2=0.45, SRR=0.0)
    run, out = _solve(v)
    m = out[-1]
    hc, hm = hamrock_dowson(v.W, v.mu, v.U, v.R, Case.e_star(v))
    d_c, d_m = m["h_central"] / hc - 1, m["h_min"] / hm - 1
    a = Case.hertz_contact(v).a
    sliding = v.mu * 2 * v.U * (math.pi * a**2 / 2) / (m["h_central"] * m["W"] / 2)
    print(f"soft disc, rolling: h_c = {m['h_central']:.5g} mm (HD {hc:.5g}, {100 * d_c:+.1f} %), "
          f"h_min = {m['h_min']:.5g} mm (HD {hm:.5g}, {100 * d_m:+.1f} %); Couette friction "
          f"{m['couette_friction_coefficient']:.3g} (sliding ≥ {sliding:.3g}, (a/R)² "
          f"{(a / v.R) ** 2:.3g})")
    assert abs(d_c) < 0.20
    assert abs(d_m) < 0.25
    assert m["h_central"] > hamrock_dowson(v.W, v.mu, v.U, v.R,
                                           Case.e_star(v.replace(E2=math.inf)))[0]
    assert m["couette_friction_coefficient"] < (a / v.R) ** 2 * sliding
    b, _ = run.problem.assemble()
    for body, name in ((run.ball, "midplane"), (run.disc, "support")):
        n_z = body.V.dofmap.index_map.size_global
        bound = 2 * math.sqrt(n_z) * b.norm() + 1e-12 * m["W"]
        reaction = 2.0 * body.reaction(name, Case.Z)
        print(f"{body.name}: reaction {reaction:.6g} N, film force {m['W']:.6g} N")
        assert abs(abs(reaction) - m["W"]) <= bound


def test_newton_quadratic(light_load):
    """Coupled Newton at a nearby plane position (0.5 % of the approach) converges quadratically."""
    v, (_, film, problem, *_), _ = light_load
    saved = problem.state()
    film.counterpart.offset.value[2] *= 1.005  # the plane 0.5 % of the approach higher
    report = problem.solve()
    floor = residual_floor(problem)
    problem.restore(saved)
    print("residuals", report.residuals, "orders", convergence_orders(report.residuals),
          "floor", floor)
    assert report.iterations <= 8
    # exact UFL tangent: every order above 10× the round-off floor nearer 2 than 1
    assert newton_is_quadratic(report.residuals, floor)


@pytest.mark.mpi
def test_coupled_tangent_taylor(light_load):
    """Exact tangent of the ball EHL residual (u, [p_s,] u_s, p, g) at a solved state.

    Remainder of the first-order Taylor expansion along a random direction is
    O(ε²): S = P(γ_l) on the plane, A, ds_S, v̄ and h depend on u_s, the traction
    (Nanson, j = J|F⁻ᵀN|, Couette (μ/h)·2U, Poiseuille (h/2) grad_S p) on u, p, g.
    The pressure is made positive (|p| + 0.01 p0, 0 on the rim, which is not
    perturbed) so that the penalty kink min(p, 0) is not crossed; perturbations
    (1e-3 of the scales × ε ≤ 1e-2) keep h > 0.
    """
    v, (ball, film, problem, *_), _ = light_load
    saved = problem.state()
    p0 = Case.scales(v)[1]
    # positive pressure except on the rim (p = 0 there: the state satisfies its
    # Dirichlet conditions, and the rim is not perturbed, p = 0 being the kink)
    rim = fem.locate_dofs_geometrical(film.Q, lambda X: np.abs(
        X[2] - cap_height(v.R, math.radians(v.theta_l))) < 1e-6 * v.R)
    film.p.x.array[:] = np.abs(film.p.x.array) + 0.01 * p0
    film.p.x.array[rim] = 0.0
    rng = np.random.default_rng(3 + MPI.COMM_WORLD.rank)
    # 1e-3 of each unknown's scale: displacements and the trace (mm), the film's
    # pressure and the solid's volumetric stress (mixed solid; both ~ p0, MPa), the
    # pressure gradient (p0/R)
    scale = {id(film.p): 1e-3 * p0, id(film.g): 1e-3 * p0 / v.R}
    if ball.p is not None:
        scale[id(ball.p)] = 1e-3 * p0
    dirs = []
    for f in problem.u:
        d = fem.Function(f.function_space)
        d.x.array[:] = scale.get(id(f), 1e-3) * rng.uniform(-1, 1, d.x.array.shape)
        d.x.scatter_forward()
        dirs.append(d)
    dirs[next(k for k, f in enumerate(problem.u) if f is film.p)].x.array[rim] = 0.0
    blocks = block_taylor_orders(problem, dirs, eps0=1e-2)
    problem.restore(saved)
    # exact Jacobian, each unknown's columns alone: order 2 up to round-off; a missing
    # dependence gives 1
    for name, (orders, rem, floor) in blocks.items():
        print("ball EHL", name, orders, rem, floor)
        assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)


@pytest.mark.mpi
@pytest.mark.parametrize("surface", [
    "plane",
    "plane-barus",     # μ(p) = μ₀ e^{αp}, α p0 = 0.7: the 3D film with a pressure-viscosity law
    "curved"])
def test_meshed_plane_tangent_taylor(light_load, surface):
    """Exact tangent with a meshed countersurface in 3D (C++ lubrication projection).

    The same ball and state as :func:`test_coupled_tangent_taylor`, the plane a
    gmsh triangulation projected at the nodes of Γ_l before every evaluation
    (``Problem.residual_at`` refreshes the kernel data at each perturbed state):
    the kernel's ∂P/∂x, ∂ν/∂x and ∂²P/∂x² must give an O(ε²) remainder.  The
    residual itself equals the analytic plane's (flat facets are exact).
    ``curved``: a sphere cap of radius 10 R touching z = 0, biquadratic facets, so
    that the curvature terms of ν and P (and the facets' third derivatives) enter;
    the film integrates by the vertex rule (``Film(quadrature="vertex")``), at the
    nodes where the kernel data are exact (the Gauss rule sees their P1
    interpolation, a first-order tangent error O(h κ), 1e-5 relative here).
    """
    from tribofx.meshes.obstacles import cap_surface_mesh, plane_surface_mesh

    from tribofx.body import Body
    from tribofx.interfaces import Film, FilmScales, Fluid, Penalty, Quadrature
    from tribofx.obstacles import rigid_surface_mesh
    from tribofx.problem import Problem

    v, (ball, film, problem, *_), _ = light_load
    twin = Body(ball.mesh, ball.facet_tags, ball.names, "3d", ball.materials[None],
                name="twin")
    twin.add_dirichlet("midplane", np.zeros(3))
    twin.add_dirichlet("symmetry", 0.0, component=1)
    R = v.R
    from tribofx.laws import named_viscosity

    counter = (plane_surface_mesh(3, (-R, R), R / 4) if surface.startswith("plane")
               else cap_surface_mesh(10 * R, (0.0, 0.0, -10 * R), (-R, R), 7))
    p0 = Case.scales(v)[1]
    mu = (named_viscosity("barus", v.mu, alpha=0.7 / p0) if surface == "plane-barus"
          else v.mu)
    meshed = Film(twin, "lubricated", rigid_surface_mesh(*counter), Fluid(mu),
                  scales=FilmScales(pressure=float(film.p_c.value), film=film.h_ref,
                                    speed=film.U_ref),
                  cavitation=Penalty(float(film.eps.value)),
                  quadrature=Quadrature("vertex" if surface == "curved" else "gauss", 2),
                  V_counter=film.V_counter.value.copy(), name="meshed")
    rim = lambda X: np.abs(X[2] - cap_height(R, math.radians(v.theta_l))) < 1e-6 * R  # noqa
    meshed.add_pressure_bc(rim)
    twin_problem = Problem([twin, meshed], name="meshed_taylor")
    for a, b in zip(twin_problem.u, problem.u):   # same mesh, same spaces: the solved state
        a.x.array[:] = b.x.array
    meshed.counterpart.offset.value[:] = film.counterpart.offset.value
    b_m, _ = twin_problem.assemble()
    b_a, _ = problem.assemble()
    if surface == "plane":   # flat facets: the kernel reproduces the plane to round-off
        assert abs(b_m.norm() - b_a.norm()) <= 1e-8 * b_a.norm() + 1e-14
    rim_dofs = fem.locate_dofs_geometrical(meshed.Q, rim)
    meshed.p.x.array[:] = np.abs(meshed.p.x.array) + 0.01 * p0
    meshed.p.x.array[rim_dofs] = 0.0
    rng = np.random.default_rng(5 + MPI.COMM_WORLD.rank)
    dirs = []
    for f, c in zip(twin_problem.u, (1e-3, 1e-3, 1e-3 * p0, 1e-3 * p0 / R)):
        d = fem.Function(f.function_space)
        d.x.array[:] = c * rng.uniform(-1, 1, d.x.array.shape)
        d.x.scatter_forward()
        dirs.append(d)
    dirs[2].x.array[rim_dofs] = 0.0
    # ε down to 3e-5 of the state scales: a first-order error of 1e-5 relative shows
    blocks = block_taylor_orders(twin_problem, dirs, eps0=1e-3, n=6)
    for name, (orders, rem, floor) in blocks.items():
        print(surface, "meshed", name, orders, rem, floor)
    inexact = {n for n, (o, r, f) in blocks.items() if not exact_tangent(o, r, f)}
    # per block, every column exact, but on the curved mesh (vertex rule) the trace's may
    # show a first-order remainder of a relative 5e-9 (at the round-off floor, so
    # whether it shows depends on the direction): an open defect
    assert inexact <= ({meshed.u_s.name} if surface == "curved" else set()), blocks


@pytest.mark.mpi
def test_tangential_pressure_gradient_converges_to_the_exact_one(light_load):
    """g (the DG0 unknown of the solved system) against the exact surface gradient on the sphere.

    Analytic field f(x) = c·x + ½ xᵀA x on the ball surface |X − X_c| = R (X_c =
    (0, 0, R)): exact Grad_Γ f(y) = (I − ν⊗ν) ∇f(y), ν = (y − X_c)/R, computed
    here in NumPy (no UFL, no code normal).  The code side: p = P1 interpolant of
    f on the cap Γ_l, and g from the DG0 constraint ∫ (g − Grad_Γ p)·δg dS = 0 of
    the solved system, solved cell by cell (the DG0 mass matrix is diagonal).

    Tolerance, per flat triangle T (vertices x_k on the sphere, centroid x_g, its
    radial projection y_g, unit plane normal N_T, in-plane edges e_1, e_2 = columns
    of E, d_k = x_k − x_g, M₂ = ‖A‖₂ the bound of the Hessian):
    (a) interpolation: ε = g_T − P_T ∇f(x_g) is in-plane with ε·e_k = r_k − r_0,
        r_k the Taylor remainders |r_k| ≤ ½ M₂ |d_k|², so |ε| ≤ ‖β‖/σ_min(E),
        β_k = ½ M₂ (|d_k|² + |d_0|²) — O(h);
    (b) centroid off the sphere: M₂ |x_g − y_g| — O(h²/R);
    (c) flat-cell normal: ‖N_T⊗N_T − ν⊗ν‖ |∇f(y_g)| = sin∠(N_T, ν) |∇f(y_g)| — O(h/R).
    |g_T − Grad_Γ f(y_g)| ≤ (a) + (b) + (c) must hold on every cell (measured
    ≈ 0.6 of the bound on mesh 1; a projection with the wrong normal, e.g. e_z,
    gives 9.5× the bound).
    """
    from tribofx.forms.ehl import tangential_gradient_constraint

    v, (_, film, *_), _ = light_load
    R = v.R
    Xc = np.array([0.0, 0.0, R])
    c = np.array([0.3, -0.7, 0.2])
    A = np.array([[2.0, 0.5, 0.0], [0.5, -1.0, 0.3], [0.0, 0.3, 1.0]]) / R
    M2 = np.linalg.norm(A, 2)

    def grad_f(y):  # (n, 3)
        return c[None, :] + y @ A

    p = fem.Function(film.Q)
    p.interpolate(lambda x: c @ x + 0.5 * np.einsum("in,ij,jn->n", x, A, x))
    dg = ufl.TestFunction(film.G)
    b = fem.assemble_vector(fem.form(tangential_gradient_constraint(
        fem.Function(film.G), p, dg, None, film.dx, film.grad_gamma)))
    m = fem.assemble_vector(fem.form(ufl.dot(ufl.as_vector([1.0, 1.0, 1.0]), dg) * film.dx))
    sub = film.sub
    nc = sub.topology.index_map(sub.topology.dim).size_local
    cell_dofs = film.G.dofmap.list[:nc, 0]
    g = (-b.array.reshape(-1, 3) / m.array.reshape(-1, 3))[cell_dofs]
    X = sub.geometry.x[sub.geometry.dofmaps[0][:nc]]  # (cells, 3 vertices, 3)
    # precondition: the cap nodes lie on the sphere (round-off)
    assert np.abs(np.linalg.norm(X - Xc, axis=2) - R).max() < 1e-10 * R
    xg = X.mean(axis=1)
    yg = Xc + R * (xg - Xc) / np.linalg.norm(xg - Xc, axis=1)[:, None]
    nu = (yg - Xc) / R
    gf = grad_f(yg)
    exact = gf - np.sum(gf * nu, axis=1)[:, None] * nu
    E = np.stack([X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]], axis=2)
    sv = np.linalg.svd(E, compute_uv=False)
    d2 = np.sum((X - xg[:, None, :]) ** 2, axis=2)
    beta = 0.5 * M2 * np.stack([d2[:, 1] + d2[:, 0], d2[:, 2] + d2[:, 0]], axis=1)
    NT = np.cross(E[:, :, 0], E[:, :, 1])
    NT /= np.linalg.norm(NT, axis=1)[:, None]
    sin = np.linalg.norm(np.cross(NT, nu), axis=1)
    bound = (np.linalg.norm(beta, axis=1) / sv[:, 1] + M2 * np.linalg.norm(xg - yg, axis=1)
             + sin * np.linalg.norm(gf, axis=1))
    err = np.linalg.norm(g - exact, axis=1)
    comm = MPI.COMM_WORLD
    worst = comm.allreduce(float(np.max(err / bound, initial=0.0)), op=MPI.MAX)
    rel = np.concatenate(comm.allgather(bound / np.linalg.norm(exact, axis=1)))
    print(f"max error/bound {worst:.3f}; bound/|Grad_Γ f|: median {np.median(rel):.3f}, "
          f"max {rel.max():.3f}")
    assert worst <= 1.0
    # the bound has resolving power: a few % of the gradient on most cells
    assert np.median(rel) < 0.1
    # g lies in the plane of its cell: |g·N_T| at round-off, ≤ 100 ε κ(E) |∇f| per cell
    kappa = sv[:, 0] / sv[:, 1]
    gn = np.abs(np.sum(g * NT, axis=1))
    assert np.all(gn <= 100 * np.finfo(float).eps * kappa * np.linalg.norm(gf, axis=1))


def _film_imbalance(film, model):
    """The x-force the film's thin-film equilibrium does not balance, two parts (N).

    flank: −∫ [(μ/h) v_rel + (h/2) grad_S p]_x (j − ds_S/dS) dS, the shear where the
    layer's area differs from that of S (the cap's steep flanks; j = 1 in the linear
    model); slope (linear model only): ∫ p ∂_x(ν·u) ds_S, the pressure on the slope
    of the displacement, which the linear model's traction −pN leaves out.
    """
    kb, u, msh = film.kin_bulk, film.body.u, film.body.mesh
    Id, N = ufl.Identity(3), ufl.FacetNormal(msh)
    nJ = ufl.det(Id + ufl.grad(u)) * ufl.inv(Id + ufl.grad(u)).T * N
    j = ufl.sqrt(ufl.dot(nJ, nJ)) if model == "finite" else 1
    shear = ((fem.Constant(msh, film.mu) / kb.h) * (kb.v_layer - kb.v_counter)
             + (kb.h / 2) * ufl.inv(kb.A).T * film.g)
    terms = [-shear[0] * (j - kb.stretch) * film.ds]
    if model == "linear":
        grad_gamma = (Id - ufl.outer(N, N)) * ufl.grad(u).T * kb.nu    # Grad_Γ(ν·u)
        terms.append(film.p * (ufl.inv(kb.A).T * grad_gamma)[0] * kb.stretch * film.ds)
    return [msh.comm.allreduce(fem.assemble_scalar(fem.form(t, entity_maps=[film.emap])),
                               op=MPI.SUM) for t in terms]


@pytest.mark.mpi
def test_film_force_on_ball_and_plane_balance():
    """Friction on the ball and on the plane: the film's x-force balance, both models.

    The film's momentum balance integrated over the contact (Reynolds' velocity
    profile: the shear at the two walls differs by h grad_S p, and ∫ h grad_S p
    ds_S = −∫ p grad_S h ds_S with p = 0 on the rim and no x-normal on the symmetry
    line): F_ball,x + F_plane,x equals the flank shear, plus in the linear model
    the pressure on the displacement slope (:func:`_film_imbalance`).  On the
    discrete solution this is the divergence theorem for p h (P1 times the
    displacement's trace, continuous) under a quadrature exact for the
    polynomial integrands (degree 4: p × cofactor of F); what remains are the
    trace and gradient constraints, solved to Newton's tolerance (≤ 1e-10 of
    their scales): 1e-8 of the force.  Checks Film.counter_force (signs of the
    Couette and Poiseuille parts at the other wall, the area of S) against
    Film.force.
    """
    for model in ("finite", "linear"):
        v = values(W=3.0, steps=1, mesh=0, model=model)
        run = Case.build(v)
        Case.load_sweep(run, v, lambda W, its: None)
        film = run.film
        f_ball, f_plane = film.force()[0], film.counter_force()[0]
        parts = _film_imbalance(film, model)
        print(model, "x-force on the ball", f_ball, "on the plane", f_plane, "flank, slope",
              parts)
        assert f_ball > 0 > f_plane      # the plane (moving in +x) drags the ball along
        assert abs(f_ball + f_plane - sum(parts)) <= 1e-8 * abs(f_ball)


def test_finite_and_linear_agree_as_load_vanishes():
    """Relative difference of h_c (finite vs linear) shrinks with the load."""
    loads = (0.5, 4.0)
    d = []
    for W in loads:
        # (the displacement solid with Gauss points: on mesh 0, a/4, the mixed solid
        # with the vertex rule stalls at 4 N, a node's film reaching h ≤ 0)
        m = {model: _solve(values(W=W, steps=1, model=model, mesh=0,
                                  formulation="displacement", quadrature="gauss"))[1][-1]
             for model in ("finite", "linear")}
        d.append(abs(m["finite"]["h_central"] / m["linear"]["h_central"] - 1))
        print(W, {k: (x["h_central"], x["p_max"]) for k, x in m.items()})
    print("relative difference of h_c", d)
    # the models differ at higher order in the strain (a/R ≈ 0.11 at 0.5 N, 0.23 at 4 N),
    # meshed alike relative to the contact radius: the difference must shrink with W
    assert d[0] < d[1]
    assert d[0] < 0.05


def _cli(tmp_path, nproc, *sets):
    out = tmp_path / f"ball-{nproc}"
    cmd = [sys.executable, "-m", "tribofx.cli", "run", "ehl-ball", "--out", str(out),
           "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    if nproc > 1:
        exe = (shutil.which("mpiexec", path=os.path.dirname(sys.executable))
               or shutil.which("mpiexec"))
        cmd = [exe, "-n", str(nproc)] + cmd
    env = dict(os.environ, UCX_TLS="self,sm,tcp")
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)
    assert p.returncode == 0, p.stderr
    return json.loads((out / "summary.json").read_text())


@pytest.mark.mpi
@pytest.mark.mpiexec
def test_serial_equals_two_processes(tmp_path):
    if MPI.COMM_WORLD.size > 1:
        pytest.skip("spawns its own serial and 2-process runs")
    sets = ("W=1", "steps=1", "mesh=0")
    s1 = _cli(tmp_path, 1, *sets)
    s2 = _cli(tmp_path, 2, *sets)
    assert s1["status"] == "ok" and s2["status"] == "ok"
    assert s2["mpi_size"] == 2 and s1["num_dofs"] == s2["num_dofs"]
    for key in ("h_min", "h_central", "p_max", "friction_coefficient"):
        v1, v2 = s1["results"][key]["value"], s2["results"][key]["value"]
        print(key, v1, v2)
        # same discrete problem; the secant stops at |W − W*| ≤ 1e-4 W* from
        # trials that depend on partition round-off only: 1e-4 relative
        assert v2 == pytest.approx(v1, rel=1e-4)


def _pressure_radius(run):
    """Pressure-weighted contact radius a_p = (5/2 ∫ p r² dS / ∫ p dS)^{1/2} (mm, all ranks).

    r = in-plane distance of the current cap point from the contact axis; for
    the Hertz pressure p0 (1 − r²/a²)^{1/2} on a flat disc a_p = a exactly.
    """
    film = run.film
    x = ufl.SpatialCoordinate(film.sub) + film.u_s
    r2 = x[0] ** 2 + x[1] ** 2
    num, den = (MPI.COMM_WORLD.allreduce(fem.assemble_scalar(fem.form(f * film.dx)),
                                         op=MPI.SUM) for f in (film.p * r2, film.p))
    return math.sqrt(2.5 * num / den)


def _equilibrium_bound(run, W):
    """Bound (N) on |mid-plane reaction + film force W| of a solved state.

    The z rows of the momentum residual of the half ball sum to ∫ P : Grad e_z (= 0)
    − F_z(film); the mid-plane rows (held, not on the lubricated cap) carry the
    internal force, i.e. half the reaction, so reaction + W = −2 Σ_free b_z and,
    by Cauchy–Schwarz, |reaction + W| ≤ 2 √n_z ‖b‖ (‖b‖ the residual norm of the
    coupled Newton system at the solved state, n_z the number of z rows), plus
    assembly round-off (1e-12 W).
    """
    ball, problem = run.ball, run.problem
    b, _ = problem.assemble()
    n_z = ball.V.dofmap.index_map.size_global
    return 2 * math.sqrt(n_z) * b.norm() + 1e-12 * abs(W)


def _mid_plane_reaction(run):
    """Vertical reaction (N, whole ball) of the held mid-plane: the solid's own rows at its dofs
    (:meth:`tribofx.body.Body.reaction`, the half model's times 2)."""
    return 2.0 * run.ball.reaction("midplane", Case.Z)


@pytest.mark.slow
def test_large_load_40N():
    """W = 40 N (Hertz a ≈ R/2): displacement-controlled thick-film path, finite vs linear.

    μU = 3 N/m (U = 3e5 mm/s), mesh 0, cap θ_l = 55°.  Checks: global
    equilibrium, contact radius against Hertz, and that the finite/linear
    difference is much larger than at 4 N (the chapter: 10–15 % at 40 N).
    """
    res = {}
    for W in (4.0, 40.0):
        for model in ("finite", "linear"):
            # (the displacement solid with Gauss points, on which these checks were
            # measured)
            v = values(W=W, steps=1, mesh=0, U=3e5, model=model,
                       theta_l=55.0 if W > 10 else 40.0, formulation="displacement",
                       quadrature="gauss")
            run, out = _solve(v)
            m = out[-1]
            m["a_p"] = _pressure_radius(run)
            m["reaction"] = _mid_plane_reaction(run)
            m["bound"] = _equilibrium_bound(run, m["W"])
            res[W, model] = m
            print(W, model, {k: m[k] for k in ("W", "reaction", "h_central", "h_min", "p_max",
                                               "a_p", "friction_coefficient", "iterations")})
    v = values(W=40.0, theta_l=55.0)
    a_h = hertz(40.0, v.R, v.E, v.nu).a
    for model in ("finite", "linear"):
        m = res[40.0, model]
        # global equilibrium of the solved state: the mid-plane reaction balances the
        # film force within the Newton residual bound (see _equilibrium_bound)
        assert abs(m["reaction"] + m["W"]) <= m["bound"]
        assert m["h_min"] > 0
    a_f = res[40.0, "finite"]["a_p"]
    print(f"pressure radius {a_f:.3f} mm, Hertz a = {a_h:.3f} mm")
    # EHL pressure is near-Hertzian (inlet and outlet spike shift it by a few %);
    # finite strain at a/R ≈ 0.5 (the Hertz half-space theory is small-strain) and
    # element size a/4: 15 %
    assert abs(a_f / a_h - 1) < 0.15

    def rel(W, key):
        return abs(res[W, "linear"][key] / res[W, "finite"][key] - 1)

    # the geometrically linear model overpredicts p_max and underpredicts h_min
    # (chapter §8.3); the difference grows with the load
    assert res[40.0, "linear"]["p_max"] > res[40.0, "finite"]["p_max"]
    assert res[40.0, "linear"]["h_min"] < res[40.0, "finite"]["h_min"]
    for key in ("h_central", "h_min", "p_max"):
        print(key, "finite vs linear at 4 N", rel(4.0, key), "at 40 N", rel(40.0, key))
        assert rel(40.0, key) > rel(4.0, key)
    # chapter: 10–15 % at 40 N; here h_min by more than 5 %
    assert rel(40.0, "h_min") > 0.05


def test_edge_refine_halves_the_cap_elements_along_the_contact_edge():
    """``edge_refine=1``: cap triangles within 0.1 a of the circle ρ = 0.95 a have size h/2.

    Reference: the size field asked of gmsh (h = a/4 near the contact at mesh 0,
    h/2 in the band).  gmsh meets a size field to within its adaptation, about
    ±25 % per edge on average over a band of many triangles (measured here on the
    unrefined cap: the mean longest edge in the band and inside the contact agree
    to that), so the ratio of the band's mean to the inner zone's must be 0.5
    within a factor 1.3 either way, and near 1 without the band.
    """
    from dolfinx import mesh as dmesh
    from tribofx.meshes.ball import LUBRICATED

    ratios = {}
    for level in (0, 1):
        v = values(W=10.0, mesh=0, edge_refine=level)
        a = Case.hertz_contact(v).a
        ball = Case.build(v).ball
        msh, facets = ball.mesh, ball.facet_tags.find(LUBRICATED)
        msh.topology.create_connectivity(2, 3)
        nodes = dmesh.entities_to_geometry(msh, 2, facets, False)
        x = msh.geometry.x[nodes]                                  # (facets, 3, 3)
        longest = np.max(np.linalg.norm(x - np.roll(x, 1, axis=1), axis=2), axis=1)
        rho = np.hypot(x[:, :, 0].mean(axis=1), x[:, :, 1].mean(axis=1))
        comm = msh.comm

        def mean(sel):
            return (comm.allreduce(float(longest[sel].sum()), op=MPI.SUM)
                    / comm.allreduce(int(sel.sum()), op=MPI.SUM))

        band = np.abs(rho - 0.95 * a) < 0.08 * a
        ratios[level] = mean(band) / mean((rho > 0.3 * a) & (rho < 0.7 * a))
    print("band / inner mean longest edge:", ratios)
    assert 1 / 1.3 < ratios[0] < 1.3
    assert 0.5 / 1.3 < ratios[1] < 0.5 * 1.3


def test_outlet_rule_of_a_smaller_load_reads_the_mesh():
    """:func:`resolves_outlet` against the elements gmsh built along each load's edge.

    The chapter's point in three steps (40 N at 0.078 N/m, the default mixed solid:
    ``mesh=1 edge_refine=2``, made for 40 N): the mean edge of the cap triangles
    within 0.05 a of the circle 0.95 a(W_k), over the outlet width ℓ(W_k, U), is
    above the rule's 2 for 13.3 N (outside the refined band) and below it at 26.7 N
    (the band's flank) and 40 N, and :func:`resolves_outlet` says so (13.3 N is then
    recorded on the thick film, not marched down to U).  gmsh meets its size field
    within about ±25 % per edge on average over a band
    (:func:`test_edge_refine_halves_the_cap_elements_along_the_contact_edge`): each
    measured ratio must lie beyond 2 by that factor, 1.3, on the side the rule gives,
    or the rule's size model is wrong.
    """
    from dolfinx import mesh as dmesh
    from tribofx.meshes.ball import LUBRICATED

    v = values(W=40.0, U=7800.0, theta_l=60.0)
    assert Case.mesh_levels(v)[:2] == (1, 2)
    ball = Case.build(v).ball
    msh, facets = ball.mesh, ball.facet_tags.find(LUBRICATED)
    nodes = dmesh.entities_to_geometry(msh, 2, facets, False)
    x = msh.geometry.x[nodes]                                      # (facets, 3, 3)
    edges = np.linalg.norm(x - np.roll(x, 1, axis=1), axis=2).mean(axis=1)
    rho = np.hypot(x[:, :, 0].mean(axis=1), x[:, :, 1].mean(axis=1))
    comm = msh.comm
    for W in (40.0 / 3, 80.0 / 3, 40.0):
        a = Case.hertz_contact(v, W).a
        band = np.abs(rho - 0.95 * a) < 0.05 * Case.hertz_contact(v).a
        mean = (comm.allreduce(float(edges[band].sum()), op=MPI.SUM)
                / comm.allreduce(int(band.sum()), op=MPI.SUM))
        ratio = mean / Case.outlet_width(v.replace(W=W))
        print(f"W = {W:.1f} N: edge/ℓ = {ratio:.2f}")
        if Case.resolves_outlet(v, W):
            assert ratio < Case.MAX_EDGE_RATIO / 1.3, W
        else:
            assert ratio > Case.MAX_EDGE_RATIO * 1.3, W
    assert [Case.resolves_outlet(v, W) for W in (40.0 / 3, 80.0 / 3, 40.0)] == \
        [False, True, True]


def test_film_oscillation_warns_above_its_tolerance(tmp_path):
    """A centre-line film zig-zagging ±δ node to node has film_oscillation δ
    (exact for a zig-zag about a constant, :func:`oscillation_indicator`); the run
    warns for δ above ``FILM_OSCILLATION_TOL`` only.  A journal written before the
    measure existed gets it from the profile it kept."""
    from tribofx.output import RunRecord

    x = np.linspace(-1.0, 1.0, 40)   # an even number of nodes where p > p_max/2
    p = np.maximum(1 - x**2, 0.0)
    for delta, warns in ((0.1, True), (0.02, False)):
        h = 0.01 * (1 + delta * (-1.0) ** np.arange(x.size))
        step = {k: 0.0 for k in Case.UNITS if k not in ("U", "mu_U", "film_oscillation")}
        step["profile"] = {"h_axis": h, "p_axis": p}     # an older journal: no measure
        record = RunRecord("ehl-ball", {}, {}, tmp_path, MPI.COMM_SELF)
        Case._report([step], [], {"mu": 1e-8}, record, "full_")
        osc = record.data["results"]["full_film_oscillation"]["value"]
        assert osc == pytest.approx(delta, rel=1e-12)
        assert bool(record.data.get("warnings")) == warns
        if warns:
            assert record.data["warnings"][0].startswith("full: film zig-zags")


def test_mesh_chosen_from_load_and_speed():
    """``mesh``/``edge_refine`` by default from W and U (tribofx.cases.ehl_ball).

    Against the measured points of the module docstring: the default 10 N at 0.1 N/m
    keeps mesh=1 (resolved there, h_edge/ℓ = 1.6); the chapter's 40 N at 0.078 N/m gets
    mesh=1 edge_refine=2 for the mixed solid (the default; measured smooth there,
    film_oscillation 0.017, h_edge/ℓ = 1.03) and mesh=2 edge_refine=1 for the
    displacement solid (the same a/32 along the edge, the whole Hertzian zone at a/16
    against its locking; on mesh=1 edge_refine=2 it dipped to 2.4 µm); with mesh=1 set,
    edge_refine=2; both set, they are kept and flagged unresolved; a point no built mesh
    resolves (40 N at 10 mm/s: a film of 0.24 µm) is refused at validation with one
    line, before any mesh is built."""
    from tribofx.cases.ehl_ball import edge_size, mesh_levels, outlet_width
    from tribofx.params import InputError

    default = values()
    assert mesh_levels(default) == (1, 0, True)
    chapter = values(W=40.0, U=7800.0, theta_l=60.0)
    Case.validate(chapter)
    assert mesh_levels(chapter) == (1, 2, True)
    assert mesh_levels(values(W=40.0, U=7800.0, theta_l=60.0,
                              formulation="displacement")) == (2, 1, True)
    assert edge_size(chapter, 2, 1) / outlet_width(chapter) == pytest.approx(1.03, abs=0.01)
    assert mesh_levels(values(W=40.0, U=7800.0, theta_l=60.0, mesh=1)) == (1, 2, True)
    assert mesh_levels(values(W=40.0, U=7800.0, theta_l=60.0, mesh=1, edge_refine=0)) == \
        (1, 0, False)
    with pytest.raises(InputError, match="no built mesh resolves"):
        Case.validate(values(W=40.0, U=10.0, theta_l=60.0))


@pytest.mark.mpi
@pytest.mark.slow
def test_chapter_point_40N_muU_0078():
    """The chapter's severe point: W = 40 N at μU = 0.078 N/m (Figs. 25–26) on 29k unknowns.

    The bare command's run (the defaults; three load steps, 13.3 N recorded on the
    thick film: :func:`test_outlet_rule_of_a_smaller_load_reads_the_mesh`).
    The mixed (u, p) solid (no locking) and the vertex rule of the film
    (``quadrature=vertex``: h at the nodes, where the P1 surface lies on the
    deformed ball; a Gauss point sees the chord, up to h_e²/(8R) ≈ 6 µm below
    it at h_e = 0.8 mm, a third of the 15 µm film) on ``mesh=1 edge_refine=2``
    (element size a/8, a/32 in the band along the contact edge), cap θ_l = 60°.
    (The displacement solid with Gauss points needs 64k unknowns for a zig-zag of
    0.062 and about 15 min: ``benchmarks/chapter_ehl_ball.py``.)  Checks:

    * the load is reached, read from the fields: the mid-plane reaction (the
      solid's own rows, :meth:`tribofx.body.Body.reaction`) balances the film
      force within the Newton residual bound (:func:`_equilibrium_bound`) and
      carries 40 N within that bound plus the load controller's stopping
      tolerance (1e-4 W);
    * ``film_oscillation`` ≤ 0.02 (the target of a smooth film);
    * the chapter's statement that at high load and low speed the minimum film
      lies in two side lobes, off the symmetry axis: |y_h_min| > a/2 (the lobes
      sit at the edge of the contact, |y| ≈ 0.9 a);
    * the pressure radius against Hertz within 15 %, as in
      :func:`test_large_load_40N`;
    * the central film against Hamrock–Dowson's isoviscous-elastic fit (16.8 µm):
      their fit holds to a few per cent within its data and the soft ball at
      a/R ≈ 0.5 is beyond its small-strain range, so within 15 %.
    """
    from tribofx import solvers

    v = values(W=40.0, U=7800.0, theta_l=60.0)
    assert (v.steps, v.formulation, Case.film_rule(v), Case.mesh_levels(v)) == \
        (3, "mixed", "vertex", (1, 2, True))
    with solvers.run_settings("direct"):
        run, out = _solve(v)
    m = out[-1]
    a_h = hertz(40.0, v.R, v.E, v.nu).a
    m["a_p"], m["reaction"] = _pressure_radius(run), _mid_plane_reaction(run)
    print({k: m[k] for k in ("W", "reaction", "h_central", "h_min", "x_h_min", "y_h_min",
                             "p_max", "a_p", "friction_coefficient", "film_oscillation")})
    bound = _equilibrium_bound(run, m["W"])
    assert abs(m["reaction"] + m["W"]) <= bound
    assert abs(m["reaction"] + 40.0) <= bound + 1e-4 * 40.0
    assert m["h_min"] > 0
    assert m["film_oscillation"] <= 0.02
    assert abs(m["y_h_min"]) > 0.5 * a_h
    assert abs(m["a_p"] / a_h - 1) < 0.15
    h_c = hamrock_dowson(40.0, v.mu, v.U, v.R, Case.e_star(v))[0]
    assert abs(m["h_central"] / h_c - 1) < 0.15

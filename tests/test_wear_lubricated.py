"""Wear under mixed lubrication: the asperities wear the body, the film does not.

References: Archard's law for a flat punch under a uniform pressure (the
chapter's dry pin, §4.4: depth k P V t), the worn-volume identity of the shape
law (28), and Archard's k V ∫ p_a ds summed in NumPy from the nodal gaps.
"""

import numpy as np
import pytest
from dolfinx import fem
from mpi4py import MPI
from tribofx.forms import mixed
from tribofx.forms.hyperelastic import lame_parameters
from tribofx.meshes.hertz import NAMES, hertz_body

from tribofx.body import Body
from tribofx.cases import wear_lubricated
from tribofx.interfaces import Film, FilmScales, Fluid, Wear
from tribofx.obstacles import rigid_plane
from tribofx.output import RunRecord
from tribofx.params import resolve
from tribofx.references_mixed import flat_punch_separation
from tribofx.roughness import Roughness, greenwood_tripp
from tribofx.stepper import Stepper


@pytest.mark.mpi
def test_rough_flat_punch_wears_by_archard():
    """A block pressed on a rough plane sliding at V: the asperities alone carry and wear it.

    The block ([0, B]², plane strain, symmetry at x = 0) carries the dead uniform
    traction P towards the plane, which slides at V; the top face stays flat and
    parallel, so the film has no wedge and no pressure, its shear is switched off
    (μ → 0), and the asperities carry P B.  Wear by the asperity pressure p_a (per
    current length b) times j = b/B is k P V per unit initial length, uniform: after t the face has
    receded by k P V t and the worn area is k P V t B — Archard's law of the dry
    pin (§4.4).  Backward Euler is exact for a constant rate; the tolerance is the
    ζ rows' Newton tolerance (1e-12 of the body size per node).  A film pressure
    driving the wear instead would give no wear at all.
    """
    B, E, nu, P, sigma, KE, V, k, dt = 2.0, 10.0, 0.3, 0.02, 1e-3, 0.05, 1.0, 1e-2, 1.0
    msh, ft = hertz_body(2, B, B / 8, B / 8, B, MPI.COMM_WORLD, block=B)
    names = {"lubricated" if k == "contact" else k: t for k, t in NAMES.items()
             if k != "symmetry_y"}
    mu_s, lm = lame_parameters(E, nu)
    body = Body(msh, ft, names, "plane_strain", ("neo-hookean", {"mu": mu_s, "lmbda": lm}),
                name="block", shape=True, aux=(E, 0.0))   # ν_aux = 0: w stays vertical
    body.add_dirichlet("symmetry_x", 0.0, component=0)
    body.add_traction("loaded", fem.Constant(msh, np.array([0.0, P])))
    body.add_shape_dirichlet("symmetry_x", 0)
    for i in range(2):
        body.add_shape_dirichlet("loaded", i)
    h0 = flat_punch_separation(P, sigma, KE)
    # the film "switched off" (μ = 1e-15 MPa·s: its shear μV/h ≈ 3e-10 P; at 1e-12 it
    # shears the block enough to tilt the face, p_a varying by 3e-7)
    film = Film(body, "lubricated", rigid_plane([0.0, h0], [0.0, -1.0]), Fluid(1e-15),
                scales=FilmScales(pressure=P, film=sigma, speed=V),
                roughness=Roughness(sigma, asperity=greenwood_tripp(KE, sigma), flow=None),
                V_counter=(V, 0.0))
    film.add_pressure_bc()
    wear = Wear(film, k, speed=V)
    stepper = Stepper([body, film, wear], wear, name="punch_wear")
    with pytest.raises(ValueError, match="writes no checkpoint"):   # (one line, no crash)
        stepper.load_checkpoint()
    stepper.problem.solve()           # the unworn punch (dt = 0: no wear)
    for _ in range(3):
        stepper.step(dt)
    t = 3 * dt
    d = wear.gather_shape(root_only=False)
    depth = k * P * V * t
    assert np.allclose(d["depth"], depth, rtol=1e-8, atol=0), d["depth"] / depth - 1
    assert wear.worn_volume() == pytest.approx(k * P * V * t * B, rel=1e-8)
    assert np.max(np.abs(film.p.x.array), initial=0.0) < 1e-10 * P      # the film: nothing


def _run(comm=MPI.COMM_WORLD, **kw):
    v = resolve(wear_lubricated.Params, {"T": 1440.0, "dt": 720.0, **kw})
    rec = RunRecord(wear_lubricated.name, {}, {}, ".", comm)
    run = wear_lubricated.run(v, rec, comm=comm)
    return v, run, {k: np.asarray(r["value"]) for k, r in rec.data["results"].items()
                    if k not in ("final_film", "worn_profiles")}


@pytest.mark.slow
def test_running_in_wears_by_the_asperity_load_and_builds_the_film():
    """Two implicit steps of the default running-in (V = 1 mm/s, λ ≈ 0.13 at the start).

    * Worn area = Σ Δt ∫ Ẇ dS (the shape law (28) sweeps exactly the volume of the
      rate, to its Newton tolerance: 1e-12 of R per node, relative 1e-6 here).
    * ∫ Ẇ dS is Archard's k V ∫ p_a ds over the current surface: with the vertex rule
      of the wear rows and j = ds/dŜ constant per P1 facet, it is k V times the
      trapezoidal sum of p_a(h_i) over the current nodal positions x_i, recomputed
      here in NumPy from the nodal gaps (p_a by the Greenwood–Tripp fit): equal to
      round-off (1e-10).
    * Running-in: the asperity load and the friction fall, the film's share of W
      and h_min rise at every step (the surface conforms).

    Slow (14 s, ``--runslow``): the default suite checks the same on the same model
    in ``demos/demo_mixed_lubrication.py`` (its worn area against k V ∫ p_a ds by
    hand, the trends), and the case's run under 2 ranks below.
    """
    v, run, r = _run()
    assert len(r["time"]) == 3
    swept = np.cumsum(r["dt"] * r["wear_rate_integral"])
    assert np.allclose(r["wear_volume"], swept, rtol=1e-6, atol=1e-12), (r["wear_volume"], swept)
    prof = run.film.profile(everywhere=True)
    A, Hc, n = mixed.GT_FIT
    KE = run.film.roughness.asperity.parameters["KE"]
    p_a = KE * A * np.maximum(Hc - prof["h"] / v.sigma, 0.0) ** n
    ds = np.linalg.norm(np.diff(prof["x"], axis=0), axis=1)
    by_hand = v.k * v.V * np.sum(ds * (p_a[1:] + p_a[:-1]) / 2)
    assert run.wear.wear_rate_integral() == pytest.approx(by_hand, rel=1e-10)
    assert r["wear_rate_integral"][-1] == pytest.approx(by_hand, rel=1e-10)
    assert np.all(np.diff(r["asperity_load"]) < 0)
    assert np.all(np.diff(r["friction_coefficient"]) < 0)
    assert np.all(np.diff(r["film_load_fraction"]) > 0)
    assert np.all(np.diff(r["h_min"]) > 0)


@pytest.mark.mpi
def test_running_in_parallel_matches_serial():
    """One step of the running-in at V = 10 mm/s (the asperities carry 5 %): 2 ranks = 1.

    The load is held by a secant to 1e-7 in log W: the states agree to ~1e-6.
    """
    if MPI.COMM_WORLD.size < 2:
        pytest.skip("run under mpiexec -n 2")
    out = []
    for comm in (MPI.COMM_SELF, MPI.COMM_WORLD):
        _, _, r = _run(comm, T=720.0, V=10.0)
        out.append(np.r_[r["wear_volume"], r["film_load_fraction"], r["friction_coefficient"]])
    assert np.allclose(out[0], out[1], rtol=1e-5, atol=1e-12), out

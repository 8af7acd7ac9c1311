"""The Stribeck ball (``stribeck geometry=ball``): the mixed film in 3D.

The same Film and Roughness as the cylinder's (tests/test_mixed_lubrication.py),
on the quarter ball of ``ehl-ball``: its full-film end is the smooth film, its
mixed film's tangent is exact, its curve has the three regimes, and 2 ranks = 1.
References: the smooth film of the chapter (Roughness off), finite differences
of the residual, the regimes' definitions.
"""

import math

import numpy as np
import pytest
from mpi4py import MPI

from tribofx.cases import stribeck as stribeck_case
from tribofx.output import RunRecord
from tribofx.params import resolve
from tribofx.testing import block_taylor_orders, exact_tangent, penalty_film_directions


def ball(rough=True, comm=MPI.COMM_WORLD, **over):
    """Run ``stribeck geometry=ball`` with ``over``; return (run, per-speed results)."""
    v = resolve(stribeck_case.Params, {"geometry": "ball",
                                      **{k: str(x) for k, x in over.items()}})
    stribeck_case.validate(v)
    rec = RunRecord(stribeck_case.name, {}, {}, ".", comm)
    run = stribeck_case.run(v, rec, rough=rough, comm=comm)
    return run, {k: r["value"] for k, r in rec.data["results"].items()}


def test_ball_full_film_end_is_the_smooth_ball():
    """At U = 1000 mm/s (λ ≈ 9) the rough ball's film is the smooth one.

    As for the cylinder, the flux differs from the smooth film's by 1 − φ_x(H) =
    0.9e^{−0.56H} in its Poiseuille part and by the shear flow σΦ_s(H)/h =
    1.126e^{−0.25H}/H against the Couette part, largest where the film is thinnest
    (H = h_min/σ ≈ 6.6: 2.2e-2 and 3.3e-2); h_T/h − 1 < 1e-12.  Tolerance: their sum at
    h_min, on h_central, h_min, p_max and the friction; the asperities (zero above
    H = 4) carry nothing.  One load step from the Hertz start (14 Newton iterations).
    """
    run, rough = ball(speeds="1000", steps=1)
    _, smooth = ball(rough=False, speeds="1000", steps=1)
    lam = rough["h_min"][0] / 1e-3
    tol = 0.9 * math.exp(-0.56 * lam) + 1.126 * math.exp(-0.25 * lam) / lam
    print({k: (rough[k][0], smooth[k][0]) for k in rough}, tol)
    for k in ("h_central", "h_min", "p_max", "friction_coefficient"):
        assert abs(rough[k][0] / smooth[k][0] - 1) < tol, (k, rough[k], smooth[k], tol)
    assert rough["film_load_fraction"][0] == pytest.approx(1.0, abs=1e-12)
    # the supports carry W: the midplane's reaction from the ball's own rows (not the
    # film force the hold controls), times the 2 copies of the modelled part, is
    # W = 0.5 N within the hold's tolerance (1e-6 W) and the momentum rows' residual
    # summed over the body's dofs (each below atol)
    body = run.body
    bound = 1e-6 * 0.5 + run.copies * 3 * body.V.dofmap.index_map.size_global * \
        body.tolerances()[body.u].atol
    assert abs(-run.copies * body.reaction("midplane", 2) - 0.5) < bound


def test_ball_mixed_film_tangent_is_exact():
    """Taylor test of the 3D mixed film at U = 10 mm/s (λ ≈ 0.36, asperities ≈ 9 % of W).

    The pressure is perturbed only where p > 0.01 p_max (the penalty's kink at p = 0).
    """
    run, res = ball(speeds="10", steps=1)
    assert 0.8 < res["film_load_fraction"][0] < 0.99 and res["lambda_ratio"][0] < 1
    prob = run.problem
    dirs = penalty_film_directions(prob, run.film.p, 5)
    for name, (orders, rem, floor) in block_taylor_orders(prob, dirs, eps0=1.0).items():
        assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)


@pytest.mark.slow
@pytest.mark.mpi
def test_ball_parallel_matches_serial():
    """The 3D mixed film at U = 10 mm/s: 2 ranks = 1 (the load secant stops within 1e-7).

    Slow (45 s on 2 ranks, ``--runslow``): the default suite runs the ball at 10 mm/s on
    2 ranks in ``demos/demo_mixed_lubrication.py`` (its checks), and the cylinder's
    mixed film against serial in ``tests/test_wear_lubricated.py``.
    """
    if MPI.COMM_WORLD.size < 2:
        pytest.skip("run under mpiexec -n 2")
    out = []
    for comm in (MPI.COMM_SELF, MPI.COMM_WORLD):
        _, r = ball(comm=comm, speeds="10", steps=1)
        out.append(np.array([r[k][0] for k in ("friction_coefficient", "film_load_fraction",
                                                "h_central", "p_max")]))
    # the secant stops within 1e-7 of log W: the states agree to ~1e-6
    assert np.allclose(out[0], out[1], rtol=1e-5, atol=0), out


@pytest.mark.slow
def test_ball_stribeck_curve_has_its_three_regimes():
    """Full film, mixed, towards boundary over four decades (1000 → 0.1 mm/s).

    The criteria of the cylinder's curve (tests/test_mixed_lubrication.py): in
    the full film (λ > 3) the film carries W and the friction falls with U; the
    minimum friction lies in the mixed regime (0.5 < film share < 1); below it the
    friction rises at every step as the asperities take over, below μ_b = 0.1.
    Slow (≈ 2 min, ``--runslow``).
    """
    _, r = ball(speeds="1000,300,100,30,10,3,1,0.3,0.1")
    lam, f, frac = (np.array(r[k]) for k in ("lambda_ratio", "friction_coefficient",
                                             "film_load_fraction"))
    print(np.c_[r["speeds"], lam, f, frac])
    full = lam > 3
    assert full.sum() >= 2 and np.all(np.diff(f[full]) < 0), (lam, f)
    assert np.all(frac[full] > 1 - 1e-3), frac
    i = int(np.argmin(f))
    assert 0.5 < frac[i] < 1.0, (frac, f)
    assert np.all(np.diff(f[i:]) > 0), f
    assert frac[-1] < 0.6
    assert np.all(f < 0.1)

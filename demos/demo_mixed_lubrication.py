# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # Mixed lubrication: the Stribeck curve and the running-in of a soft cylinder (and a ball)
#
# The chapter treats dry wear (§3–5) and full-film soft-EHL (§6–8) apart and
# leaves roughness "not discussed".  Between them lies mixed lubrication: the
# film carries part of the load, the asperities of the rough surfaces the rest,
# and the asperities wear the surface, which changes the film.  This demo
# illustrates how to:
#
# * give the chapter's ``Film`` a ``Roughness``: the average-flow Reynolds
#   equation (Patir & Cheng: pressure and shear flow factors φ_x(H), φ_s(H) of
#   H = h/σ, written on the expected gap h_T) and the Greenwood–Tripp asperity
#   pressure p_a(h) = K E* F_{5/2}(h/σ) with a boundary friction μ_b p_a — each a
#   law (a function) that a researcher replaces in one place;
# * march the sliding speed down from a full film to the mixed regime and read
#   the Stribeck curve (friction coefficient and the film's share of W);
# * put the same film on a ball (3D quarter model, ``geometry=ball``);
# * let the asperities wear the cylinder (Archard, Ẇ = k p_a ‖v_s‖: the film does
#   not wear) with the core's finite shape update (``Wear`` on the film, the
#   ``Stepper`` of the slow time) while W is held by the plane's approach.
#
# The film rows (average flow, eq. 49 with φ_x, h_T and the shear flow):
#
# $$ \int_S \Big(\frac{\phi_x h_T^3}{12\mu}\nabla_S p - h_T\bar v
#    - \tfrac{\sigma}{2} s\,\phi_s\,\Delta v\Big)\cdot\nabla_S\delta p\,ds
#    + \int \varepsilon^{-1}\min(p,0)\,\delta p = 0, $$
#
# the traction on the cylinder −(p + p_a) n + the fluid shear + μ_b p_a, and the
# load W = ∫ (p + p_a).  The wear rows are the chapter's (28) with the rate
# k p_a j ‖v_s‖ per unit initial area.
#
# ## Changing it
#
#     tribofx run stribeck --set sigma=5e-4 --set speeds=1000,100,10,1
#     tribofx run wear-lubricated --set V=0.3 --set k=1e-6 --set T=36000 --set dt=3600
#
# and in code ``Roughness(sigma, asperity=Law(my_pressure, ...), flow=(phi_x, phi_s))``.

# +
import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
from mpi4py import MPI
from tribofx.forms.mixed import GT_FIT

from tribofx.cases import rough_contact
from tribofx.cases import stribeck as stribeck_case
from tribofx.continuation import ConstantParameter, Continuation
from tribofx.hold import Hold
from tribofx.interfaces import Wear
from tribofx.output import write_summary
from tribofx.params import resolve
from tribofx.stepper import Stepper

parser = argparse.ArgumentParser(description="Stribeck curve and running-in of a soft cylinder")
parser.add_argument("--quick", action="store_true", help="fewer speeds and wear steps (CI)")
parser.add_argument("--out", default=None, help="write summary.json here")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD

# R = 10 mm, E = 10 MPa, ν = 0.45, μ = 0.1 Pa·s, W = 0.5 N/mm, σ = 1 µm, μ_b = 0.1
speeds = [1000.0, 30.0, 1.0] if args.quick else [1000.0, 100.0, 30.0, 10.0, 3.0, 1.0]
v = resolve(stribeck_case.Params, {"speeds": ",".join(map(str, speeds))})
# -

# ## 1. The Stribeck curve
#
# ``rough_contact.roughness`` is the pair's roughness: σ, K E* from the asperity
# density and radius (ηβσ = 0.1, σ/β = 0.1), the Patir–Cheng flow factors.  The
# cylinder is at rest on the plane, which slides at U; W is reached at the
# highest speed by the plane's approach (a secant on log W), then the speed is
# marched down, W held at every speed.
#
# The cylinder carries a shape field already (``shape=True``: the ALE field w and
# its auxiliary elasticity, for part 2); a ``Wear`` on the film takes the film's
# wear load, which for a rough film is the asperity pressure.  The slow-time
# ``Stepper`` builds the monolithic problem of the film, the body and the shape
# law (28); with Δt = 0 (no step yet) it is the plain mixed-EHL problem.

# +
rough = rough_contact.roughness(v)
print(f"K E* = {rough.asperity.parameters['KE']:.4g} MPa, σ = {rough.sigma} mm") \
    if comm.rank == 0 else None
V, k, dt = speeds[-1], 1e-5, 720.0          # mm/s, mm³/(N·mm), s
run = rough_contact.build(v, "cylinder", speeds[0], comm, shape=True)
film = run.film
wear = Wear(film, k=k, speed=V)
stepper = Stepper([run.body, film, wear], wear, name="running_in",
                  problem_kw={"max_it": 30})
run.problem = stepper.problem
rows = []
rough_contact.load_and_slow(run, v, speeds, on_speed=lambda U, n: rows.append(
    dict(rough_contact.measures(run, v), U=U, newton_iterations=n)))
if comm.rank == 0:
    print("   U (mm/s)   f        film/W   λ = h_c/σ")
    for r in rows:
        print(f"{r['U']:10.3g} {r['friction_coefficient']:8.4f} {r['film_load_fraction']:8.4f}"
              f" {r['lambda_ratio']:8.3f}")
# -

# ## 2. Running-in: the asperities wear the cylinder
#
# At the last speed the slow time starts: the ``Stepper`` solves the film, the
# body and the shape law (28) monolithically (θ = 1) at every step, with a
# ``Hold`` keeping W by the plane's approach.

# +
nsteps = 1 if args.quick else 6
approach = Continuation(stepper.problem, ConstantParameter(film.counterpart.offset, 1),
                        response=lambda: np.log(float(film.force()[1])), rtol=1e-7,
                        max_trials=30)
stepper.hold = Hold(approach, np.log(v.W),
                    step_slope=lambda dt: 1.0 / max(film.min_film(), v.sigma))
history = []
for n in range(nsteps + 1):
    if n:
        stepper.step(dt)
    m = rough_contact.measures(run, v)
    # Archard's k V ∫ p_a ds over the current surface, by hand: the trapezoidal sum
    # of p_a(h) at the nodes (the wear rows' vertex rule; j = ds/dŜ per facet)
    prof = film.profile(everywhere=True)
    KE, (A, Hc, n_gt) = rough.asperity.parameters["KE"], GT_FIT
    p_a = KE * A * np.maximum(Hc - prof["h"] / v.sigma, 0.0) ** n_gt
    ds = np.linalg.norm(np.diff(prof["x"], axis=0), axis=1)
    history.append({"time": n * dt, "wear_area": wear.worn_volume(),
                    "archard_rate": k * V * float(np.sum(ds * (p_a[1:] + p_a[:-1]) / 2)),
                    "max_depth": wear.max_depth(),
                    "asperity_load": m["asperity_load"],
                    "film_load_fraction": m["film_load_fraction"],
                    "friction_coefficient": m["friction_coefficient"], "h_min": m["h_min"]})
if comm.rank == 0:
    print("  t (s)   worn (mm²/mm)  depth (µm)  F_a (N/mm)  film/W   f")
    for h in history:
        print(f"{h['time']:7.0f} {h['wear_area']:12.4e} {1e3 * h['max_depth']:10.3f}"
              f" {h['asperity_load']:10.4f} {h['film_load_fraction']:8.4f}"
              f" {h['friction_coefficient']:8.4f}")
# -

# ## 3. The same film on a ball
#
# ``geometry=ball`` puts the same ``Film`` and ``Roughness`` on the quarter ball
# of ``ehl-ball`` (3D, u_y = 0 on the symmetry plane, the mid-plane held), W in N
# on the whole ball (twice the model's); the start is the ball under the Hertz
# pressure with the plane at the Hamrock–Dowson film.  Nothing in the film is
# written for 2D: the flow factors, the expected gap and the asperity pressure
# are functions of h on any surface.

# +
ball_speeds = [10.0] if args.quick else [1000.0, 100.0, 10.0, 1.0, 0.1]
vb = resolve(stribeck_case.Params, {"geometry": "ball", "W": "0.5", "steps": "1",
                                   "speeds": ",".join(map(str, ball_speeds))})
run_b = rough_contact.build(vb, "ball", ball_speeds[0], comm)
ball_rows = []
rough_contact.load_and_slow(run_b, vb, ball_speeds, on_speed=lambda U, n: ball_rows.append(
    dict(rough_contact.measures(run_b, vb), U=U, newton_iterations=n)))
if comm.rank == 0:
    print("ball (W = 0.5 N):  U (mm/s)   f        film/W   λ = h_c/σ")
    for r in ball_rows:
        print(f"{r['U']:27.3g} {r['friction_coefficient']:8.4f}"
              f" {r['film_load_fraction']:8.4f} {r['lambda_ratio']:8.3f}")
if args.out:
    write_summary(comm, f"{args.out}/summary.json",
                  {"stribeck": rows, "running_in": history, "stribeck_ball": ball_rows})
# -

# ## Checks
#
# * Full film at the first speed (λ > 3: the flow factors are 1 to 1e-3, p_a = 0
#   for H ≥ 4): the asperities carry nothing.  In the mixed regime (1 mm/s, λ < 1)
#   they carry more than 10 % of W, and the friction coefficient has its minimum
#   between the two (the three regimes of the Stribeck curve).
# * Archard: each (backward-Euler) step wears the area Δt k V ∫ p_a ds of its end
#   state, ∫ p_a ds summed by hand above: to the shape rows' Newton tolerance
#   (1e-12 of R per node; 1e-6 relative).
# * Running-in: the asperity load and the friction fall, the film's share rises.
# * The ball at 10 mm/s is mixed: λ < 1, the asperities carry part of W, the film
#   most; W is the ball's, held to the load secant's 1e-7 in log W.

# +
assert rows[0]["film_load_fraction"] == 1.0 and rows[0]["lambda_ratio"] > 3
assert rows[-1]["film_load_fraction"] < 0.9 and rows[-1]["lambda_ratio"] < 1
f = [r["friction_coefficient"] for r in rows]
assert min(f) < f[0] and min(f) < f[-1]
for a, b in zip(history, history[1:]):
    growth = b["wear_area"] - a["wear_area"]       # ∫ (1 − det G): the mesh's volume
    assert abs(growth / (dt * b["archard_rate"]) - 1) < 1e-6, (growth, b)
    assert b["asperity_load"] < a["asperity_load"]
    assert b["friction_coefficient"] < a["friction_coefficient"]
    assert b["film_load_fraction"] > a["film_load_fraction"]
mixed = [r for r in ball_rows if r["U"] == 10.0][0]
assert mixed["lambda_ratio"] < 1 and 0.5 < mixed["film_load_fraction"] < 1.0
assert abs(mixed["W"] / vb.W - 1) < 1e-6
if comm.rank == 0:
    print("demo_mixed_lubrication: all checks passed")
# -

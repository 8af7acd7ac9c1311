"""Elastic ball worn by a sliding rigid flat (quasi-steady-state wear) — chapter §5.2.

What it illustrates
-------------------
A steel-like elastic ball (R = 5 mm, E = 100 GPa, ν = 0.3) is pressed by
F = 100 N against a rigid flat that slides by at V = 10 mm/s with Coulomb
friction μ = 0.4.  Initially the contact is Hertzian (a_H = 0.15 mm, p₀ = 2.1
GPa).  Archard wear (k = 10⁻⁸ mm³/(N·mm)) grinds a flat scar into the ball; as
the scar grows, the contact pressure becomes uniform (F/(πa²), Fig. 7 of the
chapter) and the scar radius follows the rigid-cap law a(s) = (4kFRs/π)^{1/4},
s = V t.  The implicit (backward-Euler, monolithic) scheme reaches t = 1000 s in
10 steps of Δt = 100 s (the chapter: Δt = 100 s with substepping at the start).

Equations (all on the initial, never-moved mesh; quarter model y ≥ 0, z ≤ R)
----------------------------------------------------------------------------
Configurations (eq. 19): X = X̂ + w (worn, shape mapping Ψ), x = X̂ + u,
G = I + Grad w, F = (I + Grad u) G⁻¹.

* Steady frictional contact in the frame of the ball (§4.3): the ball material
  is at rest, the flat moves at V e_x, so the Eulerian slip velocity is
  v_T = −V e_x (eqs. 26–27), fixed in direction; Coulomb sliding, augmented
  Lagrangian multipliers λ_N, λ_T per unit initial area.
* Equilibrium of the worn body: ∫ P(F) : (Grad δu G⁻¹) det G dV̂ + G_c(u, λ) = 0;
  the mid-plane z = R is the rigid holder (u = 0 there in the ball frame) and
  the flat's position δ is iterated (secant) so that the contact force is F/2
  (half of the contact is modelled).
* Archard's law in dissipation form (13–14): Ẇ j_w = K T_T·v_T, K = k/μ
  (= k p V in sliding).
* Shape evolution (28), θ = 1: (w − w_n)·a = −Δt Ẇ j_w at t_{n+1} on Γ̂_c,
  a = cof(G_{n+½}) N̂; w inside from auxiliary elasticity (w_y = 0 on y = 0,
  w_z = 0 on the mid-plane); (u, λ_N, λ_T, w, ζ) in one Newton with the exact
  tangent.

Rigid-cap reference: a flat scar of radius a on a sphere removes π a⁴/(4R);
Archard over the contact removes k F s; hence a = (4kFRs/π)^{1/4} and the
uniform pressure F/(πa²) (≈ 127 MPa at T).

How to change a parameter
-------------------------
Edit ``OVERRIDES`` (keys as in ``tribofx list``), e.g. ``{"scheme": "explicit",
"dt": "5"}`` (stable only below Δt_cr ≈ 6 s on this mesh; see
benchmarks/bench_wear_ball.py), ``{"mesh": "1"}`` for h = a_H/4 in the contact
zone, ``{"friction": "0.3"}``.  From the command line:
``tribofx run wear-ball-flat --set dt=100 --out results/wear-ball-flat``.
About 1.5–2 min serial (≈ 10⁴ unknowns).

Plots (in ``OUT``): ``pressure.png`` (contact pressure on the contact plane at
t = 0 and t = T, mirrored about y = 0), ``profiles.png`` (worn profile along the
symmetry line at every step), ``scar.png`` (scar radius against the rigid-cap law).

Checks at the end: worn volume = k F V T (Archard integrated; the contact force
is F), late-time scar exponent ≈ 1/4 and scar radius ≈ rigid cap, uniform
pressure over the scar at T.
"""

import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx/petsc4py)
import numpy as np
from mpi4py import MPI

from tribofx.runner import run_case

OVERRIDES = {"scheme": "implicit", "dt": "100", "T": "1000", "mesh": "0"}
OUT = "results/demo_wear_ball_flat"

summary = run_case("wear-ball-flat", OVERRIDES, out=OUT, progress=False)
r = {k: v["value"] for k, v in summary["results"].items()}
p = {k: v["value"] for k, v in summary["parameters"].items()}

if MPI.COMM_WORLD.rank == 0:
    print(f"status: {summary['status']}, wall time {summary['wall_time_s']:.1f} s, "
          f"{summary['num_dofs']} unknowns, share of the shape field (w, ζ) "
          f"{r['shape_unknown_fraction']:.2f}")
    print(" t (s)  worn vol (mm³)  depth (mm)  contact a (mm)  scar a (mm)  rigid cap (mm)"
          "  p max/min  Newton")
    for row in zip(r["time"], r["wear_volume"], r["max_wear_depth"], r["contact_radius"],
                   r["scar_radius"], r["rigid_cap_radius"], r["pressure_ratio"],
                   r["newton_iterations"]):
        print(f"{row[0]:6.0f}  {row[1]:14.6f}  {row[2]:10.5f}  {row[3]:14.4f}  {row[4]:11.4f}"
              f"  {row[5]:14.4f}  {row[6]:9.3f}  {row[7]:6d}")
    print(f"late-time exponent of the scar radius {r['scar_radius_exponent_late']:.4f}, "
          f"of the contact radius {r['contact_radius_exponent_late']:.4f} (rigid cap: 0.25)")
    print(f"plots and fields in {OUT}/ (pressure.png, profiles.png, scar.png, *.bp)")

# --- checks ---------------------------------------------------------------------
assert summary["status"] == "ok", summary["status"]
archard = p["k"] * p["F"] * p["V"] * p["T"]
assert abs(r["wear_volume"][-1] - archard) < 1e-6 * archard, (r["wear_volume"][-1], archard)
assert abs(r["scar_radius_exponent_late"] - 0.25) < 0.015, r["scar_radius_exponent_late"]
assert abs(r["scar_radius"][-1] / r["rigid_cap_radius"][-1] - 1) < 0.03
assert r["pressure_ratio"][-1] < 1.06, "the pressure over the scar should be uniform"
assert np.all(np.asarray(r["newton_iterations"]) > 0)
if MPI.COMM_WORLD.rank == 0:
    print(f"checks passed: worn volume {r['wear_volume'][-1]:.6f} mm³ = k F V T = {archard:.6f}")

"""Reciprocating pin-on-flat wear with separation of time scales — chapter §4.2 and §5.1.

What it illustrates
-------------------
The rounded neo-Hookean plane-strain pin of ``wear-pin`` (W = H = 2 mm, tip
radius R_tip = 4 mm, E = 40 MPa, ν = 0.3, traction q = 2 MPa on the top face,
lateral faces constrained laterally) rubs with Coulomb friction μ = 0.3 on a
rigid flat that moves back and forth with peak-to-peak stroke 2A = 2 mm at
V = 10 mm/s (one cycle: Δτ = 2·stroke/V = 0.4 s, sliding distance 4 mm).
Wear follows Archard's law written with the frictional dissipation,
k = 5·10⁻⁶ mm³/(N·mm), K = k/μ.  The slow time runs to T = 1000 s
(2500 cycles) in 20 explicit steps of 125 cycles (Δt = 50 s) on the 10 × 10
mesh (``mesh=0``).  Δt must stay below the explicit critical step ~ h/E (eq. 31;
a step of 500 cycles = 200 s on the 20 × 20 mesh oscillates); θ = 1 by Picard
iteration does not lift this limit (the fixed point contracts under the same
condition), so the θ-scheme on the slow time is explicit here.

Equations (everything on the initial mesh, see ``demo_wear_pin.py``)
--------------------------------------------------------------------
* Fast time τ (eq. 21): at fixed worn shape Ψ(·, t) the deformation problem is
  a standard quasi-static frictional contact problem with Lagrangian
  (incremental) Coulomb friction.  Per slow step the contact memory is erased,
  the flat is placed at −A, slid to the centre (run-in, full sliding), then
  +A, −2A, +A in ``fast_steps`` = 16 sub-steps (chapter §5.1).
* Wear increment of the cycle (eq. 22), per node of the contact surface:
  ΔW = Σ_j K T_T^j · Δs_j (T_T nominal friction traction, Δs_j slip
  increment of sub-step j; eqs. 13–14, zero in stick);
  averaged rate W̄̇ = ΔW / Δτ (eq. 23).
* Slow time t: shape evolution (28) with the averaged rate,
  (w_{n+1} − w_n)·a = −Δt W̄̇, explicit (θ = 0, as in the chapter;
  ``scheme=implicit`` gives θ = 1 by Picard iteration over cycles), interior
  of the shape change w by the auxiliary elasticity problem.

How to change a parameter
-------------------------
Edit ``OVERRIDES`` (keys as in ``tribofx list``): ``stroke`` (mm),
``fast_steps`` (multiple of 4), ``cycles_per_step`` (slow step Δt =
cycles_per_step · 2 stroke / V), ``friction`` (μ > 0), ``E``, ``mesh``.
Steady unidirectional sliding of the same pin (Eulerian slip, eqs. 26–27) is
``{"mode": "steady", "friction": "0.3", "dt": "50"}``.  Command line:
``tribofx run wear-pin --set mode=cyclic --set friction=0.3 --set stroke=2
--set fast_steps=16 --set cycles_per_step=125 --set E=40 --set mesh=0``.

Checks at the end: the run succeeded; the worn area is below, but within 3 %
of, Archard's k F (2·stroke) N_cycles (F = q W per unit thickness) — the
deficit is the stick phase at the stroke reversals, where the elastic
tangential displacement of the contact is recovered without slip; the worn
area equals the time integral of the averaged rate; the tip is flattened.
"""

import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx/petsc4py)
from mpi4py import MPI

from tribofx.runner import run_case

OVERRIDES = {"mode": "cyclic", "friction": "0.3", "stroke": "2", "fast_steps": "16",
             "cycles_per_step": "125", "scheme": "explicit", "E": "40", "T": "1000",
             "mesh": "0"}
OUT = "results/demo_wear_reciprocating"

summary = run_case("wear-pin", OVERRIDES, out=OUT, progress=False)
r = {k: v["value"] for k, v in summary["results"].items()}
p = {k: v["value"] for k, v in summary["parameters"].items()}
cycles = [t * p["V"] / (2 * p["stroke"]) for t in r["time"]]

if MPI.COMM_WORLD.rank == 0:
    print(f"status: {summary['status']}, wall time {summary['wall_time_s']:.1f} s, "
          f"{summary['num_dofs']} unknowns")
    print(" t (s)   cycles  worn area (mm²/mm)  max depth (mm)  half-width (mm)  Newton its")
    for row in zip(r["time"], cycles, r["wear_volume"], r["max_wear_depth"],
                   r["contact_radius"], r["newton_iterations"]):
        print(f"{row[0]:6.0f}  {row[1]:7.0f}  {row[2]:18.6f}  {row[3]:14.5f}  {row[4]:15.4f}"
              f"  {row[5]:10d}")
    print(f"plots and fields in {OUT}/ (profiles.png, wear.png, *.bp)")

# --- checks ---------------------------------------------------------------------
assert summary["status"] == "ok", summary["status"]
archard = p["k"] * p["q"] * p["W"] * 2 * p["stroke"] * cycles[-1]  # k F s, s = 2·stroke·N
vol = r["wear_volume"][-1]
assert 0.97 * archard < vol < archard, (vol, archard)
# explicit: the step from t_n uses the rate averaged over the cycle at t_n
integral = sum(dt * rate for dt, rate in zip(r["dt"][1:], r["wear_rate_integral"][1:]))
assert abs(vol - integral) < 1e-9 * vol, (vol, integral)
assert r["contact_radius"][-1] > 0.95 * p["W"] / 2, "the tip should be worn flat"
if MPI.COMM_WORLD.rank == 0:
    print(f"checks passed: worn area {vol:.6f} = {vol / archard:.4f} × k F (2 stroke) N "
          f"= {archard:.6f} mm²/mm")

"""Pin-on-flat finite wear with the implicit (monolithic ALE) scheme — chapter §4.4.

What it illustrates
-------------------
A neo-Hookean plane-strain pin (width W = 2 mm, height H = 2 mm, rounded tip of
radius R_tip = 4 mm) is pressed by a uniform traction q = 2 MPa on its top face
onto a rigid plane sliding at V = 10 mm/s.  Contact is frictionless, the lateral
faces are constrained laterally.  Archard wear flattens the tip; the worn shape
after t = 1000 s is obtained in 5 implicit steps of Δt = 200 s (Fig. 3, right).

Equations (all on the initial, never-moved mesh)
------------------------------------------------
Three configurations (eq. 19): X = X̂ + w (worn, shape mapping Ψ), x = X̂ + u.
With G = I + Grad w the deformation relative to the worn body is
F = (I + Grad u) G⁻¹, volumes carry det G and areas Nanson's cof(G) N̂.

* Equilibrium of the worn body, pulled back:
  ∫ P(F) : (Grad δu G⁻¹) det G dV̂ − ∫ T*·δu j_w dŜ + G_c(u, λ) = 0,
  with frictionless Alart–Curnier contact on the plane (multiplier λ ≤ 0, the
  nominal traction per unit initial area).
* Archard law, nominal form (14) in pressure form: volume worn per unit
  initial area and time Ẇ j_w = k V |λ|.
* Shape evolution, θ-scheme (28) with θ = 1 (backward Euler), as a nodal
  constraint on Γ̂_c: (w − w_n)·a = −Δt k V |λ_{n+1}|, a = cof(G_{n+½}) N̂;
  the tangential component is free and the interior of w follows from an
  auxiliary elasticity problem (zero normal motion on sides and top).
* (u, λ, w, ζ) are solved together by one Newton method with the exact UFL
  tangent (ζ: multiplier of the shape constraint).

How to change a parameter
-------------------------
Edit ``OVERRIDES`` below (keys as in ``tribofx list``), e.g.
``{"scheme": "explicit", "dt": "5"}`` for the explicit scheme with 200 steps,
``{"E": "20"}`` for the finite-deformation regime, ``{"mesh": "2"}`` for 40×40,
``{"law": "spatial"}`` for the spatial Archard law (15)–(16), Ẇ = (k/J) p V,
``{"k_grad": "-5"}`` for a wear coefficient graded with depth,
k(d) = k max(1 + k_grad·d, 0) (k_grad in 1/mm; negative: k rises towards the
surface as in the graded layer of §5.3).  The explicit scheme is stable only for
Δt below Δt_cr ~ h/E (eq. 31; ≈ 3.8 s at E = 640 MPa on 20×20, see
benchmarks/bench_wear.py).
The same run from the command line:
``tribofx run wear-pin --set dt=200 --out results/wear-pin``.
The error-versus-Δt study of Figs. 3–4 (explicit and implicit, Δt = 200 … 5 s,
implicit reference Δt = 0.78125 s; error_vs_dt.png, profiles.png and the
``study_*`` results in summary.json):
``tribofx run wear-pin --set study=dt --set study_meshes=1 --out results/wear-pin-study``
(about 2 min on 20×20; all meshes and moduli: benchmarks/bench_wear_study.py).

Checks at the end: the worn volume equals Archard's k F V t exactly (F = q W is
the constant normal load), the tip is flattened (contact half-width → W/2) and
Newton converged in every step.
"""

import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx/petsc4py)
from mpi4py import MPI

from tribofx.runner import run_case

OVERRIDES = {"scheme": "implicit", "dt": "200", "T": "1000", "mesh": "1"}
OUT = "results/demo_wear_pin"

summary = run_case("wear-pin", OVERRIDES, out=OUT, progress=False)
r = {k: v["value"] for k, v in summary["results"].items()}
p = {k: v["value"] for k, v in summary["parameters"].items()}

if MPI.COMM_WORLD.rank == 0:
    print(f"status: {summary['status']}, wall time {summary['wall_time_s']:.1f} s, "
          f"{summary['num_dofs']} unknowns")
    print(" t (s)   worn area (mm²/mm)  max depth (mm)  half-width (mm)  Newton its")
    for row in zip(r["time"], r["wear_volume"], r["max_wear_depth"], r["contact_radius"],
                   r["newton_iterations"]):
        print(f"{row[0]:6.0f}   {row[1]:18.6f}  {row[2]:14.5f}  {row[3]:15.4f}  {row[4]:10d}")
    print(f"plots and fields in {OUT}/ (profiles.png, wear.png, *.bp)")

# --- checks ---------------------------------------------------------------------
assert summary["status"] == "ok", summary["status"]
archard = p["k"] * p["q"] * p["W"] * p["V"] * p["T"]  # k F V t, F = q W per unit thickness
assert abs(r["wear_volume"][-1] - archard) < 1e-9 * archard, (r["wear_volume"][-1], archard)
assert r["contact_radius"][-1] > 0.95 * p["W"] / 2, "the tip should be worn flat"
assert r["max_wear_depth"][-1] > 0.1, "a visible fraction of the tip (0.127 mm high) is worn"
if MPI.COMM_WORLD.rank == 0:
    print(f"checks passed: worn area {r['wear_volume'][-1]:.6f} = k q W V T = {archard:.6f}")

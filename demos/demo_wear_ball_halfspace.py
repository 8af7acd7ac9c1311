"""Rigid ball sliding against an elastic half-space: the wear groove — chapter §5.3 (Figs. 9–10).

What it illustrates
-------------------
A rigid ball (R = 5 mm, F = 10 N) slides at V = 100 mm/s over a steel-like
half-space (E = 200 GPa, ν = 0.3; small-deformation set, Hertz a = 0.055 mm,
p₀ = 1.55 GPa), as in a ball-on-disk test with track length L = 2π·10 mm.
Archard wear (k = 10⁻⁷ mm³/(N·mm)) averaged along the sliding path digs a
groove that is uniform along the sliding direction.  The half-space is
described in an Eulerian frame attached to the ball, so the problem is
quasi-steady and the groove evolves in slow time t ∈ [0, 1000 s], here in
10 implicit steps of Δt = 100 s.  A second run repeats it with the
functionally graded surface layer of Fig. 10b (E and k twice the substrate
values at the surface, decreasing linearly to them at 10 µm depth).

Equations (all on initial, never-moved meshes)
----------------------------------------------
* Three configurations (eq. 19): X = X̂ + w (worn), x = X̂ + u (deformed);
  F = (I + Grad u) G⁻¹, G = I + Grad w; the worn body's equilibrium pulled back
  to the initial block, frictionless Alart–Curnier contact with the rigid sphere.
* Eulerian frame (§4.3): the worn half-space moves at V = −V e_x; material
  velocity v = F V (eq. 26), slip velocity v_T its tangential part (eq. 27).
* Archard, nominal pressure form (eq. 14): Ẇ j_w = k |λ| ‖v_T‖ per unit initial area.
* Path average (§5.3, eqs. 22–23 with one revolution per cycle): the groove
  depth rate at y is W̄̇(y) = (1/L) ∫ Ẇ(x, y) dx.
* Ψ uniform along x: w = (0, w_y, w_z)(y, z) lives on the cross-section mesh,
  w₃ = P w₂ (extrusion).  Shape update (28), θ = 1, lumped on the top line of
  the cross-section: (w − w_n)·a = −Δt W̄̇_{n+1}, a = cof(G_{n+½}) N̂, tangential
  part free, interior by auxiliary plane elasticity.
* (u, λ, w₂, ζ) in one Newton method with the exact tangent; the coupling
  blocks are J_{u w₃} P and (Δt/L) Pᵀ J_{r ·}.

How to change a parameter
-------------------------
Edit ``OVERRIDES`` (keys as in ``tribofx list``): ``{"regime": "finite"}`` for
the soft elastomer of Fig. 9 (E = 10 MPa, a/R = 0.3), ``{"mesh": "1"}`` to halve
the element size, ``{"scheme": "explicit", "dt": "0.5"}`` for forward Euler
(stable only for small Δt, see benchmarks/bench_wear_groove.py).  From the
command line: ``tribofx run wear-ball-halfspace --set graded=true --out results/groove``.
The case also runs under ``mpiexec -n 2`` (same results as serial, checked by
tests/test_wear_groove.py::test_two_ranks_match_serial); this demo is run serially.

Checks at the end: the groove area equals Archard's global balance
k F V T / L (to the surface strain of ‖v_T‖ ≈ V), the groove conforms to the
ball (half-width b² ≈ 2 R d), the path-integrated pressure ∫ p dx is uniform
across it (rigid sinking, Fig. 10a), and the graded layer shifts the pressure
towards the groove centre relative to the edges compared with the homogeneous
half-space.
"""

import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx/petsc4py)
import numpy as np

from tribofx.cases.wear_groove import plot_pressure_across
from tribofx.runner import run_case

OVERRIDES = {"scheme": "implicit", "dt": "100", "T": "1000", "mesh": "0"}
OUT = "results/demo_wear_ball_halfspace"

runs = {}
for name, extra in (("homogeneous", {}), ("graded", {"graded": "true"})):
    summary = run_case("wear-ball-halfspace", {**OVERRIDES, **extra}, out=f"{OUT}/{name}",
                       progress=False)
    assert summary["status"] == "ok", summary["status"]
    runs[name] = summary

p = {k: v["value"] for k, v in runs["homogeneous"]["parameters"].items()}
for name, summary in runs.items():
    r = {k: v["value"] for k, v in summary["results"].items()}
    print(f"\n{name}: wall time {summary['wall_time_s']:.1f} s, {summary['num_dofs']} unknowns, "
          f"Ψ share {100 * r['psi_fraction']:.1f} %")
    print(" t (s)  groove area (mm²)  depth (µm)  half-width (mm)  p_max (MPa)  Newton")
    for row in zip(r["time"], r["wear_volume"], r["max_wear_depth"], r["contact_radius"],
                   r["max_pressure"], r["newton_iterations"]):
        print(f"{row[0]:6.0f}  {row[1]:17.4e}  {1e3 * row[2]:10.3f}  {row[3]:15.4f}  "
              f"{row[4]:11.1f}  {row[5]:6d}")


# homogeneous vs graded pressure across the groove (Fig. 10 bottom)
res = {name: {k: v["value"] for k, v in runs[name]["results"].items()} for name in runs}
plot_pressure_across([(name, res[name]["final_pressure_x0"], res[name]["final_pressure_integral"])
                      for name in runs], f"{OUT}/pressure_across.png", p["T"],
                     1.5 * max(res["graded"]["contact_radius"]))
print(f"\nplots in {OUT}/homogeneous, {OUT}/graded and the comparison {OUT}/pressure_across.png")

# --- checks ---------------------------------------------------------------------
r = {k: v["value"] for k, v in runs["homogeneous"]["results"].items()}
archard = p["k"] * p["F"] * p["V"] * p["T"] / p["L"]
A, d = r["wear_volume"][-1], r["max_wear_depth"][-1]
assert abs(A - archard) < 0.01 * archard, (A, archard)
b = 3 * A / (4 * d)
assert abs(b**2 / (2 * p["R"] * d) - 1) < 0.15, (b, d)
q = np.asarray(r["final_pressure_integral"])
inner = q[:, 0] < 0.6 * b
assert np.all(np.abs(q[inner, 1] / q[0, 1] - 1) < 0.1)
g = np.asarray(res["graded"]["final_pressure_integral"])
ratio_h = np.interp(0.8 * b, q[:, 0], q[:, 1]) / q[0, 1]
ratio_g = np.interp(0.8 * b, g[:, 0], g[:, 1]) / g[0, 1]
assert ratio_g < ratio_h - 0.1, (ratio_g, ratio_h)  # edges (high k) need less pressure
print(f"checks passed: area {A:.4e} vs k F V T / L = {archard:.4e}; b² / 2Rd = "
      f"{b**2 / (2 * p['R'] * d):.3f}; ∫p dx at 0.8 b / centre: homogeneous {ratio_h:.3f}, "
      f"graded {ratio_g:.3f}")

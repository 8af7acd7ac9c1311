# # Hydrodynamic lubrication of a plane inclined slider bearing
#
# This demo illustrates
#
# * the steady Reynolds equation of thin-film lubrication (chapter §6.3–6.4,
#   traditional planar form §6.6) on a 1D interval mesh, with the flux
#   q = −h³/(12μ) p' + h v̄ (eq. 40) and the weak form (49)
#
#       ∫ (h³/(12μ)) p' δp' dx − ∫ h v̄ δp' dx = 0,   p = 0 at x = 0 and x = L;
#
# * the forms of ``forms/reynolds.py`` (pure UFL) assembled by DOLFINx and solved
#   by the block Newton solver (one step: the problem is linear);
# * verification against the classical analytic solution and mesh convergence.
#
# ## Problem
#
# A rigid pad at rest over a plane sliding at U (so v̄ = U/2 and ∂h/∂t = 0),
# film thickness h = h0(1 + K − K x/L) (inlet gap h0(1 + K), outlet gap h0).
# Integrating (h³/(12μ)) p' = v̄(h − h*) twice with p(0) = p(L) = 0 gives, with
# s = x/L (Hamrock et al., Cameron),
#
#     p(x)  = 6μUL K s(1 − s) / (h0² (2 + K)(1 + K − K s)²),
#     p_max = 3μUL K / (2 h0² (1 + K)(2 + K))      at x = L(1 + K)/(2 + K),
#     W/B   = 6μUL²/(K² h0²) (ln(1 + K) − 2K/(2 + K))   (load per unit width).
#
# Defaults: L = 10 mm, h0 = 10 µm, K = 1, U = 1 m/s, μ = 0.1 Pa·s
# (1e-7 MPa·s): p_max = 2.5 MPa, W/B = 15.9 N/mm.  Units: mm, N, s, MPa.
#
# ## Changing a parameter
#
#     tribofx run reynolds-slider --set K=2 --set degree=2 --set mesh=50
#     tribofx list        # all parameters with units
#
# Run this script as
#
#     python demos/demo_reynolds_slider.py --out results/reynolds-slider

import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
from mpi4py import MPI

from tribofx.runner import run_case

parser = argparse.ArgumentParser(description="inclined slider demo")
parser.add_argument("--out", default="results/reynolds-slider")
args = parser.parse_args()
rank0 = MPI.COMM_WORLD.rank == 0

summary = run_case("reynolds-slider", {}, args.out, progress=False)
r = {k: v["value"] for k, v in summary["results"].items()}
if rank0:
    print(f"{summary['num_dofs']} unknowns, {summary['wall_time_s']:.2f} s, "
          f"Newton iterations {summary['newton_iterations']}")
    print(f"  load per width W/B = {r['load_per_width']:.5f} N/mm "
          f"(analytic {r['analytic_load_per_width']:.5f})")
    print(f"  p_max = {r['p_max']:.5f} MPa (analytic {r['analytic_p_max']:.5f}) "
          f"at x = {r['x_p_max']:.3f} mm ({r['analytic_x_p_max']:.3f})")
    print(f"  plots, summary.json and VTX in {args.out}")

# Mesh convergence of the L2 error of the pressure (P1: rate 2, P2: rate 3).
rates = {}
for degree in (1, 2):
    errs = []
    for n in (16, 32, 64):
        s = run_case("reynolds-slider", {"mesh": str(n), "degree": str(degree)},
                     f"{args.out}/convergence/P{degree}-{n}", progress=False)
        errs.append(s["results"]["pressure_l2_error"]["value"])
    rates[degree] = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    if rank0:
        print(f"  P{degree}: L2 errors {['%.2e' % e for e in errs]}, rates {rates[degree]}")

# ## Checks
#
# * load and peak pressure within 0.5 % of the analytic solution (measured ≈ 5e-5
#   with 200 P1 elements);
# * L2 error rates within 0.15 of the theoretical k + 1.
assert abs(r["load_rel_error"]) < 5e-3
assert abs(r["p_max_rel_error"]) < 5e-3
assert abs(rates[1][-1] - 2) < 0.15 and abs(rates[2][-1] - 3) < 0.15
if rank0:
    print("demo_reynolds_slider: all checks passed")

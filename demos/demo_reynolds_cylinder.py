# # Rigid cylinder on a plane: Reynolds equation with cavitation
#
# This demo illustrates
#
# * the steady Reynolds equation (chapter §6.3–6.6) on a 1D interval for the
#   parabolic gap h = h0 + x²/(2R) of a cylinder near a plane, entrainment
#   speed u_m (v̄ = u_m), inlet at x_in (p = 0);
# * three treatments of the negative pressures of the diverging gap:
#   - ``none``: full Sommerfeld solution, reported as half-Sommerfeld (negative
#     pressures cut off);
#   - ``penalty``: ∫ ε⁻¹ min(p, 0) δp dx added to the weak form (49), ε in MPa·s/mm;
#     this enforces p ≥ 0 (variational inequality) and reproduces the
#     Swift–Stieber (Reynolds) rupture conditions p = p' = 0 — but it is not mass
#     conserving;
#   - ``jfo``: the mass-conserving JFO model (§6.5): unknowns p and the void
#     fraction λ = 1 − ϱ̄, weak form (57)
#
#       ∫ (1 − λ) h³/(12μ) p' δp' dx + ∫ ((1 − λ) h u_m)' δp dx = 0,
#
#     with the complementarity p ≥ 0, λ ≥ 0, pλ = 0 written as the nodal
#     constraint min(p/p_c, λ) = 0 and solved by semismooth Newton;
# * SUPG stabilisation (Remark 3.2) of the advective (cavitated) zone, with
#   τ = h_e/√(4u_m² + (12D/h_e)²) from the element Péclet number;
# * a starved inlet (``inlet_void`` > 0): the supplied film is transported through
#   a cavitated inlet zone and reforms with a jump of λ.
#
# References (computed by NumPy quadrature, independent of the FE code): the
# half-Sommerfeld solution and the Swift–Stieber solution of
# p' = 12μu_m (h − h*)/h³ for the same inlet position (and, starved, for the
# supplied flux).  Defaults: R = 10 mm, h0 = 10 µm, u_m = 1 m/s, μ = 0.1 Pa·s,
# x ∈ [−2, 2] mm, 400 P1 elements.  Units: mm, N, s, MPa.
#
# ## Changing a parameter
#
#     tribofx run reynolds-cylinder --set cavitation=jfo --set inlet_void=0.945
#     tribofx run reynolds-cylinder --set cavitation=penalty --set penalty=1e-4
#
# Run this script as
#
#     python demos/demo_reynolds_cylinder.py --out results/reynolds-cylinder

import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
from mpi4py import MPI

from tribofx.runner import run_case

parser = argparse.ArgumentParser(description="cylinder–plane Reynolds demo")
parser.add_argument("--out", default="results/reynolds-cylinder")
args = parser.parse_args()
rank0 = MPI.COMM_WORLD.rank == 0

runs = {"none": {"cavitation": "none"}, "penalty": {"cavitation": "penalty"},
        "jfo": {"cavitation": "jfo"},
        "jfo-starved": {"cavitation": "jfo", "inlet_void": "0.945"}}
res = {}
for name, over in runs.items():
    s = run_case("reynolds-cylinder", over, f"{args.out}/{name}", progress=False)
    r = res[name] = {k: v["value"] for k, v in s["results"].items()}
    if rank0:
        ref = r["reference"]
        print(f"{name}: {s['wall_time_s']:.2f} s, Newton iterations per mesh level "
              f"{s['newton_iterations'][0]}")
        print(f"  load {r['load_per_length']:.5f} N/mm ({ref} {r[ref + '_load_per_length']:.5f}),"
              f" p_max {r['p_max']:.5f} MPa ({r[ref + '_p_max']:.5f}),"
              f" rupture at {r['x_rupture']:.3f} mm ({r[ref + '_x_rupture']:.3f})")
        print(f"  flux in {r['flux_in']:.5f}, out {r['flux_out']:.5f} mm²/s")

# ## Checks
#
# * cavitation=none: half-Sommerfeld load and peak within 1 %;
# * penalty and JFO: Swift–Stieber load and peak within 1 %;
# * JFO conserves mass (consistent inflow = outflow to solver tolerance) and the
#   outflow is the Swift–Stieber flux h(x_r) u_m; the penalty model does not;
# * starved JFO: load within 1 % of the starved Swift–Stieber solution.
for name in ("none", "penalty", "jfo", "jfo-starved"):
    assert abs(res[name]["load_rel_error"]) < 0.01, name
    assert abs(res[name]["p_max_rel_error"]) < 0.01, name
for name in ("jfo", "jfo-starved"):
    assert abs(res[name]["mass_balance_rel_defect"]) < 1e-9
    assert abs(res[name]["flux_out"] / res[name]["swift_stieber_flux"] - 1) < 1e-3
assert res["penalty"]["mass_balance_rel_defect"] > 1
if rank0:
    print("demo_reynolds_cylinder: all checks passed")

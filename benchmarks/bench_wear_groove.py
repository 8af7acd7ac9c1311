"""wear-ball-halfspace: implicit monolithic scheme against the explicit scheme (§5.3).

In one run, for the case defaults (small-deformation set, mesh level 0):

1. implicit scheme, Δt = 100 s to T = 1000 s: wall time, steps, Newton
   iterations, final groove area and depth;
2. the largest stable step Δt_cr of the explicit scheme, by experiment: from the
   implicit state at t = ``--t-probe`` (groove formed, contact across it) the
   groove depth gets a node-to-node alternating perturbation of amplitude
   ε = 1 % of the depth on the inner contact line (the highest mode the mesh
   carries, the first to go unstable under forward Euler), the contact problem
   is re-solved and ``--probe-steps`` explicit steps are taken, once with and
   once without the perturbation; Δt is stable if the alternating mode of the
   difference has not grown (a Newton failure or an inverted mesh counts as
   unstable).  Bisection on log Δt;
3. explicit scheme at the stable Δt (≤ Δt_cr): measured wall time per step
   over ``--probe-steps`` steps and the cost extrapolated to T (running the
   thousands of explicit steps to T is not done here);
4. the share of the unknowns that belong to Ψ (w₂ and its multiplier ζ).

Prints a table and writes benchmarks/results/wear_groove.json (run serially here;
the case also runs under mpiexec).

    .venv/bin/python benchmarks/bench_wear_groove.py [--mesh 0] [--out FILE]
"""

import argparse
import json
import math
import os
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401
import numpy as np

from tribofx.cases.wear_groove import WearBallHalfspaceCase as Case
from tribofx.newton import NewtonDivergence
from tribofx.params import resolve

parser = argparse.ArgumentParser()
parser.add_argument("--mesh", type=int, default=0)
parser.add_argument("--T", type=float, default=1000.0)
parser.add_argument("--dt", type=float, default=100.0)
parser.add_argument("--t-probe", type=float, default=100.0)
parser.add_argument("--probe-steps", type=int, default=4)
parser.add_argument("--bisections", type=int, default=3)
parser.add_argument("--out", default="benchmarks/results/wear_groove.json")
args = parser.parse_args()

v = Case.resolved(resolve(Case.params, {"mesh": str(args.mesh)}))
out = {"mesh": args.mesh, "T": args.T}

# 1. implicit run to T ------------------------------------------------------------
t0 = time.perf_counter()
prob, info = Case.build(v)
t_build = time.perf_counter() - t0
t0 = time.perf_counter()
its = Case.initial_contact(prob, info).iterations
steps, t, probe_state = 0, 0.0, None
while t < args.T - 1e-9:
    h = min(args.dt, args.T - t)
    its += sum(r.iterations for r in prob.step(h))
    t += h
    steps += 1
    if probe_state is None and t >= args.t_probe - 1e-9:
        probe_state = prob.state()
wall_imp = time.perf_counter() - t0
n = {b: len(prob.fn[b].x.array) for b in ("u", "l", "w", "z")}
out["dofs"] = n
out["psi_fraction"] = (n["w"] + n["z"]) / sum(n.values())
out["implicit"] = {"dt": args.dt, "steps": steps, "newton_iterations": int(its),
                   "wall_time_s": wall_imp, "build_time_s": t_build,
                   "groove_area": 2 * prob.groove_area(),
                   "depth": float(prob.line_profile()["depth"].max())}
print(f"implicit: {steps} steps, {its} Newton iterations, {wall_imp:.1f} s "
      f"(+ {t_build:.1f} s build); {sum(n.values())} unknowns, Ψ share "
      f"{100 * out['psi_fraction']:.2f} %")

# 2. explicit stability probe -----------------------------------------------------
prob.restore(probe_state)
prob.solve_contact()
base = prob.state()
_, ay = prob.contact_extent()
lp = prob.line_profile()
contact_nodes = np.flatnonzero(lp["Y_hat"] < 0.6 * ay)
line_dofs = prob._top2[np.argsort(prob.V2.tabulate_dof_coordinates()[prob._top2, 0])]
alt = (-1.0) ** np.arange(len(contact_nodes))
alt -= alt.mean()


def amplitude(ref):
    """Alternating-mode amplitude (mm) of the depth difference to the unperturbed run ``ref``."""
    d = prob.line_profile()["depth"][contact_nodes] - ref
    return float((d - d.mean()) @ alt / (alt @ alt))


eps = 1e-2 * float(lp["depth"].max())
prob.w2.x.array.reshape(-1, 2)[line_dofs[contact_nodes], 1] -= eps * alt
prob.sync()
prob.solve_contact()
seeded = prob.state()
a0 = amplitude(lp["depth"][contact_nodes])
prob.scheme = "explicit"
probe = []


def growth(dt):
    """|a_N / a_0| of the seeded mode after N explicit steps (unperturbed run subtracted)."""
    t0 = time.perf_counter()
    try:
        prob.restore(base)
        for _ in range(args.probe_steps):
            prob.step(dt)
        ref = prob.line_profile()["depth"][contact_nodes]
        prob.restore(seeded)
        for _ in range(args.probe_steps):
            prob.step(dt)
    except NewtonDivergence:
        probe.append((dt, math.inf, time.perf_counter() - t0))
        print(f"  explicit Δt = {dt:8.4f} s: failed (Newton or inverted mesh)")
        return math.inf
    g = amplitude(ref) / a0
    probe.append((dt, g, (time.perf_counter() - t0) / 2))
    print(f"  explicit Δt = {dt:8.4f} s: seeded alternating mode × {g:+.3e} after "
          f"{args.probe_steps} steps")
    return abs(g)


lo, hi = None, None
for dt in (0.1, 1.0, 10.0, 100.0):
    if growth(dt) <= 1:
        lo = dt
    else:
        hi = dt
        break
if lo is not None and hi is not None:
    for _ in range(args.bisections):
        mid = math.sqrt(lo * hi)
        if growth(mid) <= 1:
            lo = mid
        else:
            hi = mid
out["explicit_probe"] = [{"dt": d, "growth": g, "wall_time_s": w} for d, g, w in probe]
out["explicit_dt_stable"] = lo
out["explicit_dt_unstable"] = hi

# 3. explicit cost at the stable step -----------------------------------------------
if lo is not None:
    per_step = [w / args.probe_steps for d, g, w in probe if d == lo][0]
    n_exp = math.ceil(args.T / lo)
    out["explicit"] = {"dt": lo, "wall_time_per_step_s": per_step, "steps_to_T": n_exp,
                       "wall_time_to_T_estimate_s": per_step * n_exp}
    print(f"explicit: stable Δt = {lo:.3g} s (unstable at {hi:.3g} s), {per_step:.2f} s/step, "
          f"{n_exp} steps to T → ≈ {per_step * n_exp:.0f} s (estimate) vs implicit "
          f"{wall_imp:.0f} s: ratio {per_step * n_exp / wall_imp:.0f}")

Path(args.out).parent.mkdir(parents=True, exist_ok=True)
with open(args.out, "w") as f:
    json.dump(out, f, indent=2)
print(f"written {args.out}")

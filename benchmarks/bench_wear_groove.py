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

The two schemes share one configuration (body, contact, steady wear): the
explicit :class:`tribofx.stepper.Stepper` is built on the same components with
θ = 0.  Prints a table and writes benchmarks/results/wear_groove.json; runs
serially or under mpiexec (the linear solver is the run's ``auto``: the lagged
LU from 50k unknowns).

    .venv/bin/python benchmarks/bench_wear_groove.py [--mesh 0] [--bisections 3] [--out FILE]
    .venv/bin/mpiexec -n 2 .venv/bin/python benchmarks/bench_wear_groove.py --mesh 2

``--probe-steps 0``: the implicit run only.
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
from mpi4py import MPI

from tribofx import solvers
from tribofx.cases import wear_ball_halfspace as Case
from tribofx.cases.wear_ball_halfspace import surface_data
from tribofx.params import resolve
from tribofx.problem import NewtonDivergence
from tribofx.scheme import EXPLICIT
from tribofx.stepper import Stepper

parser = argparse.ArgumentParser()
parser.add_argument("--mesh", type=int, default=0)
parser.add_argument("--T", type=float, default=1000.0)
parser.add_argument("--dt", type=float, default=100.0)
parser.add_argument("--t-probe", type=float, default=100.0)
parser.add_argument("--probe-steps", type=int, default=4)
parser.add_argument("--bisections", type=int, default=3)
parser.add_argument("--out", default="benchmarks/results/wear_groove.json")
parser.add_argument("--verbose", action="store_true", help="print the Newton histories")
args = parser.parse_args()
comm = MPI.COMM_WORLD


def say(*a, **k):
    if comm.rank == 0:
        print(*a, **k, flush=True)


v = Case.resolved(resolve(Case.Params, {"mesh": str(args.mesh)}))
out = {"mesh": args.mesh, "T": args.T}

# 1. implicit run to T ------------------------------------------------------------
t0 = time.perf_counter()
stepper, info = Case.build(v)
stepper.verbose = args.verbose
wear = stepper.wear
t_build = time.perf_counter() - t0
t0 = time.perf_counter()
its = Case.initial_contact(stepper, info, args.verbose).iterations
probe_state = None
newton_per_step = []


def on_step(st, rep):
    global its, probe_state
    its += rep.iterations
    newton_per_step.append(int(rep.iterations))
    krylov = sum(r.linear_iterations for r in rep.reports)
    say(f"  t = {st.t:7.1f} s: {rep.iterations} Newton iterations, {krylov} Krylov, "
        f"{getattr(st.problem.solver, 'factorisations', '-')} factorisations so far, "
        f"{time.perf_counter() - t0:.0f} s")
    if probe_state is None and st.t >= args.t_probe - 1e-9:
        probe_state = st.state()


stepper.run(args.T, args.dt, on_step=on_step)
wall_imp = time.perf_counter() - t0
n = {"u": wear.body.u.function_space.dofmap.index_map.size_global * 3,
     "l": wear.contact.lam_n.function_space.dofmap.index_map.size_global,
     "w": len(wear.w2.x.array), "z": len(wear.zeta.x.array)}
out["dofs"] = n
out["psi_fraction"] = (n["w"] + n["z"]) / sum(n.values())
out["linear_solver"] = dict(solvers.current_run().used)
out["implicit"] = {"dt": args.dt, "steps": stepper.steps, "newton_iterations": int(its),
                   "newton_per_step": newton_per_step,
                   "factorisations": getattr(stepper.problem.solver, "factorisations", None),
                   "wall_time_s": wall_imp, "build_time_s": t_build,
                   "groove_area": 2 * wear.groove_area(),
                   "depth": float(wear.line_profile()["depth"].max())}
say(f"implicit: {stepper.steps} steps, {its} Newton iterations, {wall_imp:.1f} s "
    f"(+ {t_build:.1f} s build); {sum(n.values())} unknowns, Ψ share "
    f"{100 * out['psi_fraction']:.2f} %")


def write_out():
    out["ranks"] = comm.size
    if comm.rank == 0:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        with open(args.out, "w") as f:
            json.dump(out, f, indent=2)
    say(f"written {args.out}")


if args.probe_steps == 0:   # the implicit run only
    write_out()
    raise SystemExit(0)

# 2. explicit stability probe -----------------------------------------------------
wear.scheme = EXPLICIT  # the same configuration, forward Euler
explicit = Stepper(stepper.components, wear, name="groove_explicit",
                   problem_class=wear.problem_class)
explicit.restore(probe_state)
explicit.problem.solve()
base = explicit.state()
d = surface_data(wear.contact, root=0)
ay = comm.bcast(float(d["X"][d["active"], 1].max()) if comm.rank == 0 else None, root=0)
lp = wear.line_profile()
contact_nodes = np.flatnonzero(lp["Y_hat"] < 0.6 * ay)
X2 = wear.V2.tabulate_dof_coordinates()
top = np.flatnonzero(np.abs(X2[:, 1]) < 1e-12)
line_dofs = top[np.argsort(X2[top, 0])]
alt = (-1.0) ** np.arange(len(contact_nodes))
alt -= alt.mean()


def amplitude(ref):
    """Alternating-mode amplitude (mm) of the depth difference to the unperturbed run ``ref``."""
    dd = wear.line_profile()["depth"][contact_nodes] - ref
    return float((dd - dd.mean()) @ alt / (alt @ alt))


eps = 1e-2 * float(lp["depth"].max())
wear.w2.x.array.reshape(-1, 2)[line_dofs[contact_nodes], 1] -= eps * alt
explicit.problem.solve()  # contact on the seeded shape (w₃ = P w₂ refreshed)
seeded = explicit.state()
a0 = amplitude(lp["depth"][contact_nodes])
probe = []


def growth(dt):
    """|a_N / a_0| of the seeded mode after N explicit steps (unperturbed run subtracted)."""
    t0 = time.perf_counter()
    try:
        explicit.restore(base)
        for _ in range(args.probe_steps):
            explicit.step(dt)
        ref = wear.line_profile()["depth"][contact_nodes]
        explicit.restore(seeded)
        for _ in range(args.probe_steps):
            explicit.step(dt)
    except NewtonDivergence:
        probe.append((dt, math.inf, time.perf_counter() - t0))
        say(f"  explicit Δt = {dt:8.4f} s: failed (Newton or inverted mesh)")
        return math.inf
    g = amplitude(ref) / a0
    probe.append((dt, g, (time.perf_counter() - t0) / 2))
    say(f"  explicit Δt = {dt:8.4f} s: seeded alternating mode × {g:+.3e} after "
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
    say(f"explicit: stable Δt = {lo:.3g} s (unstable at {hi:.3g} s), {per_step:.2f} s/step, "
        f"{n_exp} steps to T → ≈ {per_step * n_exp:.0f} s (estimate) vs implicit "
        f"{wall_imp:.0f} s: ratio {per_step * n_exp / wall_imp:.0f}")

write_out()

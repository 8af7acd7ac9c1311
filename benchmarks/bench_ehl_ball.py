"""Soft-EHL ball on a rigid plane (chapter §8.3, 3D): cost of the coupled load sweep.

Runs the ``ehl-ball`` load sweep (finite deformation, penalty cavitation) in
one process and reports

* the number of unknowns of the coupled system {u, u_s, p, Grad_Γ p} and of the
  displacement alone;
* the Newton iterations per load step (one entry per secant trial of the load
  control, the first step starting with the coupled solve from the Hertz state)
  and the wall time of the whole sweep;
* the cost of one coupled Newton iteration (assemble residual + Jacobian, MUMPS
  LU solve) against one purely hyperelastic Newton iteration (same mesh, same
  P1 displacement space and material, the Hertz pressure at W as a dead load on
  the cap instead of the film), both timed in this run at their converged
  states (best of ``--repeat``).

    .venv/bin/python benchmarks/bench_ehl_ball.py [--W 6] [--steps 3] [--mesh 1]
"""

import argparse
import json
import os
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401
import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI
from tribofx.forms.hyperelastic import external_virtual_work, internal_virtual_work, lame_parameters
from tribofx.meshes.ball import LUBRICATED, MIDPLANE, SYMMETRY

from tribofx.cases.ehl_ball import EHLBallCase as Case
from tribofx.newton import BlockNewton
from tribofx.params import resolve
from tribofx.references import hertz

parser = argparse.ArgumentParser()
parser.add_argument("--W", type=float, default=6.0, help="final load (N)")
parser.add_argument("--steps", type=int, default=3, help="load increments")
parser.add_argument("--mesh", type=int, default=1, help="refinement level near the contact")
parser.add_argument("--model", default="finite", choices=("finite", "linear"))
parser.add_argument("--repeat", type=int, default=3, help="timed assemble+solve repetitions")
parser.add_argument("--out", default="benchmarks/results/ehl_ball.json")
args = parser.parse_args()
comm = MPI.COMM_WORLD
rank0 = comm.rank == 0


def timed_iteration(solver, repeat):
    """Best wall time of one assemble (residual + Jacobian) + LU solve, and its two parts."""
    times = []
    for _ in range(repeat):
        comm.barrier()
        t0 = time.perf_counter()
        b, _ = solver.assemble()
        t1 = time.perf_counter()
        solver.ksp.solve(b, solver.dx)
        comm.barrier()
        t2 = time.perf_counter()
        times.append((t2 - t0, t1 - t0, t2 - t1))
    best = min(times)
    return {"total_s": best[0], "assemble_s": best[1], "solve_s": best[2]}


v = resolve(Case.params, {"W": str(args.W), "steps": str(args.steps), "mesh": str(args.mesh),
                          "model": args.model})
Case.validate(v)

# -- coupled load sweep
t0 = time.perf_counter()
prob = Case.build(v, comm)
t_build = time.perf_counter() - t0
steps = []


def on_step(W, its, final):
    m = prob.measures()
    steps.append({"W": W, "newton_iterations": list(its), "h_central": m["h_central"],
                  "h_min": m["h_min"], "p_max": m["p_max"],
                  "friction_coefficient": m["friction_coefficient"]})


t0 = time.perf_counter()
Case.load_sweep(prob, v, on_step)
t_sweep = time.perf_counter() - t0
n_its = sum(max(i, 0) for s in steps for i in s["newton_iterations"])  # -1: failed trial
n_failed = sum(i < 0 for s in steps for i in s["newton_iterations"])
t_coupled = timed_iteration(prob.solver, args.repeat)
n_u = prob.V.dofmap.index_map.size_global * prob.V.dofmap.index_map_bs

# -- purely hyperelastic problem on the same mesh: Hertz pressure as a dead load
msh, ct, ft = prob.mesh, prob.cell_tags, prob.facet_tags
V = fem.functionspace(msh, ("Lagrange", 1, (3,)))
u = fem.Function(V)
w = ufl.TestFunction(V)
mu, lm = lame_parameters(v["E"], v["nu"])
R = internal_virtual_work(u, w, "3d", "neo-hookean", {"mu": mu, "lmbda": lm},
                          ufl.Measure("dx", msh))
a, p0 = Case.hertz_contact(v)[:2]
X = ufl.SpatialCoordinate(msh)
pH = p0 * ufl.sqrt(ufl.max_value(0.0, 1 - (X[0] ** 2 + X[1] ** 2) / a**2))
ds = ufl.Measure("ds", msh, subdomain_data=ft, subdomain_id=LUBRICATED)
R -= external_virtual_work(-pH * ufl.FacetNormal(msh), w, "3d", ds)
mid = fem.locate_dofs_topological(V, 2, ft.find(MIDPLANE))
sym = fem.locate_dofs_topological(V.sub(1), 2, ft.find(SYMMETRY))
bcs = [fem.dirichletbc(np.zeros(3), mid, V), fem.dirichletbc(np.float64(0.0), sym, V.sub(1))]
hyper = BlockNewton(R, u, bcs=bcs, rtol=1e-10, atol=1e-12)
t0 = time.perf_counter()
rep = hyper.solve()
t_hyper_solve = time.perf_counter() - t0
t_hyper = timed_iteration(hyper, args.repeat)
t_coupled = min(t_coupled, timed_iteration(prob.solver, args.repeat), key=lambda t: t["total_s"])

result = {
    "parameters": {"W": v["W"], "steps": v["steps"], "mesh": v["mesh"], "model": v["model"],
                   "mu_U_N_per_mm": v["mu"] * v["U"], "theta_l_deg": v["theta_l"],
                   "h_fine_mm": hertz(v["W"], v["R"], v["E"], v["nu"]).a
                   / (4 * 2 ** v["mesh"])},
    "mpi_size": comm.size,
    "num_dofs_coupled": prob.solver.num_dofs,
    "num_dofs_displacement": n_u,
    "num_dofs_hyperelastic": hyper.num_dofs,
    "build_time_s": t_build,
    "sweep_wall_time_s": t_sweep,
    "newton_iterations_total": n_its,
    "failed_secant_trials": n_failed,
    "sweep_time_per_newton_iteration_s": t_sweep / n_its,
    "steps": steps,
    "coupled_iteration": t_coupled,
    "hyperelastic_iteration": t_hyper,
    "coupled_to_hyperelastic_ratio": t_coupled["total_s"] / t_hyper["total_s"],
    "hyperelastic_newton_iterations": rep.iterations,
    "hyperelastic_solve_s": t_hyper_solve,
}
if rank0:
    print(f"coupled unknowns {result['num_dofs_coupled']} (displacement {n_u}), "
          f"mesh {v['mesh']}, model {v['model']}, {comm.size} process(es)")
    print(f"{'W[N]':>6} {'Newton its per secant trial':<30} {'h_c[um]':>8} {'h_min[um]':>9} "
          f"{'p_max[MPa]':>10} {'friction':>8}")
    for s in steps:
        print(f"{s['W']:6.2f} {str(s['newton_iterations']):<30} {1e3 * s['h_central']:8.2f} "
              f"{1e3 * s['h_min']:9.2f} {s['p_max']:10.4f} {s['friction_coefficient']:8.4f}")
    print(f"load sweep: {t_sweep:.1f} s, {n_its} Newton iterations, "
          f"{t_sweep / n_its:.3f} s per iteration (incl. Hertz starts, post-processing and "
          f"{n_failed} diverged secant trials, -1 above)")
    print(f"{'one Newton iteration':<22} {'total[s]':>9} {'assemble[s]':>11} {'LU solve[s]':>11}")
    for name, t in (("coupled", t_coupled), ("hyperelastic", t_hyper)):
        print(f"{name:<22} {t['total_s']:9.3f} {t['assemble_s']:11.3f} {t['solve_s']:11.3f}")
    print(f"ratio coupled / hyperelastic: {result['coupled_to_hyperelastic_ratio']:.2f}")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(result, indent=2))

"""Soft-EHL ball on a rigid plane (chapter §8.3, 3D): cost of the coupled load sweep.

Runs the ``ehl-ball`` load sweep (finite deformation, penalty cavitation) in
one process and reports

* the number of unknowns of the coupled system {u, u_s, p, Grad_Γ p} and of the
  displacement alone;
* the Newton iterations per load step (one entry per converged secant trial of the
  load control, the first step starting with the coupled solve from the Hertz state)
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
from mpi4py import MPI

from tribofx.body import Body
from tribofx.cases import ehl_ball as Case
from tribofx.cases.ehl_ball import NAMES
from tribofx.params import resolve
from tribofx.problem import Problem
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


def timed_iteration(problem, repeat):
    """Best wall time of one assemble (residual + Jacobian) + LU solve, and its two parts."""
    ksp, times = problem.snes.getKSP(), []
    for _ in range(repeat):
        comm.barrier()
        t0 = time.perf_counter()
        b, A = problem.assemble()
        t1 = time.perf_counter()
        ksp.setOperators(A)
        dx = b.duplicate()
        ksp.solve(b, dx)
        comm.barrier()
        t2 = time.perf_counter()
        dx.destroy()
        times.append((t2 - t0, t1 - t0, t2 - t1))
    best = min(times)
    return {"total_s": best[0], "assemble_s": best[1], "solve_s": best[2]}


v = resolve(Case.Params, {"W": str(args.W), "steps": str(args.steps), "mesh": str(args.mesh),
                          "model": args.model})
Case.validate(v)

# -- coupled load sweep
t0 = time.perf_counter()
run = Case.build(v, comm)
ball, film, prob = run.ball, run.film, run.problem
t_build = time.perf_counter() - t0
steps = []


def on_step(W, its):
    m = Case.measures(run, v)
    steps.append({"W": W, "newton_iterations": list(its), "h_central": m["h_central"],
                  "h_min": m["h_min"], "p_max": m["p_max"],
                  "friction_coefficient": m["friction_coefficient"]})


t0 = time.perf_counter()
Case.load_sweep(run, v, on_step)
t_sweep = time.perf_counter() - t0
n_its = sum(i for s in steps for i in s["newton_iterations"])
t_coupled = timed_iteration(prob, args.repeat)
n_u = ball.V.dofmap.index_map.size_global * ball.V.dofmap.index_map_bs

# -- purely hyperelastic problem on the same mesh: Hertz pressure as a dead load
plain = Body(ball.mesh, ball.facet_tags, NAMES, "3d", ball.materials[None], name="plain")
plain.add_dirichlet("midplane", np.zeros(3))
plain.add_dirichlet("symmetry", 0.0, component=1)
h = Case.hertz_contact(v)
X = ufl.SpatialCoordinate(ball.mesh)
pH = h.p0 * ufl.sqrt(ufl.max_value(0.0, 1 - (X[0] ** 2 + X[1] ** 2) / h.a**2))
plain.add_traction("lubricated", -pH * ufl.FacetNormal(ball.mesh))
hyper = Problem([plain], name="hyperelastic")
t0 = time.perf_counter()
rep = hyper.solve()
t_hyper_solve = time.perf_counter() - t0
t_hyper = timed_iteration(hyper, args.repeat)
t_coupled = min(t_coupled, timed_iteration(prob, args.repeat), key=lambda t: t["total_s"])

result = {
    "parameters": {"W": v.W, "steps": v.steps, "mesh": v.mesh, "model": v.model,
                   "mu_U_N_per_mm": v.mu * v.U, "theta_l_deg": v.theta_l,
                   "h_fine_mm": hertz(v.W, v.R, v.E, v.nu).a
                   / (4 * 2 ** v.mesh)},
    "mpi_size": comm.size,
    "num_dofs_coupled": prob.num_dofs,
    "num_dofs_displacement": n_u,
    "num_dofs_hyperelastic": hyper.num_dofs,
    "build_time_s": t_build,
    "sweep_wall_time_s": t_sweep,
    "newton_iterations_total": n_its,
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
          f"mesh {v.mesh}, model {v.model}, {comm.size} process(es)")
    print(f"{'W[N]':>6} {'Newton its per secant trial':<30} {'h_c[um]':>8} {'h_min[um]':>9} "
          f"{'p_max[MPa]':>10} {'friction':>8}")
    for s in steps:
        print(f"{s['W']:6.2f} {str(s['newton_iterations']):<30} {1e3 * s['h_central']:8.2f} "
              f"{1e3 * s['h_min']:9.2f} {s['p_max']:10.4f} {s['friction_coefficient']:8.4f}")
    print(f"load sweep: {t_sweep:.1f} s, {n_its} Newton iterations, "
          f"{t_sweep / n_its:.3f} s per iteration (incl. Hertz starts and post-processing)")
    print(f"{'one Newton iteration':<22} {'total[s]':>9} {'assemble[s]':>11} {'LU solve[s]':>11}")
    for name, t in (("coupled", t_coupled), ("hyperelastic", t_hyper)):
        print(f"{name:<22} {t['total_s']:9.3f} {t['assemble_s']:11.3f} {t['solve_s']:11.3f}")
    print(f"ratio coupled / hyperelastic: {result['coupled_to_hyperelastic_ratio']:.2f}")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(result, indent=2))

"""Hertz 3D (quarter sphere on a rigid plane): solve time against the number of unknowns.

Runs the ``hertz`` case at dim=3 for several refinement levels in one process and
reports unknowns, wall time, Newton iterations and time per Newton iteration,
with ratios against the coarsest level of the same run.

    .venv/bin/python benchmarks/bench_hertz.py [--levels 1 2 3] [--out FILE]
"""

import argparse
import json
import os
import tempfile
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401
from mpi4py import MPI

from tribofx.runner import run_case

parser = argparse.ArgumentParser()
parser.add_argument("--levels", type=int, nargs="+", default=[1, 2, 3])
parser.add_argument("--out", default="benchmarks/results/hertz.json")
args = parser.parse_args()

rows = []
with tempfile.TemporaryDirectory() as tmp:
    for level in args.levels:
        t0 = time.perf_counter()
        s = run_case("hertz", {"dim": "3", "mesh": str(level), "load": "0.1", "steps": "1"},
                     Path(tmp) / f"l{level}", progress=False)
        wall = time.perf_counter() - t0
        its = sum(sum(step) for step in s["newton_iterations"])
        rows.append({
            "level": level, "num_dofs": s["num_dofs"], "wall_time_s": wall,
            "solve_time_s": s["wall_time_s"], "newton_iterations": its,
            "time_per_newton_iteration_s": s["wall_time_s"] / its,
            "p_max_rel_error": s["results"]["p_max_rel_error"]["value"],
            "contact_radius_rel_error": s["results"]["contact_radius_rel_error"]["value"],
            "mpi_size": s["mpi_size"],
        })
base = rows[0]
for r in rows:
    r["dofs_ratio"] = r["num_dofs"] / base["num_dofs"]
    r["time_ratio"] = r["solve_time_s"] / base["solve_time_s"]
if MPI.COMM_WORLD.rank == 0:
    print(f"{'level':>5} {'dofs':>8} {'time[s]':>8} {'its':>4} {'s/it':>6} {'dofs x':>7} "
          f"{'time x':>7} {'p_max err':>9}")
    for r in rows:
        print(f"{r['level']:5d} {r['num_dofs']:8d} {r['solve_time_s']:8.1f} "
              f"{r['newton_iterations']:4d} {r['time_per_newton_iteration_s']:6.2f} "
              f"{r['dofs_ratio']:7.1f} {r['time_ratio']:7.1f} {r['p_max_rel_error']:9.4f}")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(rows, indent=2))

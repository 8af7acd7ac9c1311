"""A Stribeck sweep of 20 speeds on the soft cylinder, serial and on 2 ranks (issue 32).

``stribeck`` at its defaults (E 10 MPa, R 10 mm, W 0.5 N/mm, σ 1 µm) with 20
speeds geometric from 1000 to 0.01 mm/s (five decades; the continuation from
speed to speed takes at most 8 geometric steps per decade).  Each run is the
CLI in a subprocess (``tribofx run stribeck``, serial and under ``mpiexec -n 2``);
reported per run: the wall time (build included), the unknowns, and per speed
the Newton iterations spent reaching it (load march included in the first),
λ = h_c/σ, the film's share of W and the friction coefficient.  Writes
``--out`` (JSON) and prints a table.

    .venv/bin/python benchmarks/bench_stribeck.py [--out results/stribeck_sweep.json]
        [--ranks 1,2] [--speeds 20]
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

__all__ = ["main", "sweep"]

ROOT = Path(__file__).resolve().parents[1]


def sweep(ranks, n_speeds):
    """Run the sweep on ``ranks`` processes; return wall time and the per-speed results."""
    speeds = ",".join(f"{u:.6g}" for u in np.geomspace(1000.0, 0.01, n_speeds))
    exe = Path(sys.executable).parent
    with tempfile.TemporaryDirectory() as out:
        cmd = [str(exe / "tribofx"), "run", "stribeck", "--set", f"speeds={speeds}",
               "--quiet", "--out", out]
        if ranks > 1:
            cmd = [str(exe / "mpiexec"), "-n", str(ranks)] + cmd
        env = dict(os.environ, UCX_TLS="self,sm,tcp")
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, env=env, cwd=ROOT, stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - t0
        summary = json.loads((Path(out) / "summary.json").read_text())
    r = summary["results"]
    keys = ("speeds", "newton_iterations", "lambda_ratio", "film_load_fraction",
            "friction_coefficient")
    return {"ranks": ranks, "wall_s": wall, "unknowns": summary.get("num_dofs"),
            **{k: r[k]["value"] for k in keys}}


def main():
    """Run the sweeps, print the table, write the JSON."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="results/stribeck_sweep.json")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--speeds", type=int, default=20)
    args = ap.parse_args()
    runs = [sweep(int(n), args.speeds) for n in args.ranks.split(",")]
    for run in runs:
        print(f"ranks {run['ranks']}: {run['wall_s']:.1f} s, {run['unknowns']} unknowns, "
              f"{sum(run['newton_iterations'])} Newton iterations")
    print("   U (mm/s)  " + "  ".join(f"its({r['ranks']})" for r in runs)
          + "   λ       film/W   f")
    base = runs[0]
    for i, U in enumerate(base["speeds"]):
        its = "  ".join(f"{r['newton_iterations'][i]:7d}" for r in runs)
        print(f"{U:11.4g}  {its}  {base['lambda_ratio'][i]:7.3f}  "
              f"{base['film_load_fraction'][i]:7.4f}  {base['friction_coefficient'][i]:.4f}")
    if len(runs) > 1:
        print(f"wall time serial / {runs[1]['ranks']} ranks: "
              f"{runs[0]['wall_s'] / runs[1]['wall_s']:.2f}")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(runs, indent=1))


if __name__ == "__main__":
    main()

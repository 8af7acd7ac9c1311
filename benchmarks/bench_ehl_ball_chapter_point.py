"""The chapter's severe point from the command line: before and after the defaults changed.

``tribofx run ehl-ball --set W=40 --set U=7800 --set theta_l=60`` (W = 40 N,
μU = 0.078 N/m, a ≈ R/2; chapter §8.3, Figs. 25–26), three load steps, each run
under ``mpiexec -n RANKS`` in this one script:

* ``after``: the bare command, today's defaults (the mixed (u, p) solid, the vertex
  rule of the film, the mesh the outlet rule picks for them: ``mesh=1
  edge_refine=2``);
* ``before``: the defaults the case had until then, set explicitly
  (``formulation=displacement quadrature=gauss``; the rule then picks ``mesh=2
  edge_refine=1``, the displacement solid's resolving mesh);
* ``one_step``: the ``after`` configuration with ``steps=1``, the run the issue
  measured to reach 40 N where three steps failed at 13.3 N.

Each row: wall time, unknowns, the load reached, h_central and h_min against
Hamrock–Dowson's, p_max, ``film_oscillation`` (the zig-zag, target ≤ 0.02), the
speed at which each load step was recorded (``steps_U``), or the run's last line
if it failed.  Ratios to ``after`` in one run (the machine's drift cancels).

    .venv/bin/python benchmarks/bench_ehl_ball_chapter_point.py [--ranks 2]
        [--only after before one_step] [--out results/bench_ehl_ball_chapter_point]
"""

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")
os.environ.setdefault("OMP_NUM_THREADS", "1")

BARE = {"W": 40, "U": 7800, "theta_l": 60}
RUNS = {
    "after": {},
    "before": {"formulation": "displacement", "quadrature": "gauss"},
    "one_step": {"steps": 1},
}
KEYS = ("W_reached", "h_central", "hamrock_dowson_h_c", "h_min", "hamrock_dowson_h_min",
        "p_max", "film_oscillation", "friction_coefficient", "steps_W", "steps_U")


def run(name: str, out: Path, ranks: int) -> dict:
    """Run one configuration from nothing; its row."""
    d = out / name
    sets = {**BARE, **RUNS[name]}
    cmd = [sys.executable, "-m", "tribofx.cli", "run", "ehl-ball", "--out", str(d), "--quiet"]
    cmd += [x for k, v in sets.items() for x in ("--set", f"{k}={v}")]
    if ranks > 1:
        cmd = [str(Path(sys.executable).parent / "mpiexec"), "-n", str(ranks)] + cmd
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    row: dict = {"wall_s": wall, "sets": sets}
    if p.returncode != 0:
        row["failed"] = (p.stderr or p.stdout).strip().splitlines()[-1:]
        return row
    s = json.loads((d / "summary.json").read_text())
    res = {k: v["value"] if isinstance(v, dict) else v for k, v in s["results"].items()}
    row.update(unknowns=s["num_dofs"], mesh_levels=s.get("mesh_levels"),
               **{k: res.get(k) for k in KEYS})
    return row


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--only", nargs="*", default=list(RUNS))
    parser.add_argument("--out", default="results/bench_ehl_ball_chapter_point")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = {name: run(name, out, args.ranks) for name in args.only}
    base = rows.get("after", {}).get("wall_s")
    print(f"{'run':>9} {'wall s':>8} {'/after':>7} {'unknowns':>9} {'mesh':>6} {'W N':>6} "
          f"{'h_c µm':>7} {'HD h_c':>7} {'h_min':>6} {'osc':>6} {'p_max':>6}")
    for name, r in rows.items():
        if "failed" in r:
            print(f"{name:>9} {r['wall_s']:8.0f} failed: {r['failed']}")
            continue
        m = r["mesh_levels"] or {}
        print(f"{name:>9} {r['wall_s']:8.0f} {r['wall_s'] / base if base else float('nan'):7.2f} "
              f"{r['unknowns']:9d} {m.get('mesh')},{m.get('edge_refine'):<4} "
              f"{r['W_reached']:6.2f} {1e3 * r['h_central']:7.2f} "
              f"{1e3 * r['hamrock_dowson_h_c']:7.2f} {1e3 * r['h_min']:6.2f} "
              f"{r['film_oscillation']:6.3f} {r['p_max']:6.3f}")
    (out / "bench_ehl_ball_chapter_point.json").write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()

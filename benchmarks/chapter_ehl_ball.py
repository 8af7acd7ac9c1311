"""§8.3 at the chapter's own points: Figs. 25 (film maps), 26 (centre line), 27 (friction).

Runs ``tribofx run ehl-ball`` (under ``mpiexec -n RANKS``) at

* ``fig26``: W = 40 N, μU = 0.078 N/m, ``compare=all`` (full, no-shear, linear);
* ``fig25_W2_U078``: W = 2 N at μU = 0.78 N/m (light load, fast: the film's
  minimum on the symmetry axis at the rear, as the chapter says);
* ``fig25_W10_U078``, ``fig25_W10_U0078``: W = 10 N at μU = 0.78 and 0.078 N/m;
* ``fig25_W40_U078``: W = 40 N at μU = 0.78 N/m;
* ``fig27_W40_finite``, ``fig27_W40_linear``: W = 40 N reached at μU = 0.078 N/m,
  then continued in speed to μU = 39 N/m (2.7 decades, the chapter's "nearly
  three orders of magnitude"), the full and the geometrically linear model
  (friction coefficients of the film force on the ball and on the plane),

all on ``mesh=2 edge_refine=1`` (element size a/16, a/32 along the contact edge),
θ_l = 60°, one load step, MUMPS.  Each run writes its own ``--out`` under
``OUT`` (checkpointed: rerunning this script continues an interrupted run with
``--resume``; a finished one is not rerun).  Prints the results beside the
Hamrock–Dowson film and writes
``OUT/chapter_ehl_ball.json``; ``--figures`` copies the centre line of
``fig26``, a montage of four film maps and the friction coefficient against μU
of both Fig. 27 runs into ``docs/figures``.

    .venv/bin/python benchmarks/chapter_ehl_ball.py [--ranks 2] [--only fig26 ...]
        [--out results/chapter_ehl_ball] [--figures]
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")
os.environ.setdefault("OMP_NUM_THREADS", "1")

MU = 1e-8  # MPa·s (10 mPa·s): U = μU / μ
# the displacement solid with Gauss points (the case's defaults until the mixed solid
# and the vertex rule replaced them), on the mesh that resolves it at 40 N
COMMON = {"steps": 1, "theta_l": 60, "mesh": 2, "edge_refine": 1, "solver": "direct",
          "formulation": "displacement", "quadrature": "gauss"}
# mm/s: μU = 0.078 (the start) … 39 N/m at μ = 1e-8 MPa·s
FIG27_SPEEDS = "15600,39000,78000,156000,390000,780000,1560000,3900000"
RUNS = {
    "fig26": {"W": 40, "U": 7800, "compare": "all"},
    "fig25_W2_U078": {"W": 2, "U": 78000},
    "fig25_W10_U078": {"W": 10, "U": 78000},
    "fig25_W10_U0078": {"W": 10, "U": 7800},
    "fig25_W40_U078": {"W": 40, "U": 78000},
    "fig27_W40_finite": {"W": 40, "U": 7800, "speeds": FIG27_SPEEDS},
    "fig27_W40_linear": {"W": 40, "U": 7800, "speeds": FIG27_SPEEDS, "model": "linear"},
}
KEYS = ("W_reached", "h_central", "h_min", "x_h_min", "y_h_min", "p_max",
        "friction_coefficient", "plane_friction_coefficient", "hamrock_dowson_h_c",
        "hamrock_dowson_h_min", "hertz_a")


def run(name, out, ranks):
    """Run one configuration (resuming a checkpoint if one is there); its summary."""
    d = out / name
    done = d / "summary.json"
    if done.exists() and json.loads(done.read_text()).get("status") == "ok":
        return summary(d, None)
    sets = [f"{k}={v}" for k, v in {**COMMON, **RUNS[name]}.items()]
    cmd = [sys.executable, "-m", "tribofx.cli", "run", "ehl-ball", "--out", str(d), "--quiet"]
    cmd += [x for s in sets for x in ("--set", s)]
    if (d / "checkpoint").exists():
        cmd.append("--resume")
    if ranks > 1:
        cmd = [str(Path(sys.executable).parent / "mpiexec"), "-n", str(ranks)] + cmd
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return {"failed": (p.stderr or p.stdout).strip().splitlines()[-1:]}
    return summary(d, time.perf_counter() - t0)


def summary(d, wall):
    """Results of the run in ``d`` (its ``summary.json``)."""
    s = json.loads((d / "summary.json").read_text())
    res = {k: v["value"] if isinstance(v, dict) else v for k, v in s["results"].items()}
    return {"wall_s": wall if wall is not None else s["wall_time_s"], "ranks": s["mpi_size"],
            "unknowns": s["num_dofs"], "results": res}


def montage(out, names, path):
    """The film maps of ``names`` side by side (each with its own colour bar)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(names), figsize=(4.2 * len(names), 4.0))
    for ax, name in zip(axes, names):
        ax.imshow(plt.imread(out / name / "film_map.png"))
        W, U = RUNS[name]["W"], RUNS[name]["U"]
        ax.set_title(f"W = {W} N, μU = {MU * U * 1e3:.3g} N/m", fontsize=10)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--only", nargs="*", default=list(RUNS))
    parser.add_argument("--out", default="results/chapter_ehl_ball")
    parser.add_argument("--figures", action="store_true")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = {}
    for name in args.only:
        rows[name] = run(name, out, args.ranks)
        print(name, json.dumps(rows[name].get("failed") or {
            k: rows[name]["results"].get(k) for k in KEYS + ("full_h_min", "linear_h_min",
                                                               "full_p_max", "linear_p_max")
            if k in rows[name]["results"]}), flush=True)
    (out / "chapter_ehl_ball.json").write_text(json.dumps(rows, indent=1))
    if args.figures:
        fig = Path(__file__).resolve().parents[1] / "docs" / "figures"
        if (out / "fig26" / "centerline.png").exists():
            shutil.copy(out / "fig26" / "centerline.png", fig / "ehl_ball_fig26_W40.png")
        maps = [n for n in ("fig25_W2_U078", "fig25_W10_U0078", "fig25_W40_U078", "fig26")
                if (out / n / "film_map.png").exists()]
        if maps:
            montage(out, maps, fig / "ehl_ball_fig25_maps.png")
        # the friction force on the plane (what a rig measures on the counterpart) and
        # on the ball (the linear model's differ by the pressure on the displacement's
        # slope and its shear on the reference area: see the ehl_ball module docstring)
        fig27 = {f"{model}, on the {where}": (rows[n]["results"]["speed_mu_U"],
                                              rows[n]["results"][key])
                 for where, key in (("plane", "speed_plane_friction_coefficient"),
                                    ("ball", "speed_friction_coefficient"))
                 for model, n in (("finite", "fig27_W40_finite"),
                                  ("linear", "fig27_W40_linear"))
                 if key in rows.get(n, {}).get("results", {})}
        if fig27:
            from tribofx.plots.film import plot_friction_vs_speed

            plot_friction_vs_speed(fig27, fig / "ehl_ball_fig27_W40.png")


if __name__ == "__main__":
    main()

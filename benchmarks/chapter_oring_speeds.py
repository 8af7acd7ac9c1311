"""Fig. 19 of §8.1 redrawn: the film against the rod speed, per mesh density and solid.

The chapter (Fig. 19) shows the O-ring's film at several rod speeds on densities 4
and 8 with the P1 displacement solid: the slower the rod (the thinner the film),
the finer the mesh it needs before the zig-zag goes.  This script solves the
outstroke at p_s = 1 MPa, first at ``--speeds[0]`` and then down the list by
speed continuation (``ORingSeal.speed``), for each solid of ``--solids``
(``displacement``: the chapter's P1 solid with penalty cavitation; ``mixed``: the
locking-free (u, p) solid with JFO cavitation, the case's default) and each
density of ``--densities``, in one process.  Per run and speed: the oscillation
indicator, flux spread, mean film of the loaded zone, h_min, p_max, Newton
iterations and wall time; a speed whose continuation fails is recorded as failed
(the later speeds of that run are skipped).  Writes ``--out`` (JSON) and, with
``--figure``, ``docs/figures/ehl_oring_fig19_speeds.png`` (h against z, one
panel per solid and density).

    .venv/bin/python benchmarks/chapter_oring_speeds.py [--speeds 400,200,100,50]
        [--densities 4,8] [--solids displacement,mixed] [--figure]
        [--out results/chapter_oring_speeds.json]
"""

import argparse
import json
import os
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401,E402

from tribofx.cases import ehl_oring as Case  # noqa: E402
from tribofx.cases.ehl_oring import build, solve_to  # noqa: E402
from tribofx.params import resolve  # noqa: E402
from tribofx.reports import NewtonDivergence  # noqa: E402

KEYS = ("oscillation", "flux_spread", "h_mean", "h_min", "p_max")


def sweep(solid, density, speeds):
    """Solve one seal down the speeds; a list of per-speed records with profiles."""
    v = resolve(Case.Params, {"mesh": str(density), "U": str(speeds[0]), "p_s": "1",
                              "formulation": solid})
    Case.validate(v)
    out = []
    t0 = time.perf_counter()
    seal = build(v, max(speeds[0], 1000.0))
    for k, U in enumerate(speeds):
        n0 = len(seal.iterations)
        try:
            if k == 0:
                solve_to(seal, v, U, [1.0])
            else:
                seal.speed(U, 3)
        except NewtonDivergence as err:
            out.append({"U": U, "failed": str(err).splitlines()[0][:200]})
            break
        m, pr = seal.measures(), seal.profile()
        out.append({"U": U, **{q: m[q] for q in KEYS},
                    "newton_iterations": int(sum(seal.iterations[n0:])),
                    "wall_time": time.perf_counter() - t0,
                    "z": pr["z"].tolist(), "h": pr["h"].tolist(), "p": pr["p"].tolist()})
        t0 = time.perf_counter()
    return {"solid": solid, "density": density, "unknowns": seal.problem.num_dofs,
            "speeds": out}


def figure(runs, path):
    """h(z) at every speed, one panel per run (rows: solids, columns: densities)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    solids = sorted({r["solid"] for r in runs})
    dens = sorted({r["density"] for r in runs})
    fig, axes = plt.subplots(len(solids), len(dens), figsize=(5 * len(dens), 3.4 * len(solids)),
                             squeeze=False, sharex=True)
    for r in runs:
        ax = axes[solids.index(r["solid"])][dens.index(r["density"])]
        for s in r["speeds"]:
            if "failed" in s:
                ax.plot([], [], " ", label=f"U = {s['U']:g}: failed")
                continue
            ax.plot(s["z"], [1e3 * h for h in s["h"]], ".-", ms=2, lw=0.8,
                    label=f"U = {s['U']:g} mm/s ({100 * s['oscillation']:.1f} %)")
        hs = [1e3 * s["h_mean"] for s in r["speeds"] if "failed" not in s]
        ax.set_ylim(0, 2.5 * max(hs) if hs else 1)
        ax.set_xlim(-0.8, 1.0)
        ax.set_title(f"{r['solid']} solid, density {r['density']} ({r['unknowns']} unknowns)",
                     fontsize=9)
        ax.set_ylabel("h (µm)")
        ax.legend(fontsize=7, title="rod speed (zig-zag indicator)", title_fontsize=7)
    for ax in axes[-1]:
        ax.set_xlabel("z (mm, air side > 0)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    """Run the sweeps, print the table, write JSON (and the figure)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speeds", default="400,200,100,50")
    ap.add_argument("--densities", default="4,8")
    ap.add_argument("--solids", default="displacement,mixed")
    ap.add_argument("--figure", action="store_true")
    ap.add_argument("--out", default="results/chapter_oring_speeds.json")
    a = ap.parse_args()
    speeds = [float(s) for s in a.speeds.split(",")]
    runs = [sweep(s, int(d), speeds) for s in a.solids.split(",")
            for d in a.densities.split(",")]
    print("solid         density unknowns  U (mm/s)  oscillation  flux spread  h_mean (µm)  "
          "h_min (µm)  Newton  wall (s)")
    for r in runs:
        for s in r["speeds"]:
            head = f"{r['solid']:13s} {r['density']:7d} {r['unknowns']:8d} {s['U']:9g}"
            if "failed" in s:
                print(f"{head}  failed: {s['failed']}")
                continue
            print(f"{head} {s['oscillation']:12.4f} {s['flux_spread']:12.4f} "
                  f"{1e3 * s['h_mean']:12.4f} {1e3 * s['h_min']:11.4f} "
                  f"{s['newton_iterations']:7d} {s['wall_time']:9.1f}")
    Path(a.out).parent.mkdir(parents=True, exist_ok=True)
    Path(a.out).write_text(json.dumps({"speeds": speeds, "runs": runs}, indent=1))
    if a.figure:
        figure(runs, Path(__file__).resolve().parents[1] / "docs" / "figures"
               / "ehl_oring_fig19_speeds.png")


if __name__ == "__main__":
    main()

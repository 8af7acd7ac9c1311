"""wear-pin: the full error-versus-Δt study of Fig. 4 (and the profiles of Fig. 3).

Runs ``tribofx run wear-pin --set study=dt`` (explicit and implicit, Δt = 200,
100, 50, 20, 10, 5 s, implicit reference Δt = 0.78125 s = T/1280) for

* Fig. 4 left: E = 10, 20, 40, 80, 160, 320, 640 MPa on the 80 × 80 mesh (level 3);
* Fig. 4 right: meshes 20 × 20, 40 × 40, 80 × 80 (levels 1, 2, 3) at E = 640 MPa;

each in its own folder under ``--out`` (summary.json, error_vs_dt.png,
profiles.png), then collects the critical steps and errors in ``study.json`` and
the check Δt_cr ∝ h/E (eq. 31).  The 80 × 80 reference alone is 1280 monolithic
steps: expect hours on 2 cores.  A smaller version, e.g.

    .venv/bin/python benchmarks/bench_wear_study.py --Es 40,160,640 --E-mesh 1 --meshes 0,1,2

(``--E-mesh``: mesh level of the E sweep; ``--dts``, ``--ref-dt``, ``--ref`` as in
the case; ``--meshes none`` skips the mesh sweep; ``--schemes implicit,bdf2`` puts
BDF2 beside backward Euler, against a BDF2 reference.)  ``fig4_left.png``: error
against Δt of the E sweep, explicit and implicit, Δt_cr marked.  Runs split
over several processes (one core each) are merged without running anything by

    .venv/bin/python benchmarks/bench_wear_study.py --merge DIR1 DIR2 --out DIR
"""

import argparse
import json
import os
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401
from mpi4py import MPI

from tribofx.runner import run_case

parser = argparse.ArgumentParser()
parser.add_argument("--Es", default="10,20,40,80,160,320,640", help="moduli (MPa), E sweep")
parser.add_argument("--E-mesh", type=int, default=3, help="mesh level of the E sweep")
parser.add_argument("--meshes", default="1,2,3", help="mesh levels of the mesh sweep")
parser.add_argument("--E-meshes", type=float, default=640.0, help="E (MPa) of the mesh sweep")
parser.add_argument("--dts", default="200,100,50,20,10,5")
parser.add_argument("--ref-dt", default="0.78125")
parser.add_argument("--ref", default="fine", choices=("fine", "richardson"),
                    help="reference: implicit at --ref-dt, or Richardson from --ref-dt and 2x")
parser.add_argument("--schemes", default="explicit,implicit",
                    help="study_schemes: explicit, implicit, bdf2 (bdf2: a BDF2 reference)")
parser.add_argument("--merge", nargs="+", default=[],
                    help="only merge the study.json of these folders into --out and plot")
parser.add_argument("--out", default="benchmarks/results/wear_study")
args = parser.parse_args()
comm = MPI.COMM_WORLD
out = Path(args.out)


def plot_fig4_left(runs, path):
    """Fig. 4 left: error of the worn profile against Δt, one curve per E (one mesh)."""
    from tribofx.plots.common import pyplot
    from tribofx.plots.wear import error_curve

    plt = pyplot()
    schemes = [s for s in ("explicit", "implicit", "bdf2")
               if any(c.get(f"study_error_{s}") for c in runs.values())]
    fig, axes = plt.subplots(1, len(schemes), figsize=(5 * len(schemes), 4), sharey=True,
                             squeeze=False)
    axes = axes[0]
    sweep = sorted((c for c in runs.values()
                    if len(c[f"study_error_{schemes[0]}"] or {}) == 1), key=lambda c: c["E_MPa"])
    for ax, scheme in zip(axes, schemes):
        for i, c in enumerate(sweep):
            (mesh, err), = c[f"study_error_{scheme}"].items()
            dt_cr = (c["study_dt_cr"] or {}).get(mesh) if scheme == "explicit" else None
            error_curve(ax, c["study_dt"], err, c[f"study_unstable_{scheme}"][mesh], f"C{i}",
                        f"E = {c['E_MPa']:g} MPa", dt_cr)
        ax.set_xlabel("Δt (s)")
        ax.set_title(f"{scheme}" + (" (× unstable, ⋮ Δt_cr)" if scheme == "explicit" else ""))
        ax.legend(fontsize=7)
    axes[0].set_ylabel("error of the worn contact profile (mm)")
    if sweep:
        fig.suptitle(f"wear-pin, {mesh} mesh; reference: {sweep[0]['study_reference']}",
                     fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def dt_cr_scaling(runs):
    """eq. 31: Δt_cr · E / h should be the same for every E and mesh."""
    check = {}
    for c in runs.values():
        for mesh, dt_cr in (c["study_dt_cr"] or {}).items():
            if dt_cr:
                n = int(mesh.split("x")[0])
                check[f"E{c['E_MPa']:g}_{mesh}"] = dt_cr * c["E_MPa"] * n
    return check


if args.merge:
    merged = {}
    for d in args.merge:
        merged.update(json.loads((Path(d) / "study.json").read_text())["runs"])
    out.mkdir(parents=True, exist_ok=True)
    (out / "study.json").write_text(json.dumps({"runs": merged,
                                                "dt_cr_E_over_h": dt_cr_scaling(merged)},
                                               indent=2))
    plot_fig4_left(merged, out / "fig4_left.png")
    print("dt_cr * E / h:", dt_cr_scaling(merged))
    raise SystemExit(0)

jobs = [(f"E{float(E):g}_mesh{args.E_mesh}", {"E": E, "study_meshes": str(args.E_mesh)})
        for E in args.Es.split(",") if E.strip()]
if args.meshes != "none":
    jobs.append((f"E{args.E_meshes:g}_meshes", {"E": str(args.E_meshes),
                                                 "study_meshes": args.meshes}))
collected = {}
for label, over in jobs:
    t0 = time.perf_counter()
    s = run_case("wear-pin", {"study": "dt", "study_dts": args.dts,
                              "study_ref_dt": args.ref_dt, "study_ref": args.ref,
                              "study_schemes": args.schemes, **over},
                 out=out / label, progress=False)
    r = {k: v["value"] for k, v in s["results"].items()}
    collected[label] = {"E_MPa": float(over["E"]), "status": s["status"],
                        "wall_time_s": time.perf_counter() - t0,
                        **{k: v for k, v in r.items() if k in ("study_dt", "study_dt_cr",
                                                               "study_reference")
                           or k.startswith(("study_error_", "study_unstable_"))}}
    if comm.rank == 0:
        c = collected[label]
        print(f"{label}: {c['status']}, {c['wall_time_s']:.0f} s, dt_cr {c['study_dt_cr']}")
        for scheme in args.schemes.split(","):
            for mesh, e in (c.get(f"study_error_{scheme}") or {}).items():
                print(f"  {mesh} {scheme} {e}")

check = dt_cr_scaling(collected)
if comm.rank == 0:
    print("dt_cr * E / h (MPa s / mm, up to the factor W = 2 mm):", check)
    out.mkdir(parents=True, exist_ok=True)
    (out / "study.json").write_text(json.dumps({"runs": collected, "dt_cr_E_over_h": check},
                                               indent=2))
    plot_fig4_left(collected, out / "fig4_left.png")

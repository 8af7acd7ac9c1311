"""Memory per rank by phase, serial and 2 ranks: the §5.3 groove or the Hertz ball.

Where the resident memory of a run goes, and how much of it splits over ranks.
``--problem groove``: the groove (``wear-ball-halfspace``, mesh level
``--mesh``) is built and its unworn contact solved (Newton with the lagged
solver: GMRES on the MUMPS LU of an earlier Newton matrix).  ``--problem
ball``: the frictional Hertz sphere (``hertz dim=3 friction=0.3``, P1
tetrahedra) is built and loaded in three approach steps with the iterative
solver (GAMG/Schur fieldsplit; MUMPS columns then read 0); both problems come
from ``bench_solvers.build``.  ``--strategy`` changes the solver.  Each
process reports its resident memory (``/proc``
VmRSS) and its peak so far (VmHWM) after the imports, after the build and after
the solve, and MUMPS reports per rank the memory it allocated for the
factorisation (INFO(16), MB), the memory it used (INFO(22)) and, summed over
ranks, the factor entries (INFOG(29)).  Each configuration runs in its own
process(es), so that every peak is its own.  The ratio printed last is the
largest 2-rank peak over the serial peak (half the serial memory per rank would
be 0.5).

    .venv/bin/python benchmarks/bench_memory.py [--problem groove|ball] [--mesh 2]
        [--strategy lagged] [--ranks 1 2] [--petsc-option mat_mumps_icntl_37=0 ...]

``--petsc-option KEY=VALUE`` (no prefix, repeatable) changes the factorisation,
e.g. ``mat_mumps_icntl_37=0`` (contribution blocks not compressed) or
``mat_mumps_icntl_7=3`` (SCOTCH ordering).  Mesh 2 (230,742 unknowns) takes
about 5 min serially and 4 min on 2 ranks and peaks near 6 GB per process;
mesh 1 (50,010 unknowns) takes under a minute; the ball at mesh 4 (141,590
unknowns) takes about 5 min serially and 3 min on 2 ranks, at mesh 5 (970,804
unknowns) 47 min serially (peak 4.0 GB) and 25 min on 2 ranks.  Results in
``docs/solvers.md`` ("Memory per rank").
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


def _memory():
    """Return (VmRSS, VmHWM) of this process in MB."""
    out = {}
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(("VmRSS", "VmHWM")):
                key, value = line.split(":")
                out[key] = int(value.split()[0]) / 1024
    return out["VmRSS"], out["VmHWM"]


def one(problem, mesh, strategy, options):
    """Build and solve one problem in this process; rank 0 prints one JSON line."""
    phases = {}
    import dolfinx_solver  # noqa: F401  (before dolfinx)
    from mpi4py import MPI

    __import__("dolfinx")

    phases["imports"] = _memory()
    from bench_solvers import build  # the same problems and steps as the solver table

    from tribofx import solvers

    comm = MPI.COMM_WORLD
    with solvers.run_settings(strategy, options):
        prob, steps = build(problem, mesh, comm)
        if problem == "groove":   # the unworn contact only
            steps = steps[:1]
        phases["built"] = _memory()
        t0 = time.perf_counter()
        newton = 0
        for k, step in enumerate(steps):
            newton += sum(r.iterations for r in step())
            if k == 0 and len(steps) > 1:
                phases["first step"] = _memory()
        t_solve = comm.allreduce(time.perf_counter() - t0, op=MPI.MAX)
        phases["solved"] = _memory()
        mumps, entries = {"allocated_mb": 0, "used_mb": 0}, 0
        if strategy != "iterative":
            F = prob.snes.getKSP().getPC().getFactorMatrix()
            mumps = {"allocated_mb": F.getMumpsInfo(16), "used_mb": F.getMumpsInfo(22)}
            entries = F.getMumpsInfog(29)
    gathered = comm.gather({"phases": phases, "mumps": mumps}, root=0)
    if comm.rank == 0:
        print(json.dumps({"problem": problem, "mesh": mesh, "strategy": strategy,
                          "ranks": comm.size, "unknowns": prob.num_dofs,
                          "options": options, "newton": newton,
                          "solve_s": t_solve, "factor_entries": entries,
                          "per_rank": gathered}))


def launch(problem, mesh, strategy, ranks, options):
    """Run :func:`one` in fresh process(es); return its JSON, or a failure."""
    here = Path(__file__).resolve()
    cmd = [sys.executable, str(here), "--one", "--problem", problem, "--mesh", str(mesh),
           "--strategy", strategy]
    cmd += [a for kv in options.items() for a in ("--petsc-option", "=".join(kv))]
    if ranks > 1:
        cmd = [str(Path(sys.executable).parent / "mpiexec"), "-n", str(ranks)] + cmd
    p = subprocess.run(cmd, capture_output=True, text=True)
    lines = [ln for ln in p.stdout.splitlines() if ln.startswith("{")]
    if p.returncode != 0 or not lines:
        tail = (p.stderr or p.stdout).strip().splitlines()[-1:] or ["?"]
        return {"mesh": mesh, "ranks": ranks, "failed": f"exit {p.returncode}: {tail[0][:200]}"}
    return json.loads(lines[-1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--one", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--problem", choices=("groove", "ball"), default="groove")
    parser.add_argument("--mesh", type=int, default=2)
    parser.add_argument("--strategy", default=None,
                        help="solver strategy (default: lagged for groove, iterative for ball)")
    parser.add_argument("--ranks", type=int, nargs="*", default=[1, 2])
    parser.add_argument("--petsc-option", action="append", default=[], metavar="KEY=VALUE")
    parser.add_argument("--out", default="benchmarks/results/memory.json")
    args = parser.parse_args()
    options = dict(kv.split("=", 1) for kv in args.petsc_option)
    strategy = args.strategy or {"groove": "lagged", "ball": "iterative"}[args.problem]
    if args.one:
        one(args.problem, args.mesh, strategy, options)
        return
    rows = []
    for ranks in args.ranks:
        r = launch(args.problem, args.mesh, strategy, ranks, options)
        rows.append(r)
        if "failed" in r:
            print(f"{ranks} rank(s): failed: {r['failed']}")
            continue
        print(f"{ranks} rank(s), {r['unknowns']} unknowns, {r['newton']} Newton iterations, "
              f"{r['solve_s']:.1f} s, factor entries {r['factor_entries']:.3e}")
        print(f"  {'rank':>4s} {'imports':>8s} {'built':>8s} {'built peak':>10s} "
              f"{'solved':>8s} {'peak':>8s} {'MUMPS alloc':>11s} {'MUMPS used':>10s}  (MB)")
        for k, q in enumerate(r["per_rank"]):
            ph, m = q["phases"], q["mumps"]
            print(f"  {k:4d} {ph['imports'][0]:8.0f} {ph['built'][0]:8.0f} "
                  f"{ph['built'][1]:10.0f} {ph['solved'][0]:8.0f} {ph['solved'][1]:8.0f} "
                  f"{m['allocated_mb']:11d} {m['used_mb']:10d}")
    ok = {r["ranks"]: r for r in rows if "failed" not in r}
    if 1 in ok:
        serial = ok[1]["per_rank"][0]["phases"]["solved"][1]
        for ranks, r in ok.items():
            if ranks > 1:
                peak = max(q["phases"]["solved"][1] for q in r["per_rank"])
                print(f"largest peak per rank on {ranks} ranks / serial peak: "
                      f"{peak:.0f} / {serial:.0f} MB = {peak / serial:.2f}")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()

"""Direct (MUMPS LU) against iterative (GMRES + AMG/Schur fieldsplit) at growing size.

Two 3D problems of the chapter:

* ``groove``: the §5.3 wear groove (``wear-ball-halfspace``, Q1 hexahedra, the
  monolithic implicit step in displacement, contact multiplier, cross-section Ψ
  and ζ), the unworn contact and one implicit step of 100 s;
* ``ball``: the frictional Hertz sphere (``hertz dim=3 friction=0.3``, P1
  tetrahedra), three approach steps.

Each (problem, mesh level, strategy) runs in its own process, so that its peak
resident memory (``ru_maxrss``) is its own; the timings are the Newton solves
only (assembly, kernels and linear solves), per Newton iteration, with the
time of their parts (PETSc events: ``EVENTS``) in the JSON.  The largest
size is also run on 2 ranks (per-rank peak memory, speed-up).  Prints a table,
the iterative/direct cost ratio per size (the crossover) and writes
``benchmarks/results/solvers.json``.

    .venv/bin/python benchmarks/bench_solvers.py [--groove 0 1 2] [--ball 2 3 4]
        [--ranks2] [--strategies direct iterative blr1e-8] [--out FILE]

``blr<eps>``: MUMPS LU with block low-rank compression (ICNTL(35) = 1, dropping
tolerance CNTL(7) = eps, compressed contribution blocks ICNTL(37) = 1; the
settings of ``DirectSolver(blr=eps)``): its gain in time and memory against
plain LU.
``STRATEGY:key=value,...``: the strategy with extra PETSc options (no prefix),
e.g. ``iterative:pc_fieldsplit_schur_fact_type=lower``.
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


#: PETSc events whose time (s, the largest rank's) a run reports: assembly of the
#: Newton matrix, the linear solves and, within them, the preconditioner's set-up
#: (AMG hierarchy, factorisations) and application, and the matrix-vector products
EVENTS = ("SNESJacobianEval", "KSPSolve", "PCSetUp", "PCApply", "MatMult")


def build(problem, level, comm):
    """Build ``problem`` ("groove" or "ball") at mesh ``level``; return (Problem, steps).

    ``steps``: callables, each solving one load or time step and returning its
    Newton reports.  Groove: the unworn contact, then one implicit step of 100 s.
    Ball: three approach steps (0.3, 0.6, 1 of the Hertz approach a²/R).
    """
    from tribofx.params import resolve

    if problem == "groove":
        from tribofx.cases import wear_ball_halfspace as Case

        v = Case.resolved(resolve(Case.Params, {"mesh": str(level)}))
        stepper, info = Case.build(v, comm)
        return stepper.problem, [lambda: [Case.initial_contact(stepper, info)],
                                 lambda: stepper.step(100.0).reports]
    from tribofx.cases import hertz as Case
    from tribofx.continuation import ConstantParameter
    from tribofx.references import hertz

    v = resolve(Case.Params, {"dim": "3", "mesh": str(level), "friction": "0.3"})
    Case.validate(v)
    _, contact, prob = Case.build(v, comm)
    a = hertz(v.load, v.R, v.E, v.nu)[0]
    delta = ConstantParameter(contact.counterpart.offset, 2)

    def approach(f):
        def step():
            delta.set(f * a**2 / v.R)
            report = prob.solve()
            prob.commit()
            return [report]
        return step

    return prob, [approach(f) for f in (0.3, 0.6, 1.0)]


def one(problem, level, strategy):
    """Run one configuration in this process; print one JSON line (rank 0)."""
    import resource

    import dolfinx_solver  # noqa: F401
    import numpy as np
    from mpi4py import MPI
    from petsc4py import PETSc

    from tribofx import solvers

    PETSc.Log.begin()   # the time of the solve's parts (PETSc events, summed over the run)
    comm = MPI.COMM_WORLD
    reports = []
    t_solve = 0.0
    if strategy.startswith("blr"):   # MUMPS LU with block low-rank compression, tolerance
        eps = float(strategy[3:] or 1e-10)
        blr = solvers.DirectSolver(blr=eps).options()   # the solver's own BLR settings
        settings = solvers.run_settings("direct", {k: v for k, v in blr.items()
                                                   if k.startswith("mat_mumps_")})
    else:   # "iterative:key=value,key=value": extra PETSc options (without prefix)
        name, _, extra = strategy.partition(":")
        settings = solvers.run_settings(name, dict(kv.split("=", 1)
                                                   for kv in extra.split(",") if kv))
    with settings:
        prob, steps = build(problem, level, comm)
        t0 = time.perf_counter()
        for step in steps:
            reports += step()
        t_solve = time.perf_counter() - t0
    factor = {}
    if not strategy.startswith("iterative"):   # MUMPS: entries of the factors (all ranks)
        F = prob.snes.getKSP().getPC().getFactorMatrix()
        factor = {"blr": F.getMumpsIcntl(35), "factor_entries_full_rank": F.getMumpsInfog(9),
                  "factor_entries_effective": F.getMumpsInfog(29),
                  "factor_mb_total": F.getMumpsInfog(22)}
    factor["factorisations"] = getattr(prob.solver, "factorisations", None)
    events = {name: round(comm.allreduce(PETSc.Log.Event(name).getPerfInfo()["time"],
                                         op=MPI.MAX), 2) for name in EVENTS}
    newton = sum(r.iterations for r in reports)
    krylov = sum(r.linear_iterations for r in reports)
    rss = comm.gather(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, root=0)
    t_solve = comm.allreduce(t_solve, op=MPI.MAX)
    if comm.rank == 0:
        print(json.dumps({"problem": problem, "level": level, "strategy": strategy,
                          "ranks": comm.size, "unknowns": prob.num_dofs, "newton": newton,
                          "krylov": krylov, "solve_s": t_solve,
                          "s_per_newton": t_solve / max(newton, 1),
                          "peak_mb_per_rank": [float(x) for x in np.round(rss, 1)],
                          "events_s": events,
                          **factor}))


def launch(problem, level, strategy, ranks=1, timeout=7200):
    """Run :func:`one` in a fresh process (``ranks`` MPI processes); its JSON, or a failure."""
    here = Path(__file__).resolve()
    cmd = [sys.executable, str(here), "--one", problem, str(level), strategy]
    if ranks > 1:
        cmd = [str(Path(sys.executable).parent / "mpiexec"), "-n", str(ranks)] + cmd
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"problem": problem, "level": level, "strategy": strategy, "ranks": ranks,
                "failed": f"timeout {timeout} s"}
    lines = [ln for ln in p.stdout.splitlines() if ln.startswith("{")]
    if p.returncode != 0 or not lines:
        tail = (p.stderr or p.stdout).strip().splitlines()[-1:] or ["?"]
        return {"problem": problem, "level": level, "strategy": strategy, "ranks": ranks,
                "failed": f"exit {p.returncode}: {tail[0][:200]}"}
    out = json.loads(lines[-1])
    out["wall_s"] = time.perf_counter() - t0
    return out


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--one", nargs=3, metavar=("PROBLEM", "LEVEL", "STRATEGY"))
    parser.add_argument("--groove", type=int, nargs="*", default=[0, 1, 2])
    parser.add_argument("--ball", type=int, nargs="*", default=[2, 3, 4])
    parser.add_argument("--strategies", nargs="*", default=["direct", "iterative"],
                        help="direct, iterative, or blr<eps> (MUMPS BLR, e.g. blr1e-8)")
    parser.add_argument("--ranks2", action="store_true",
                        help="also run the largest size of each problem on 2 ranks")
    parser.add_argument("--out", default="benchmarks/results/solvers.json")
    args = parser.parse_args()
    if args.one:
        one(args.one[0], int(args.one[1]), args.one[2])
        return
    rows = []
    for problem, levels in (("groove", args.groove), ("ball", args.ball)):
        for level in levels:
            for strategy in args.strategies:
                r = launch(problem, level, strategy)
                rows.append(r)
                print(json.dumps(r), flush=True)
        if args.ranks2 and levels:
            for strategy in args.strategies:
                r = launch(problem, levels[-1], strategy, ranks=2)
                rows.append(r)
                print(json.dumps(r), flush=True)
    print(f"\n{'problem':8s} {'lvl':>3s} {'strategy':9s} {'ranks':>5s} {'unknowns':>9s} "
          f"{'newton':>6s} {'krylov':>6s} {'s/newton':>9s} {'peak MB/rank':>14s}")
    for r in rows:
        if "failed" in r:
            print(f"{r['problem']:8s} {r['level']:3d} {r['strategy']:9s} {r['ranks']:5d} "
                  f"failed: {r['failed']}")
            continue
        print(f"{r['problem']:8s} {r['level']:3d} {r['strategy']:9s} {r['ranks']:5d} "
              f"{r['unknowns']:9d} {r['newton']:6d} {r['krylov']:6d} "
              f"{r['s_per_newton']:9.2f} {max(r['peak_mb_per_rank']):14.0f}")
    print("\niterative / direct cost per Newton iteration (serial):")
    ok = {(r["problem"], r["level"], r["strategy"], r["ranks"]): r for r in rows
          if "failed" not in r}
    for (problem, level, strategy, ranks), r in ok.items():
        d = ok.get((problem, level, "direct", 1))
        if strategy == "iterative" and ranks == 1 and d:
            print(f"  {problem} level {level} ({r['unknowns']} unknowns): "
                  f"{r['s_per_newton'] / d['s_per_newton']:.2f}")
    for (problem, level, strategy, ranks), r in ok.items():
        s = ok.get((problem, level, strategy, 1))
        if ranks == 2 and s:
            print(f"  2-rank speed-up {problem} level {level} {strategy}: "
                  f"{s['solve_s'] / r['solve_s']:.2f}, peak memory per rank "
                  f"{max(r['peak_mb_per_rank']):.0f} MB vs serial "
                  f"{s['peak_mb_per_rank'][0]:.0f} MB")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()

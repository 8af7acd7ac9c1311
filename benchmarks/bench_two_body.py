"""Benchmark of 3D two-body contact with a deformable master (issue: two deformable bodies).

Part 1, one Newton solve of a box pressed and slid on a deformable block
(about 50k unknowns, P1 tetrahedra): per Newton iteration, the time of the
contact (master gather, box-tree refit and projection, the C++ nodal kernel,
the C++ insertion into PETSc) against the bulk UFL assembly and the rest of
the iteration (the linear solve).  Goal: contact ≤ 10 % of an iteration.

Part 2, the projection throughput of the kernel's search
(:class:`tribofx.two_body.MasterSurface3`: build, refit, project) against
libigl's AABB tree (``igl.AABB``, PyPI ``libigl``) on the same triangulated
surface and the same points, in the same run, one core; the nearest
distances are compared.  Goal: at least as fast per core as libigl (the
process is pinned to one CPU for this part: libigl threads its points).

Usage: .venv/bin/python benchmarks/bench_two_body.py [results.json] [--quick]
(libigl: ``.venv/bin/python -m pip install libigl``; without it part 2 reports
the kernel alone.)
"""

from __future__ import annotations

import json
import os
import platform
import sys
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401,E402  (before dolfinx / petsc4py)
import numpy as np  # noqa: E402
from mpi4py import MPI  # noqa: E402
from timing import Timer  # noqa: E402  (benchmarks/timing.py)

from tribofx.two_body import MasterSurface3  # noqa: E402

sys.path.insert(0, str(Path(__file__).parents[1] / "tests"))
from test_two_body_3d import box  # noqa: E402

__all__ = ["main"]


def newton_split(n_slave, n_master):
    """Time one press-and-slide solve; returns the per-iteration split (dict)."""
    from tribofx.interfaces import TwoBodyContact
    from tribofx.problem import Problem

    slave = box(0.0, 1.0, 0.0, 0.5, n_slave, n_slave // 2, "slave")
    push = slave.add_dirichlet("top", np.array([0.0, 0.0, -0.02]))
    master = box(-0.5, 1.5, -0.5, 0.0, n_master, n_master // 4, "master")
    master.add_dirichlet("bottom", np.zeros(3))
    contact = TwoBodyContact(slave, "bottom", master, "top", 10.0, friction=0.3)
    problem = Problem([slave, master, contact], name="bench_two_body")
    problem.solve()
    problem.commit()
    push.value[:] = [0.05, 0.02, -0.02]
    timer = Timer()
    timer.time_split(contact, ("add_residual", "add_jacobian", "_pairs"), problem)
    t0 = time.perf_counter()
    rep = problem.solve()
    total = time.perf_counter() - t0
    its = rep.iterations
    t = timer.total
    contact_t = t.get("add_residual", 0.0) + t.get("add_jacobian", 0.0)
    bulk = t.get("_assemble_residual", 0.0) + t.get("_assemble_jacobian", 0.0)
    return {"num_dofs": problem.num_dofs, "slave_nodes": int(len(contact._q)),
            "newton_iterations": its, "time_per_iteration_s": total / max(its, 1),
            "contact_fraction": contact_t / total,
            "contact_search_fraction": t.get("_pairs", 0.0) / total,
            "bulk_assembly_fraction": bulk / total,
            "solve_and_rest_fraction": 1 - (contact_t + bulk) / total}


def surface(n, rng):
    """Triangulated wavy surface z = f(x, y) on [0, 1]², (n + 1)² nodes, 2n² triangles."""
    u = np.linspace(0, 1, n + 1)
    X, Y = np.meshgrid(u, u, indexing="xy")
    Z = 0.1 * np.sin(4 * X) * np.cos(3 * Y) + 0.002 * rng.standard_normal(X.shape)
    nodes = np.c_[X.ravel(), Y.ravel(), Z.ravel()]
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="xy")
    a = (j * (n + 1) + i).ravel()
    tris = np.concatenate([np.c_[a, a + 1, a + n + 2], np.c_[a, a + n + 2, a + n + 1]])
    return nodes, tris.astype(np.int32)


def throughput(n, n_points, rng):
    """Kernel search against igl.AABB on the same surface and points, pinned to one core.

    libigl's ``squared_distance`` runs its points on several threads; the
    comparison is per core, so the process is pinned to one CPU for it.
    """
    cpus = os.sched_getaffinity(0)
    os.sched_setaffinity(0, {min(cpus)})
    try:
        return _throughput(n, n_points, rng)
    finally:
        os.sched_setaffinity(0, cpus)


def _throughput(n, n_points, rng):
    nodes, tris = surface(n, rng)
    xy = rng.uniform(0, 1, (n_points, 2))
    pts = np.c_[xy, 0.1 * np.sin(4 * xy[:, 0]) * np.cos(3 * xy[:, 1])
                + 0.01 * rng.standard_normal(n_points)]
    out = {"triangles": int(len(tris)), "points": n_points}
    t0 = time.perf_counter()
    master = MasterSurface3(nodes, tris)
    out["kernel_build_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    res = master.project(pts)
    out["kernel_project_s"] = time.perf_counter() - t0
    moved = np.ascontiguousarray(nodes + 0.001 * rng.standard_normal(nodes.shape))
    t0 = time.perf_counter()
    master.refit(moved)
    out["kernel_refit_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    MasterSurface3(moved, tris)
    out["kernel_rebuild_s"] = time.perf_counter() - t0
    try:
        import igl
    except ImportError:
        out["libigl"] = "not installed (pip install libigl)"
        return out
    tri64 = tris.astype(np.int64)
    t0 = time.perf_counter()
    tree = igl.AABB()
    tree.init(nodes, tri64)
    out["igl_build_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    d2, _, _ = tree.squared_distance(nodes, tri64, pts)
    out["igl_project_s"] = time.perf_counter() - t0
    out["max_distance_difference"] = float(np.abs(np.sqrt(d2) - res["distance"]).max())
    out["speed_ratio_project"] = out["igl_project_s"] / out["kernel_project_s"]
    out["speed_ratio_build"] = out["igl_build_s"] / out["kernel_build_s"]
    return out


def main(argv: list[str]) -> dict:
    quick = "--quick" in argv
    args = [a for a in argv if not a.startswith("--")]
    out = Path(args[0]) if args else Path(__file__).parent / "results" / "two_body.json"
    rng = np.random.default_rng(2026)
    res = {"machine": platform.processor() or platform.machine(),
           "mpi_size": MPI.COMM_WORLD.size,
           "newton": newton_split(*((6, 8) if quick else (20, 32))),
           "search": throughput(*((60, 20_000) if quick else (224, 200_000)), rng)}
    if MPI.COMM_WORLD.rank == 0:
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(json.dumps(res, indent=1))
        print(json.dumps(res, indent=1))
    return res


if __name__ == "__main__":
    main(sys.argv[1:])

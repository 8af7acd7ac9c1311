"""Mesh convergence of ``ehl-cylinder-layer``: the film measures at one load on refined layers."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from mpi4py import MPI

from ..cases import ehl_cylinder_layer as Case
from ..params import InputError

if TYPE_CHECKING:
    from collections.abc import Iterable

__all__ = ["mesh_convergence"]


def mesh_convergence(v: Case.Params, levels: Iterable[int] = (0, 1, 2), W: float | None = None,
                     steps: int | None = None,
                     comm: MPI.Comm = MPI.COMM_WORLD) -> list[dict[str, Any]]:
    """Film measures at one load W for the mesh levels ``levels`` (all else as in ``v``).

    Each level (element size 0.04/2^level mm along Γ_l) is loaded in ``steps``
    increments (default ``v.steps``) to W (default ``v.W``).  Returns a list
    of dicts (level, h_fine, num_dofs, h_min, h_central, p_max, newton_iterations)
    and, from the second level on, the differences ``d_h_min``, ``d_p_max`` to the
    previous level (relative to the finer value).
    """
    if v.mesh_file:
        raise InputError("mesh_convergence refines the built layer: not with mesh_file")
    W = v.W if W is None else W
    steps = v.steps if steps is None else steps
    rows: list[dict[str, Any]] = []
    for level in levels:
        vv = v.replace(mesh=int(level), W=W, steps=steps)
        run = Case.build(vv, comm)
        loads, _ = Case.load_control(run, vv)
        loads.march(W, steps, predictor=False)
        m = Case.measures(run, vv)
        row = {"level": int(level), "h_fine": 0.04 / 2 ** int(level),
               "num_dofs": run.problem.num_dofs, "h_min": m["h_min"], "h_central": m["h_central"],
               "p_max": m["p_max"], "newton_iterations": list(loads.record)}
        if rows:
            for k in ("h_min", "p_max"):
                row[f"d_{k}"] = abs(row[k] - rows[-1][k]) / abs(row[k])
        rows.append(row)
    return rows

"""Run outputs: ``summary.json``, VTX (.bp) fields for ParaView and PNG plots."""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from .params import CaseParams, declared

if TYPE_CHECKING:
    from collections.abc import Mapping

    from dolfinx import fem
    from dolfinx.io import VTXWriter
    from mpi4py import MPI

__all__ = ["RunRecord", "SubRecord", "VTXSeries", "bp4_steps", "jsonable", "write_summary",
           "write_vtx"]


def jsonable(obj: object) -> Any:
    """``obj`` with NumPy arrays and scalars (also inside dicts, lists, tuples) as JSON types.

    An infinite float (e.g. ``E2=inf``, a rigid body) becomes the string "inf"
    ("-inf"): strict JSON has no infinity.
    """
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, (np.floating, np.integer, np.bool_)):
        obj = obj.item()
    if isinstance(obj, float) and obj in (math.inf, -math.inf):
        return "inf" if obj > 0 else "-inf"
    return obj


class RunRecord:
    """Collects what a run reports and writes ``summary.json`` (rank 0 only).

    The summary holds: case name, status, parameters with units, results (a dict
    of value/unit pairs or plain values), Newton iterations per step, wall time,
    number of unknowns, DOLFINx version and MPI size; ``warnings`` if any
    (:meth:`warn`).

    ``params`` is the case's :class:`~tribofx.params.CaseParams` (the units from its
    declaration; ``units`` may add more) or {name: value} with ``units`` {name: unit}.
    """

    profile: Any   # what a case's run keeps for its plot (``plot(profile, outdir)``)

    def __init__(self, case: str, params: CaseParams | Mapping[str, Any],
                 units: Mapping[str, str] | None, outdir: str | Path, comm: MPI.Comm) -> None:
        import dolfinx

        if isinstance(params, CaseParams):
            units = {**{p.name: p.unit for p in declared(type(params))}, **(units or {})}
            params = params.as_dict()
        units = cast("Mapping[str, str]", units)   # given with a dict of parameters

        self.comm = comm
        self.outdir = Path(outdir)
        self.t0 = time.perf_counter()
        self.data: dict[str, Any] = {
            "case": case,
            "status": "running",
            "units": {"length": "mm", "force": "N", "stress": "MPa", "time": "s"},
            "parameters": {k: {"value": params[k], "unit": units[k]} for k in params},
            "results": {},
            "newton_iterations": [],
            "num_dofs": None,
            "wall_time_s": None,
            "dolfinx_version": dolfinx.__version__,
            "mpi_size": comm.size,
        }

    def result(self, key: str, value: object, unit: str = "-") -> None:
        """Record a scalar or list result with its unit."""
        self.data["results"][key] = {"value": value, "unit": unit}

    def warn(self, message: str) -> None:
        """Record a warning (``warnings`` of the summary; the CLI prints them)."""
        self.data.setdefault("warnings", []).append(message)

    def write(self, status: str) -> dict[str, Any]:
        """Write ``summary.json`` with ``status`` ("ok" or "failed: …")."""
        self.data["status"] = status
        self.data["wall_time_s"] = time.perf_counter() - self.t0
        write_summary(self.comm, self.outdir / "summary.json", self.data)
        return self.data


class SubRecord:
    """Minimal stand-in for :class:`RunRecord` for the runs of a study."""

    profile: Any   # what the run keeps for its plot, as on a RunRecord

    def __init__(self) -> None:
        self.data: dict[str, Any] = {"newton_iterations": [], "results": {}}
        self.profile = None

    def result(self, key: str, value: object, unit: str = "-") -> None:
        """Record ``key`` = ``value`` (unit) as :meth:`RunRecord.result` does."""
        self.data["results"][key] = {"value": value, "unit": unit}

    def warn(self, message: str) -> None:
        """Record a warning as :meth:`RunRecord.warn` does."""
        self.data.setdefault("warnings", []).append(message)


def write_summary(comm: MPI.Comm, path: str | Path, data: Mapping[str, Any]) -> None:
    """Write the dict ``data`` as JSON to ``path`` on rank 0 (NumPy values converted)."""
    if comm.rank == 0:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(jsonable(data), indent=2))


def write_vtx(comm: MPI.Comm, path: str | Path, functions: list[fem.Function],
              t: float = 0.0) -> None:
    """Write ``functions`` (same mesh, Lagrange) to the VTX file ``path``."""
    from dolfinx.io import VTXWriter

    with VTXWriter(comm, str(path), functions, engine="BP4") as w:
        w.write(t)


class VTXSeries:
    """VTX time series for ParaView: one ``<stem>.bp`` per mesh, one write per step.

    ``groups`` is {file stem: [Functions on one mesh]} (e.g. a case's
    ``vtx_fields``).  Displacement-like vector fields (u, the shape change w)
    are what ParaView's "Warp By Vector" takes: warping by w shows the worn
    undeformed configuration X = X̂ + w, by u the deformed one x = X̂ + u.
    Used as a context manager or closed by :meth:`close`.  ``outdir`` None
    (a sub-run of a study, which has no folder of its own): nothing is written.
    The files are opened at the first :meth:`write`, so a series with no step
    (a resumed sweep with nothing left to do) leaves no empty file.
    """

    writers: list[VTXWriter]

    def __init__(self, comm: MPI.Comm, outdir: str | Path | None,
                 groups: Mapping[str, list[fem.Function]]) -> None:
        self.comm, self.groups, self.writers = comm, groups, []
        self.outdir = None if comm.bcast(outdir is None, root=0) else Path(
            comm.bcast(str(outdir), root=0))   # one file for all ranks

    def _open(self) -> None:
        from dolfinx.io import VTXWriter

        assert self.outdir is not None   # opened by write() only while not closed
        if self.comm.rank == 0:
            self.outdir.mkdir(parents=True, exist_ok=True)
        self.comm.barrier()
        self.writers = [VTXWriter(self.comm, str(self.outdir / f"{stem}.bp"), fns, engine="BP4")
                        for stem, fns in self.groups.items()]

    def write(self, t: float) -> None:
        """Write every group at time ``t`` (collective; the first write opens the files)."""
        if self.outdir is not None and not self.writers:
            self._open()
        for w in self.writers:
            w.write(float(t))

    def close(self) -> None:
        """Close the files (no further write)."""
        for w in self.writers:
            w.close()
        self.writers, self.outdir = [], None

    def __enter__(self) -> VTXSeries:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def bp4_steps(path: str | Path) -> int:
    """Return the number of steps in the BP4 file ``path`` (index: 64 bytes + 64 per step)."""
    return (Path(path, "md.idx").stat().st_size - 64) // 64

"""The latest accepted state of a slow-time run on disk (``--out/checkpoint``).

Written by :meth:`tribofx.stepper.Stepper.run` after every accepted step and read
back by ``--resume`` (:mod:`tribofx.restart`).
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt
from mpi4py import MPI

if TYPE_CHECKING:
    from dolfinx import fem

__all__ = ["Checkpoint", "assign_fields", "field_arrays", "field_names"]


def field_arrays(objects: Iterable[fem.Function | fem.Constant]) -> list[npt.NDArray[Any]]:
    """Return copies of the values of ``objects`` (Functions: local arrays with ghosts)."""
    return [(f.x.array if hasattr(f, "x") else np.asarray(f.value)).copy() for f in objects]


def assign_fields(objects: Iterable[fem.Function | fem.Constant],
                  arrays: Iterable[npt.NDArray[Any]]) -> None:
    """Set ``objects`` (Functions, Constants) to ``arrays`` (as from :func:`field_arrays`)."""
    for f, a in zip(objects, arrays):
        if hasattr(f, "x"):
            f.x.array[:] = a
        else:
            f.value = a


def field_names(objects: Iterable[fem.Function | fem.Constant]) -> list[str]:
    """Return names of ``objects`` for a checkpoint (Functions by name, Constants by index)."""
    return [getattr(f, "name", None) or f"constant{i}" for i, f in enumerate(objects)]


class Checkpoint:
    """The latest accepted state on disk: ``state_r<rank>.npz`` per rank and ``state.json``.

    The JSON holds the scalars of the state (a stepper's time, Δt, cut level,
    step count and PI memory; a sweep's position, :mod:`tribofx.restart`), the MPI size
    and the names and shapes of the arrays; the npz the local arrays (ghosts
    included) of every state field, in the order given.  ``state["steps"]``
    counts the writes (it detects a torn write).  Files are
    written to a temporary name and renamed; a kill between the arrays and the
    JSON is detected on reading (each npz holds its step count).  The directory
    must be the same (shared) on all ranks.
    """

    def __init__(self, directory: str | os.PathLike[str], comm: MPI.Comm) -> None:
        self.dir, self.comm = Path(directory), comm

    def write(self, state: dict[str, Any], names: Iterable[str],
              history: dict[str, Any] | None = None) -> None:
        """Write ``state`` (``fields``: arrays, ``steps``: int, other JSON scalars); ``names``.

        ``history``: a JSON-able dict of the run's records so far (the case's
        time series), restored with the state on ``--resume``.
        """
        self.dir.mkdir(parents=True, exist_ok=True)
        npz = self.dir / f"state_r{self.comm.rank}.npz"
        tmp = self.dir / f".state_r{self.comm.rank}.tmp.npz"
        np.savez(tmp, steps=np.array(state["steps"]),
                 **{f"field{i}": a for i, a in enumerate(state["fields"])})
        os.replace(tmp, npz)
        self.comm.barrier()
        if self.comm.rank == 0:
            meta = {k: x for k, x in state.items() if k != "fields"}
            meta.update(mpi_size=self.comm.size, fields=list(names),
                        shapes=[list(np.shape(a)) for a in state["fields"]],
                        history=history or {})
            tmp = self.dir / ".state.tmp.json"
            tmp.write_text(json.dumps(meta))   # no indent: histories may be long
            os.replace(tmp, self.dir / "state.json")
        self.comm.barrier()

    def read(self) -> dict[str, Any]:
        """Return the state dict written last (one-line error for another partition)."""
        error, meta, fields, torn = None, None, [], False
        try:
            meta = json.loads((self.dir / "state.json").read_text())
            if meta["mpi_size"] != self.comm.size:
                error = (f"checkpoint {self.dir} was written on {meta['mpi_size']} ranks, "
                         f"not {self.comm.size}")
            else:
                with np.load(self.dir / f"state_r{self.comm.rank}.npz") as data:
                    fields = [data[f"field{i}"] for i in range(len(meta["fields"]))]
                    torn = "steps" in data and int(data["steps"]) != meta["steps"]
        except Exception as err:   # unreadable on this rank (missing, truncated, not shared)
            error = f"cannot read checkpoint {self.dir} on rank {self.comm.rank}: {err}"
        # the same decision on every rank (a failure on one rank must not hang the others)
        errors = [e for e in self.comm.allgather(error) if e is not None]
        if errors:
            raise ValueError(errors[0])
        # a kill between the arrays and the JSON: the arrays are a step ahead
        if self.comm.allreduce(torn, op=MPI.LOR):
            raise ValueError(f"checkpoint {self.dir} is incomplete (killed while writing); "
                             "restart the run without --resume")
        assert meta is not None     # read (no error on any rank)
        own = ("mpi_size", "fields", "shapes", "history")
        return {**{k: x for k, x in meta.items() if k not in own}, "fields": fields,
                "history": meta.get("history", {})}

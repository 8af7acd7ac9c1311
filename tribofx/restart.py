"""Resuming a slow-time run from its checkpoint (``tribofx run ... --resume``).

A resumable case's ``run(v, record, ..., checkpoint, resume)`` builds its
:class:`tribofx.stepper.Stepper` with ``checkpoint=DIR`` (the state is written
after every accepted step, with :attr:`Stepper.history`, the case's records
so far) and calls :func:`open_history` before its first step:

* a fresh run: the history starts empty, with the physical parameters in it;
* ``resume=True``: the stepper's state and history are read back, and the
  parameters of the checkpoint must be the run's (the solver strategy may
  differ: it does not change the answer beyond the solver tolerance).

The case keeps every record it reports in the returned dict (JSON types
only), so a resumed run reports the whole time series.  A resumed run writes
its VTX series into files of their own (:func:`series_stem`), beside the
series of the interrupted run.

A continuation sweep (loads, then speeds or sealed pressures, for each
variant of the model) has no time step; its cases use a
:class:`SweepJournal`: after every recorded point of the sweep it writes the
state of the variant's problem, the variant's records and its *position* (which
leg of the sweep, the increments of the march in progress, the history of the
inner position search) into ``DIR/<variant>/``, and a resumed run restores the
state and continues from that position on the same step sequence.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import numpy as np
import numpy.typing as npt

from . import interrupt
from .checkpoint import Checkpoint, assign_fields, field_arrays, field_names
from .output import jsonable
from .params import InputError

if TYPE_CHECKING:
    from dolfinx import fem
    from mpi4py import MPI

    from .params import CaseParams
    from .stepper import Stepper

__all__ = ["SweepJournal", "check_parameters", "open_history", "series_stem", "sweep_stem"]

#: parameters that select how the problem is solved, not which problem
SOLVER_PARAMETERS = ("solver", "force_control")
# parameters a checkpoint may not record: missing, they count as these values (the defaults)
ADDED_PARAMETERS = {"tol_per": "unit_step", "error_filter": False, "controller": "i"}


def open_history(stepper: Stepper, v: CaseParams, resume: bool) -> dict[str, Any]:
    """Read back the checkpoint when resuming; return ``stepper.history``.

    ``v``: the run's parameters (a :class:`~tribofx.params.CaseParams`).  Raises
    :class:`InputError` (one line) for an incomplete checkpoint, one written on
    another number of ranks, or with other physical parameters.
    """
    params = {k: x for k, x in v.as_dict().items() if k not in SOLVER_PARAMETERS}
    if resume:
        try:
            stepper.load_checkpoint()
        except (ValueError, OSError, KeyError) as err:
            raise InputError(f"cannot resume: {err}") from None
        saved = stepper.history.get("parameters")
        if saved is not None:
            added = {k: x for k, x in ADDED_PARAMETERS.items() if k in params}
            # as the checkpoint holds them
            check_parameters({**added, **saved}, json.loads(json.dumps(params)))
    stepper.history.setdefault("parameters", params)
    return stepper.history


def check_parameters(saved: Mapping[str, Any], now: Mapping[str, Any]) -> None:
    """Raise InputError (one line) unless the checkpoint's parameters ``saved`` are ``now``."""
    if saved != now:
        diff = sorted(k for k in set(saved) | set(now) if saved.get(k) != now.get(k))
        raise InputError(f"--resume with other parameters than the checkpoint's "
                         f"({', '.join(diff)})")


def series_stem(stem: str, stepper: Stepper, resume: bool) -> str:
    """File stem of a VTX series: a resumed run's series starts at its restart time."""
    return stem + (f"_from_t{stepper.t:g}" if resume else "")


def sweep_stem(stem: str, n: int) -> str:
    """File stem of a sweep's VTX series: a sweep resumed after n points starts at n."""
    return stem + (f"_from_{n}" if n else "")


class SweepJournal:
    """The checkpoint of a continuation sweep, written after every recorded point.

    Per variant ``name`` (a model of ``compare``, a stroke), ``DIR/<name>/`` holds
    a :class:`tribofx.checkpoint.Checkpoint`: the arrays of the state objects
    (Functions and Constants, :meth:`save`), and as its history the variant's
    ``records`` (the case's lists of measures, JSON), its ``position`` (a dict
    the case defines: the leg, the march increments, …) and the number of
    further arrays saved after the objects.  ``DIR/state.json`` lists the variants written and the
    parameters of the run.  Every :meth:`save` ends with
    :func:`tribofx.interrupt.check` (a signal stops the run after the point
    written).

    Args:
        directory: the checkpoint directory (None: nothing is written, no resume).
        comm: the run's communicator.
        v: the run's parameters, a :class:`~tribofx.params.CaseParams` (a resume must
            have the same ones).
        resume: read the checkpoint back.
    """

    saved: dict[str, dict[str, Any]]    # per variant: the state read back (Checkpoint.read)
    order: list[str]                    # the variants written, in order
    steps: int                          # points written (the checkpoints' step count)

    def __init__(self, directory: str | os.PathLike[str] | None, comm: MPI.Comm, v: CaseParams,
                 resume: bool = False) -> None:
        self.dir = None if directory is None else Path(directory)
        self.comm = comm
        self.params = jsonable({k: x for k, x in v.as_dict().items() if k not in SOLVER_PARAMETERS})
        self.saved, self.order, self.steps = {}, [], 0
        if resume:
            self._read()

    def _read(self) -> None:
        top, error = None, None
        if self.comm.rank == 0:     # read once, decided on all ranks (no rank left waiting)
            try:
                # (no directory: the TypeError below, "cannot resume")
                top = json.loads((cast(Path, self.dir) / "state.json").read_text())
                top = {"variants": list(top["variants"]), "parameters": top["parameters"]}
            except (ValueError, OSError, KeyError, TypeError) as err:
                error = f"cannot resume: {err}"
        top, error = self.comm.bcast((top, error), root=0)
        if error is not None:
            raise InputError(error)
        check_parameters(top["parameters"], self.params)
        order = top["variants"]
        try:
            saved = {name: Checkpoint(cast(Path, self.dir) / name, self.comm).read()
                     for name in order}
        except ValueError as err:    # the same on all ranks (Checkpoint.read)
            raise InputError(f"cannot resume: {err}") from None
        self.saved, self.order = saved, order
        self.steps = max(int(s["steps"]) for s in saved.values()) if saved else 0

    # -- reading ----------------------------------------------------------------------
    def records(self, name: str, **empty: Any) -> dict[str, Any]:
        """Return the variant's records: the saved ones on resume, else ``empty``."""
        saved = self.saved.get(name)
        return saved["history"]["records"] if saved is not None else dict(empty)

    def position(self, name: str) -> dict[str, Any] | None:
        """Return the saved position of the variant (None: a fresh variant)."""
        saved = self.saved.get(name)
        return None if saved is None else saved["history"]["position"]

    def restore(self, name: str,
                objects: Sequence[fem.Function | fem.Constant]) -> list[npt.NDArray[Any]]:
        """Copy the saved arrays of the variant into ``objects`` (Functions, Constants).

        Returns the further arrays saved with them (``arrays`` of :meth:`save`).
        """
        saved = self.saved[name]["fields"]
        n = len(saved) - int(self.saved[name]["history"].get("arrays", 0))
        arrays, extra = saved[:n], saved[n:]
        bad = len(arrays) != len(objects) or any(
            np.shape(a) != np.shape(o.x.array if hasattr(o, "x") else o.value)
            for a, o in zip(arrays, objects))
        if self.comm.allreduce(bad):
            raise InputError(f"cannot resume: the checkpoint of {name!r} does not fit the "
                             "problem (another mesh?)")
        assign_fields(objects, arrays)
        return extra

    # -- writing ----------------------------------------------------------------------
    def save(self, name: str, objects: Sequence[fem.Function | fem.Constant],
             records: Mapping[str, Any], position: Mapping[str, Any],
             arrays: Iterable[npt.ArrayLike] = ()) -> None:
        """Write the variant's state, records and position; then stop on a signal.

        ``objects``: the state (Functions, Constants) restored by :meth:`restore`;
        ``records``: the variant's JSON-able records (NumPy arrays are converted);
        ``position``: a JSON-able dict the case reads back by :meth:`position`;
        ``arrays``: further local arrays (e.g. a second state the sweep returns
        to), given back by :meth:`restore`.
        """
        if self.dir is not None:
            self.steps += 1
            extra = [np.asarray(a) for a in arrays]
            fields = field_arrays(objects) + extra
            names = field_names(objects) + [f"array{i}" for i in range(len(extra))]
            history = {"records": jsonable(records), "position": jsonable(position),
                       "arrays": len(extra)}
            Checkpoint(self.dir / name, self.comm).write(
                {"steps": self.steps, "fields": fields}, names, history)
            if name not in self.order:
                self.order.append(name)
            if self.comm.rank == 0:
                top = {"variants": self.order, "steps": self.steps,
                       "parameters": self.params, "mpi_size": self.comm.size}
                tmp = self.dir / ".state.tmp.json"
                tmp.write_text(json.dumps(top))
                tmp.replace(self.dir / "state.json")
            self.comm.barrier()
        interrupt.check(self.comm)

"""One variant of a journalled continuation sweep: its records, series, checkpoint and failure.

A sweep (the load and speed sweeps of the soft-EHL cases, the strokes of the
O-ring) runs each *variant* (a model of ``compare``, a stroke) along its
continuation path; what every variant needs besides the path is the same and
lives here:

* its records (lists of measures the case defines), restored from the
  :class:`tribofx.restart.SweepJournal` on ``--resume``, and its saved position;
* a ParaView time series of its fields (:class:`tribofx.output.VTXSeries`, one
  index per recorded point, the point's coordinates in ``series_points``; a
  resumed run writes its points into series of their own);
* :meth:`SweepVariant.save` after every converged point (state, records and the
  case's position; then it stops on a signal, :mod:`tribofx.interrupt`) and
  :meth:`SweepVariant.resume` (the saved state back into the problem);
* the end of the variant as a context: the series closed, the Newton iterations
  recorded, and a failed or interrupted run (``NewtonDivergence``,
  ``Interrupted``) carrying ``model`` = the run at its last converged point.

The case keeps only its physics: what a point measures, where it goes next.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from types import TracebackType
from typing import TYPE_CHECKING, Any, Literal, cast

from . import interrupt
from .output import VTXSeries
from .problem import NewtonDivergence
from .restart import sweep_stem

if TYPE_CHECKING:
    import numpy.typing as npt
    from dolfinx import fem
    from mpi4py import MPI
    from tqdm import tqdm

    from .output import RunRecord
    from .restart import SweepJournal

__all__ = ["SweepVariant"]


class SweepVariant:
    """The journalled records, series and checkpoint of one variant ``key`` of a sweep.

    Args:
        journal: the sweep's :class:`tribofx.restart.SweepJournal`.
        key: the variant's name in the journal and in ``series_points``.
        run: what a failed run reports (``err.model``), e.g. ``(body, film, problem)``.
        state: the objects of the variant's state (Functions, Constants) saved and restored.
        record: the run record (``data``, ``outdir``).
        fields: ``{name: [Function, ...]}`` of the VTX series, written as
            ``<prefix><name>_series.bp``.
        prefix: file prefix of the series (``"full_"`` for a variant of ``compare``).
        records: the names of the variant's record lists, or ``{name: default}``;
            ``"points"`` (the series' coordinates, one per point) and ``"its"``
            (Newton iterations) are added.
        comm: the communicator of the series.
        progress: a progress bar, advanced by the restored ``progress_key`` records.
        newton: add the variant's ``its`` to the run's Newton iterations at the end
            (False: the case records them itself).
    """

    def __init__(self, journal: SweepJournal, key: str, run: object,
                 state: Sequence[fem.Function | fem.Constant], record: RunRecord,
                 fields: Mapping[str, list[fem.Function]], prefix: str = "",
                 records: Iterable[str] | Mapping[str, Any] = ("steps",),
                 comm: MPI.Comm | None = None, progress: tqdm | None = None,
                 progress_key: str = "steps", newton: bool = True) -> None:
        self.journal, self.key, self.run, self.state = journal, key, run, state
        self.record, self.newton = record, newton
        defaults = dict(records) if isinstance(records, dict) else {k: [] for k in records}
        defaults.setdefault("its", [])
        defaults.setdefault("points", [])
        self.records = journal.records(key, **defaults)
        self.position = journal.position(key)
        self.points, self.its = self.records["points"], self.records["its"]
        if progress is not None and self.records.get(progress_key):
            progress.update(len(self.records[progress_key]))
        # (every caller gives comm: VTXSeries needs one)
        self.series = VTXSeries(cast("MPI.Comm", comm), getattr(record, "outdir", None),
                                {sweep_stem(f"{prefix}{k}_series", len(self.points)): f
                                 for k, f in fields.items()})
        record.data.setdefault("series_points", {})[key] = self.points

    def __getitem__(self, name: str) -> list[Any]:
        """Return the record list ``name``."""
        return self.records[name]

    def write(self, point: float | Sequence[float]) -> None:
        """Append the point's coordinates (a number or a list) and write the fields there."""
        self.points.append(point)
        self.series.write(len(self.points) - 1)

    def save(self, position: Mapping[str, Any],
             arrays: Iterable[npt.ArrayLike] = ()) -> None:
        """Checkpoint the state, the records and the case's ``position`` (a dict)."""
        self.journal.save(self.key, self.state, self.records, position, arrays=list(arrays))

    def resume(self) -> list[npt.NDArray[Any]]:
        """Copy the saved state back (a resumed variant); returns the saved extra arrays."""
        return self.journal.restore(self.key, self.state)

    def __enter__(self) -> SweepVariant:
        interrupt.arm()   # gmsh (a mesh built for the variant) resets the SIGTERM handler
        return self

    def __exit__(self, kind: type[BaseException] | None, err: BaseException | None,
                 tb: TracebackType | None) -> Literal[False]:
        self.series.close()
        if self.newton:
            self.record.data["newton_iterations"].extend(self.its)
        if isinstance(err, (NewtonDivergence, interrupt.Interrupted)):
            err.model = self.run    # restored to its last converged point
        return False

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
* its *legs*, journalled by the variant itself: :meth:`SweepVariant.march` (a
  continuation marched to a target) and :meth:`SweepVariant.loop` (a loop over
  points, e.g. loads or sealed pressures) save the state, the records and the
  position (the leg, its increments or the points done, the legs finished, the
  secant states of the searches :meth:`~SweepVariant.track` names and what
  :meth:`~SweepVariant.keep` adds) after every accepted step, then stop on a
  signal (:mod:`tribofx.interrupt`); on ``--resume`` :meth:`SweepVariant.resume`
  puts the state back, and the legs skip what was done and continue where the
  run stopped, on the same step sequence;
* the end of the variant as a context: the series closed, the Newton iterations
  recorded, and a failed or interrupted run (``NewtonDivergence``,
  ``Interrupted``) carrying ``model`` = the run at its last converged point.

The case keeps only its physics: what a point measures, where it goes next; it
threads no resume position through its functions.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from types import TracebackType
from typing import TYPE_CHECKING, Any, Literal, cast

from . import interrupt
from .output import VTXSeries
from .params import InputError
from .problem import NewtonDivergence
from .restart import sweep_stem

if TYPE_CHECKING:
    import numpy.typing as npt
    from dolfinx import fem
    from mpi4py import MPI
    from tqdm import tqdm

    from .continuation import Continuation
    from .output import RunRecord
    from .restart import SweepJournal

__all__ = ["SweepVariant", "journalled_march", "journalled_points"]


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
        self._saved = journal.position(key)     # where a resumed variant stopped (or None)
        if self._saved is not None and "finished" not in self._saved:
            raise InputError(f"cannot resume: the checkpoint of {key!r} was written by an "
                             "earlier tribofx (another journal); run again without --resume")
        self._finished: list[str] = list(self._saved["finished"]) if self._saved else []
        self._searches: dict[str, Continuation] = {}
        self._keep: dict[str, tuple[Callable[[], Any], Callable[[Any], object]]] = {}
        self._arrays: Callable[[], Iterable[npt.ArrayLike]] | None = None
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

    @property
    def resumed(self) -> bool:
        """Whether the variant continues a stopped run (it has a saved position)."""
        return self._saved is not None

    def track(self, **searches: Continuation) -> None:
        """Keep the secant state of each search (a response-controlled Continuation).

        A resumed search then makes the same trials as the uninterrupted one.
        """
        self._searches.update(searches)

    def keep(self, name: str, save: Callable[[], Any], restore: Callable[[Any], object]) -> None:
        """Further position of the case: ``save()`` (JSON) at every point, ``restore`` on resume."""
        self._keep[name] = (save, restore)

    def resume(self) -> list[npt.NDArray[Any]]:
        """Put a resumed variant back where it stopped; returns the saved extra arrays.

        The state, the tracked searches' secant states and the case's kept position
        (:meth:`keep`).
        """
        saved = cast("dict[str, Any]", self._saved)
        extra = self.journal.restore(self.key, self.state)
        for name, search in self._searches.items():
            search.set_secant_state(saved["searches"][name])
        for name, (_, restore) in self._keep.items():
            restore(saved["kept"][name])
        return extra

    def finished(self, leg: str) -> bool:
        """Whether the leg ``leg`` was finished before a resumed run stopped."""
        return leg in self._finished

    def _resuming(self, leg: str) -> dict[str, Any] | None:
        """Return the saved position if the run stopped inside ``leg`` (None otherwise)."""
        saved = self._saved
        return saved if saved is not None and saved["leg"] == leg else None

    def _save(self, leg: str, **where: Any) -> None:
        """Checkpoint the state, the records and the position inside ``leg``."""
        position = {"leg": leg, "finished": list(self._finished), **where,
                    "searches": {k: c.secant_state() for k, c in self._searches.items()},
                    "kept": {name: save() for name, (save, _) in self._keep.items()}}
        arrays = list(self._arrays()) if self._arrays is not None else []
        self.journal.save(self.key, self.state, self.records, position, arrays=arrays)

    def march(self, leg: str, continuation: Continuation, target: float,
              **kw: Any) -> list[float | None]:
        """March ``continuation`` to ``target`` as the leg ``leg``, journalled.

        After every accepted step (after the continuation's own ``on_accept``) the
        variant saves the state, the records and the position; a resumed variant
        skips the leg if it was finished, continues it from its saved parameter
        value and increments if it stopped inside it.  ``kw``: the keywords of
        :meth:`Continuation.march`.  Returns its responses.
        """
        if self.finished(leg):
            return []
        saved = self._resuming(leg)
        if saved is not None:
            continuation.resume_from(saved["done"])
            kw["increments"] = saved["increments"]
        own = continuation.on_accept

        def accepted() -> None:
            if own is not None:
                own()
            self._save(leg, done=continuation.done, increments=continuation.increments)

        continuation.on_accept = accepted
        try:
            out = continuation.march(target, **kw)
        finally:
            continuation.on_accept = own
        self._finished.append(leg)
        return out

    def loop(self, leg: str, count: int,
             arrays: Callable[[], Iterable[npt.ArrayLike]] | None = None) -> Iterator[int]:
        """Yield the points 0 … count − 1 of the leg ``leg``, saving after each, journalled.

        The body of each iteration reaches its point; when it returns, the variant
        saves the state, the records, the position and ``arrays()`` (a state the next
        point starts from).  A resumed variant yields only the points not done.
        """
        if self.finished(leg):
            return
        saved = self._resuming(leg)
        for k in range(0 if saved is None else int(saved["at"]), count):
            yield k
            self._arrays = arrays
            try:
                self._save(leg, at=k + 1)
            finally:
                self._arrays = None
        self._finished.append(leg)

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


def journalled_points(journal: SweepVariant | None, leg: str, count: int,
                      arrays: Callable[[], Iterable[npt.ArrayLike]] | None = None
                      ) -> Iterable[int]:
    """Return the points 0 … count − 1 of a leg (:meth:`SweepVariant.loop`, or plain)."""
    return range(count) if journal is None else journal.loop(leg, count, arrays)


def journalled_march(journal: SweepVariant | None, leg: str, continuation: Continuation,
                     target: float, **kw: Any) -> list[float | None]:
    """March a leg: :meth:`SweepVariant.march`, or ``continuation.march`` without a journal."""
    if journal is None:
        return continuation.march(target, **kw)
    return journal.march(leg, continuation, target, **kw)

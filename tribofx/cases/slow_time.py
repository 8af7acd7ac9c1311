"""What the slow-time cases share: the scheme, its error control, and their per-step records.

Every wear case (``wear-pin``, ``wear-ball-flat``, ``wear-ball-halfspace``,
``wear-reciprocating``, ``wear-lubricated``) takes ``scheme`` (explicit θ = 0,
implicit θ = 1, or the second-order BDF2 of :mod:`tribofx.bdf2`) and ``tol``, the
error control of :class:`tribofx.step_control.ErrorControl` (mm; 0: the fixed
step ``dt``, else ``dt`` is the first step) with ``tol_per``: ``unit_step`` (the
steps' estimates add up to tol) or ``step`` (each step's estimate within tol), and
``controller``: the step-size rule, elementary (``i``) or Gustafsson's PI (``pi``).
:func:`step_controller` turns them into the step controller of the run.

:class:`SlowTimeRecords` keeps what every such case records besides its physics:
the per-step measures (``hist``: lists keyed by measure; ``newton_iterations``)
in the stepper's ``history``, so the checkpoint written after every step carries
them and ``--resume`` continues them (:func:`tribofx.restart.open_history`
checks the checkpoint's parameters); a ParaView time series of the case's fields
at every accepted step (a resumed run writes its steps into series of their own,
:func:`tribofx.restart.series_stem`); and, around the case's own call of
:meth:`tribofx.stepper.Stepper.run`, the series closed and the case's report
written whatever happens, a failed or interrupted run carrying its model at the
last accepted step (:meth:`SlowTimeRecords.closing`).
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..output import VTXSeries
from ..params import CaseParams, InputError, param
from ..reports import RunStop
from ..restart import open_history, series_stem
from ..scheme import Scheme
from ..step_control import ERROR_MEASURES, STEP_RULES, ErrorControl, FixedStep

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable, Iterator, Mapping

    from dolfinx import fem

    from ..interfaces import Wear
    from ..output import RunRecord, SubRecord
    from ..step_control import StepController
    from ..stepper import Stepper, StepReport

__all__ = ["SCHEMES", "FilteredSchemeParams", "SchemeParams", "SlowTimeRecords", "check_scheme",
           "scheme_param", "step_controller", "wear_fields"]

SCHEMES = ("explicit", "implicit", "bdf2")


def scheme_param(default: str = "implicit", note: str = "") -> Any:
    """Return the ``scheme`` field (``note`` ends its help): explicit, implicit or bdf2."""
    return param(default, "-",
                 "slow-time scheme: explicit (θ=0), implicit (θ=1) or bdf2 (second order, "
                 f"started by one implicit step){note}", choices=SCHEMES)


@dataclass(frozen=True)
class SchemeParams(CaseParams):
    """The slow-time scheme and its error control, parameters of every wear case."""

    scheme: str = scheme_param()
    tol: float = param(
        0.0, "mm",
        "scheme=bdf2: error control, each step's estimate held at tol·Δt/T so that they add "
        "up to tol (tol_per=step: at tol; dt: the first step); 0: the fixed step dt",
        lower=0.0, closed=True)
    tol_per: str = param(
        "unit_step", "-",
        "tol per unit_step (the steps' estimates add up to tol over T) or per step (each "
        "step's estimate within tol, as ODE codes: for wear that damps its own errors, e.g. "
        "wear-ball-flat)", choices=ERROR_MEASURES)
    controller: str = param(
        "i", "-",
        "tol: the step-size rule, elementary i (the last estimate) or pi (Gustafsson's "
        "proportional-integral rule: the last two)", choices=STEP_RULES)
    #: the filter of :func:`tribofx.error_filter.filtered_defect` (:class:`FilteredSchemeParams`)
    error_filter = False


@dataclass(frozen=True)
class FilteredSchemeParams(SchemeParams):
    """:class:`SchemeParams` and ``error_filter``, for a case whose wear step is one Newton problem.

    (:func:`tribofx.error_filter.filtered_defect`.)
    """

    error_filter: bool = param(
        False, "-",
        "tol: filter each step's estimate through the step's implicit operator (the error "
        "wear damps within the step is not charged)")


def step_controller(v: SchemeParams, dt: float) -> StepController:
    """Return the step controller of a run: the fixed step ``dt`` (s), or error control.

    Error control (``tol`` > 0) starts at ``dt``.
    """
    if not v.tol:
        return FixedStep(dt)
    return ErrorControl(dt, v.tol, per=v.tol_per, rule=v.controller,
                        filtered=v.error_filter)


def check_scheme(v: SchemeParams) -> None:
    """One-line error for tol > 0 without bdf2, or a filter or PI controller without tol."""
    if v.tol > 0 and not Scheme.of(v.scheme).bdf2:
        raise InputError("tol > 0 (error control) needs scheme=bdf2")
    if v.error_filter and not v.tol > 0:
        raise InputError("error_filter filters the estimates of the error control: set tol > 0")
    if v.controller != "i" and not v.tol > 0:
        raise InputError("controller chooses the steps of the error control: set tol > 0")


def wear_fields(wear: Wear) -> dict[str, list[fem.Function]]:
    """VTX fields of a worn body: displacement and shape change (bulk), contact multiplier."""
    return {"displacement": [wear.body.u, wear.body.w], "contact": [wear.contact.lam_n]}


class SlowTimeRecords:
    """Per-step records, series and failure handling of one slow-time run of ``stepper``.

    Args:
        stepper: the :class:`tribofx.stepper.Stepper`.
        v: the run's parameter values (checked against a checkpoint on resume).
        record: the run record (``data``, ``result``, ``outdir``).
        keys: the names of the per-step measures (``hist[key]`` lists).
        fields: ``{name: [Function, ...]}`` written as ``<name>_series.bp``.
        resume: continue from the stepper's checkpoint.
    """

    def __init__(self, stepper: Stepper, v: CaseParams, record: RunRecord | SubRecord,
                 keys: Iterable[str], fields: Mapping[str, list[fem.Function]],
                 resume: bool = False) -> None:
        self.stepper, self.record = stepper, record
        record.data["num_dofs"] = stepper.problem.num_dofs
        if stepper.shape is not None:
            record.data["num_dofs_shape"] = stepper.shape.num_dofs
        self.history = open_history(stepper, v, resume)
        self.hist: dict[str, list[Any]] = self.history.setdefault("hist", {k: [] for k in keys})
        record.data["newton_iterations"] = self.history.setdefault("newton_iterations", [])
        self.series = VTXSeries(stepper.comm, getattr(record, "outdir", None),
                                {series_stem(f"{k}_series", stepper, resume): f
                                 for k, f in fields.items()})

    def log(self, iterations: int,
            values: dict[str, Any] | Iterable[tuple[str, Any]]) -> None:
        """Append the step's measures ``values`` (pairs or a dict) and its Newton iterations."""
        for key, val in (values.items() if isinstance(values, dict) else values):
            self.hist[key].append(val)
        self.record.data["newton_iterations"].append(iterations)

    def written(self, on_step: Callable[[Stepper, StepReport], object] | None = None
                ) -> Callable[[Stepper, StepReport], None]:
        """Return the ``on_step`` of :meth:`Stepper.run`: the case's, then the series entry."""
        def step(stepper: Stepper, report: StepReport) -> None:
            if on_step is not None:
                on_step(stepper, report)
            self.series.write(stepper.t)
        return step

    @contextlib.contextmanager
    def closing(self, report: Callable[[], object] | None = None,
                model: object = None) -> Iterator[None]:
        """Around the run: the series from the current time, closed and ``report()`` at the end.

        A :class:`~tribofx.reports.RunStop` leaving the block carries ``model``
        (default: the stepper) at its last accepted state.
        """
        self.series.write(self.stepper.t)
        try:
            yield
        except RunStop as err:
            err.model = self.stepper if model is None else model
            raise
        finally:
            self.series.close()
            if report is not None:
                report()

"""A response held at a target: every solve re-finds the parameter that keeps it there.

Force control by a position is the everyday example: the load a film or a
contact carries (the *response*) is held at W by moving the countersurface
(the *parameter*).  One class, :class:`Hold`, does it everywhere:

* to hold a load, one call: :meth:`Hold.march` steps the held target to its
  final value (the load march: equal steps, a failed step restored and cut in
  half, a secant predictor of the state), each step found by the hold's search;
* as a problem of an outer :class:`tribofx.continuation.Continuation`: that
  continuation marches another parameter (a speed) with the load held (the
  hold's ``get``/``set`` are those of its target, so :meth:`Hold.march` is
  ``Continuation(hold, hold).march``);
* in the slow time of :class:`tribofx.stepper.Stepper` (``stepper.hold``): the
  deformation problem of each step is solved with the load held, the first
  trial from estimates evaluated at step entry (:meth:`Hold.begin`).

How the parameter is found:

* by a **secant of complete solves** (:meth:`tribofx.continuation.Continuation.reach`
  of the ``search``: each trial is a converged Newton solve at a trial value of
  the parameter, a failed trial is restored and retried nearer the converged
  value); or
* by the **bordered Newton system** (``border=(functional, mesh)``,
  :class:`tribofx.bordered.Border`): the parameter is an unknown of one Newton
  solve, with the held response as its equation; if that solve fails, the
  secant runs from the entry state (counted in :attr:`Hold.fallbacks`).

Robustness lives in the two loops around a hold: the secant's own restore and
retry inside it, and the step cutting of the continuation or stepper that
drives it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, cast

from .bordered import Border
from .continuation import Continuation
from .reports import NewtonDivergence

if TYPE_CHECKING:
    import ufl
    from dolfinx import fem, mesh

    from .continuation import ConstantParameter, Iterations, Parameter
    from .problem import Problem

__all__ = ["Hold", "HoldReport"]


@dataclass
class HoldReport:
    """Outcome of one :meth:`Hold.solve`.

    Attributes:
        iterations: Newton iterations of each converged trial of the search (a list).
        reports: the :class:`tribofx.reports.NewtonReport` of every Newton solve
            of the search, failed trials included (for the stepper's records).
    """

    iterations: list = field(default_factory=list)
    reports: list = field(default_factory=list)


class Hold:
    """A response held at ``target`` by its search's parameter.

    Args:
        search: a response-controlled :class:`~tribofx.continuation.Continuation`:
            its problem, its parameter (e.g. the position of a countersurface),
            its response (e.g. the load), its tolerance and trials.
        target: the held value, in the held quantity (see ``transform``).
        slope: estimate of d(response)/d(parameter) for the first update of a
            solve: a float, or a callable of the target; used while the search
            has fewer than two distinct converged points.
        guess: callable → the first trial of the parameter (default: the
            search's secant extrapolation, or along ``slope`` from one point).
        predict: callable(target) setting a predicted state before the first
            trial; if that solve fails, the search restarts from the converged state.
        transform: the search's response is ``transform`` of the held quantity
            (e.g. 1/W, nearly linear in the position of a rigid film).
        step_guess, step_slope: callables of the step Δt (s), evaluated by
            :meth:`begin` at a slow step's entry (before its shape update): the
            first trial and the first-update slope of that step's solve.  They
            replace ``guess``/``slope`` in the slow time.
        border: ``(functional, mesh)``: the response as a UFL functional of the
            unknowns and of the parameter's Constant, and a mesh of its forms;
            each solve is then one bordered Newton solve, the secant its
            fallback.  None: the secant alone.
    """

    def __init__(self, search: Continuation, target: float, *,
                 slope: float | Callable[[float], float] | None = None,
                 guess: Callable[[], float] | None = None,
                 predict: Callable[[float], object] | None = None,
                 transform: Callable[[float], float] | None = None,
                 step_guess: Callable[[float], float] | None = None,
                 step_slope: Callable[[float], float] | None = None,
                 border: tuple[ufl.Form, mesh.Mesh] | None = None) -> None:
        if search.response is None:
            raise ValueError("a hold needs a response-controlled search (Continuation(..., "
                             "response=...))")
        self.search, self.target = search, float(target)
        self.slope, self.guess, self.predict = slope, guess, predict
        self.transform = transform if transform is not None else (lambda value: value)
        self.step_guess, self.step_slope = step_guess, step_slope
        # (a bordered hold's search drives a Problem by a Constant's parameter)
        self.border = None if border is None else Border(
            cast("Problem", search.problem), cast("ConstantParameter", search.parameter),
            border[0], self.transform(target), border[1], rtol=search.rtol)
        self.fallbacks = 0
        # (guess, slope) of the slow step in progress
        self._step: tuple[float | None, float | None] | None = None
        self._steps: Continuation | None = None   # the load march of :meth:`march`
        self._on_step: Callable[[], object] | None = None

    @property
    def parameter(self) -> Parameter:
        """The search's parameter (the one the hold moves)."""
        return self.search.parameter

    @property
    def u(self) -> list[fem.Function]:
        """Unknowns of the search's problem (for the predictor of an outer continuation)."""
        return self.search.problem.u

    # -- the target as the parameter of an outer continuation --------------------------
    def get(self) -> float:
        """Return the held target."""
        return self.target

    def set(self, value: float) -> None:
        """Set the held target."""
        self.target = float(value)

    def march(self, target: float, steps: int = 1, *, on_step: Callable[[], object] | None = None,
              record: list[Iterations] | None = None, predictor: bool = True,
              min_fraction: float = 2.0**-10) -> list[float | None]:
        """Step the held target from its value to ``target`` (the load march); returns targets.

        ``steps`` equal steps; each is one :meth:`solve` (the search finds the
        parameter), a failed step is restored and cut in half, down to
        ``min_fraction`` of the first (then :class:`~tribofx.reports.NewtonDivergence`,
        the state the last converged load's); ``predictor``: the state of each step
        extrapolated from the last two converged loads.  ``on_step()`` runs after
        every converged step; ``record`` (a list) receives each step's trial
        iterations.  Repeated calls go on with the same march (its predictor's
        history).
        """
        if self._steps is None:
            self._steps = Continuation(self, self, response=self._stepped)
        if record is not None:
            self._steps.record = record
        self._on_step = on_step
        return self._steps.march(target, steps, predictor=predictor,
                                 min_fraction=min_fraction)

    def _stepped(self) -> float:
        if self._on_step is not None:
            self._on_step()
        return self.target

    # -- the slow time ---------------------------------------------------------------
    def begin(self, dt: float) -> None:
        """At a slow step's entry: the converged parameter, and the step's estimates for Δt."""
        self.search.done = self.parameter.get()
        self._step = (None if self.step_guess is None else self.step_guess(dt),
                      None if self.step_slope is None else self.step_slope(dt))

    # -- problem protocol --------------------------------------------------------------
    def solve(self, verbose: bool = False, guess: float | None = None) -> HoldReport:
        """Find the parameter at which the response is the target (``guess``: first trial).

        Raises :class:`~tribofx.reports.NewtonDivergence` (state at entry) when
        the search gives up.  ``verbose`` is the problem protocol's: the
        search's own ``verbose`` prints its Newton histories.  The Newton
        reports of this solve are taken out of the search's ``reports`` (a long
        slow-time run does not accumulate them).
        """
        n0 = len(self.search.reports)
        try:
            if self._step is not None:
                step_guess, slope = self._step
                self._step = None
                self._reach(step_guess if guess is None else guess, slope)
            elif self.predict is not None and guess is None:
                converged = self.search.problem.state()
                self.predict(self.target)
                try:
                    self._reach(*self._estimates())
                except NewtonDivergence:
                    self.search.problem.restore(converged)
                    self._reach(*self._estimates())
            else:
                first, slope = self._estimates()
                self._reach(first if guess is None else guess, slope)
        finally:
            reports = self.search.reports[n0:]
            del self.search.reports[n0:]
        # (the search's last record is the list of its trials' iterations)
        return HoldReport(iterations=cast(list, self.search.record[-1]), reports=reports)

    def _estimates(self) -> tuple[float | None, float | None]:
        """(first trial, first-update slope) of a solve outside the slow time."""
        search = self.search
        slope = search.history_slope()
        if slope is None:
            slope = self.slope(self.target) if callable(self.slope) else self.slope
        guess = self.guess() if self.guess is not None else None
        if guess is None and len(search.history) == 1 and slope:
            # one converged point: the first trial along the estimated slope
            guess = search.done + (self.transform(self.target)
                                   - cast(float, search.history[-1][1])) / slope
        return guess, slope

    def _reach(self, guess: float | None, slope: float | None) -> None:
        """Solve bordered (if there is a border), and by the secant without one or on failure."""
        target = self.transform(self.target)
        if self.border is not None:
            try:
                self._bordered(guess, target)
                return
            except NewtonDivergence:
                self.fallbacks += 1
        self.search.reach(target, guess=guess, slope=slope)

    def _bordered(self, guess: float | None, target: float) -> None:
        """One Newton solve with the parameter an unknown, from ``guess``; restored on failure."""
        # (a bordered hold's search drives a Problem: the Border is built on it)
        search, problem = self.search, cast("Problem", self.search.problem)
        entry = self.parameter.get()
        if problem.snes.getLineSearch().getType() != "basic":
            raise NewtonDivergence("the bordered solve needs SNES's basic line search")
        if guess is not None:
            self.parameter.set(guess)
        assert self.border is not None      # _reach calls it when there is one
        self.border.target = target
        try:
            report = search.solve_once(border=self.border)
        except NewtonDivergence:
            self.parameter.set(entry)
            problem.refresh()
            raise
        search.accept([report.iterations])

    def state(self) -> list:
        """State of the search's problem (its parameter included)."""
        return self.search.problem.state()

    def restore(self, state: list) -> None:
        """Restore a :meth:`state`."""
        self.search.problem.restore(state)

    def commit(self) -> None:
        """Do nothing: the search has committed its converged solve."""

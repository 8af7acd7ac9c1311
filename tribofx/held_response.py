"""Responses held by an inner continuation: a solve that re-finds a parameter each time.

* :class:`HeldResponse` — a problem whose every solve is an inner
  :meth:`tribofx.continuation.Continuation.reach` (e.g. the position of a
  countersurface that carries a load), so that an outer continuation marches
  the load or another parameter with the response held;
* :class:`ResponseControl` — the same through the slow time of
  :class:`tribofx.stepper.Stepper` (force control of a wear run), with a
  predictor and a slope evaluated at each step's entry; with a ``border`` the
  parameter is instead an unknown of each Newton solve
  (:class:`tribofx.bordered.Border`), the secant its fallback.
"""

from .bordered import Border
from .continuation import Continuation
from .problem import NewtonDivergence

__all__ = ["HeldResponse", "ResponseControl"]


class HeldResponse:
    """A problem whose every solve re-finds a parameter so that a response keeps a target.

    Wraps a response-controlled :class:`Continuation` ``inner`` (its problem, its
    parameter, e.g. the position of a countersurface, and its response, e.g. the
    load): :meth:`solve` runs ``inner.reach(target)``.  It is a problem for an
    outer :class:`Continuation`, in one of two ways:

    * the held target is itself the outer parameter (``get``/``set``): the outer
      :meth:`Continuation.march` then steps the load with step cutting, each step
      found by the inner secant (load control by a position);
    * another parameter (e.g. a speed) is marched with the response held.

    Args:
        inner: the response-controlled continuation.
        target: the held response value.
        slope: first-update estimate of d(response)/d(parameter) (a float or a
            callable of the target; used until ``inner`` has a converged history).
        guess: callable → first trial of the inner parameter (default: the inner
            secant extrapolation).
        predict: callable(target) setting a predicted state before the first trial;
            if that solve fails, the inner search restarts from the converged state.
        transform: the inner response is ``transform`` of the held quantity (e.g. 1/W,
            nearly linear in the position of a rigid film); the target is held in the
            quantity itself, the slope is of the transformed response.
    """

    def __init__(self, inner, target, slope=None, guess=None, predict=None, transform=None):
        self.inner, self.target = inner, float(target)
        self._slope, self.guess, self.predict = slope, guess, predict
        self.transform = transform if transform is not None else (lambda value: value)

    @property
    def u(self):
        """Unknowns of the inner problem (for predictors)."""
        return self.inner.problem.u

    # -- parameter protocol (the target) -----------------------------------------------
    def get(self):
        """Return the held target."""
        return self.target

    def set(self, value):
        """Set the held target."""
        self.target = float(value)

    # -- problem protocol ----------------------------------------------------------------
    def _reach(self):
        slope = self.inner.history_slope()
        if slope is None:
            slope = self._slope(self.target) if callable(self._slope) else self._slope
        target = self.transform(self.target)
        guess = self.guess() if self.guess is not None else None
        if guess is None and len(self.inner.history) == 1 and slope:
            # one converged point: first trial along the estimated slope
            guess = self.inner.done + (target - self.inner.history[-1][1]) / slope
        self.inner.reach(target, guess=guess, slope=slope)
        return self.inner.record[-1]

    def solve(self, verbose=False):
        """Reach the target; returns a report whose ``iterations`` lists the Newton trials."""
        from .problem import NewtonReport

        if self.predict is not None:
            converged = self.inner.problem.state()
            self.predict(self.target)
            try:
                return NewtonReport(iterations=self._reach())
            except NewtonDivergence:
                self.inner.problem.restore(converged)
        return NewtonReport(iterations=self._reach())

    def state(self):
        """State of the inner problem (its parameter included)."""
        return self.inner.problem.state()

    def restore(self, state):
        """Restore a :meth:`state`."""
        self.inner.problem.restore(state)

    def commit(self):
        """Do nothing: the inner search has committed its converged step."""


class _Recorder:
    """A problem whose Newton reports are kept (also of failed solves)."""

    def __init__(self, problem):
        self.problem, self.reports = problem, []

    def solve(self, verbose=False):
        try:
            return self.problem.solve(verbose=verbose)
        finally:
            self.reports.append(self.problem.report)

    def __getattr__(self, name):
        return getattr(self.problem, name)


class ResponseControl(HeldResponse):
    """A :class:`HeldResponse` of the slow time: the response held at every step's solves.

    Each solve of the deformation problem is a
    :meth:`tribofx.continuation.Continuation.reach` on ``parameter``, started
    from ``predictor(dt)`` (evaluated at step entry, before any shape update)
    with the first update along ``slope(dt)`` (an estimate of d response / d
    parameter); both optional.

    Args:
        problem: the problem solved at each trial (the stepper's ``problem``).
        parameter: e.g. :class:`tribofx.continuation.ConstantParameter`.
        response: callable → float.
        target: the value the response is held at.
        predictor, slope: callables of Δt (s), or None.
        rtol, max_trials: of :meth:`Continuation.reach` (and rtol of the border).
        border: ``(functional, mesh)``: the response as a UFL functional of the
            unknowns and of the parameter's Constant, and a mesh of its forms.
            Each solve is then one Newton solve with the parameter an unknown
            (:class:`tribofx.bordered.Border`), started from the guess; if it
            fails, the secant of complete solves runs from the entry state
            (counted in :attr:`fallbacks`).  None: the secant alone.
    """

    def __init__(self, problem, parameter, response, target, predictor=None, slope=None,
                 rtol=1e-8, max_trials=12, verbose=False, border=None):
        self._rec = _Recorder(problem)
        super().__init__(Continuation(self._rec, parameter, response=response,
                                      verbose=verbose, rtol=rtol, max_trials=max_trials),
                         target)
        self.parameter = parameter
        self.predictor, self.step_slope = predictor, slope
        self._guess = self._step_slope = None
        self.border = None if border is None else Border(
            problem, parameter, border[0], target, border[1], rtol=rtol)
        self.fallbacks = 0

    @property
    def trials(self):
        """Newton iteration counts of the trials of every converged reach."""
        return self.inner.record

    def begin(self, dt):
        """At step entry: the parameter's value is the converged one; predictor and slope for Δt."""
        self.inner.done = self.parameter.get()
        self._guess = None if self.predictor is None else self.predictor(dt)
        self._step_slope = None if self.step_slope is None else self.step_slope(dt)

    def solve(self, guess=None, slope=None):
        """Reach the target from ``guess`` (default: the step's predictor); Newton reports."""
        n0 = len(self._rec.reports)
        guess = self._guess if guess is None else guess
        slope = self._step_slope if slope is None else slope
        self._guess = self._step_slope = None
        if self.border is not None:
            try:
                self._bordered(guess)
                return self._rec.reports[n0:]
            except NewtonDivergence:
                self.fallbacks += 1
        self.inner.reach(self.target, guess=guess, slope=slope)
        return self._rec.reports[n0:]

    def _bordered(self, guess):
        """One Newton solve with the parameter an unknown, from ``guess``; restored on failure."""
        problem, entry = self._rec.problem, self.parameter.get()
        if problem.snes.getLineSearch().getType() != "basic":
            raise NewtonDivergence("the bordered solve needs SNES's basic line search")
        if guess is not None:
            self.parameter.set(guess)
        self.border.target = self.target
        problem.border = self.border
        try:
            report = self._rec.solve(verbose=self.inner.verbose)
        except NewtonDivergence:
            self.parameter.set(entry)
            problem.refresh()
            raise
        finally:
            problem.border = None
        self.inner.accept([report.iterations])

"""Continuation: drive one scalar parameter of a problem (load, position, speed, pressure).

The controller knows nothing of the physics.  It holds a :class:`tribofx.problem.Problem`
(anything with ``solve``, ``state``, ``restore`` and ``commit``), a parameter
(``get()``/``set(value)``, e.g. :class:`ConstantParameter` on a
``dolfinx.fem.Constant``) and, for response control, a measured response
(a callable returning a float, e.g. the normal contact force).

Two strategies:

* :meth:`Continuation.march` — natural-parameter continuation to a value in
  steps; a failed Newton solve restores the last converged state and halves the
  increment (step cutting), which doubles back after :attr:`Continuation.regrow`
  converged steps at its size; the initial iterate of a step is a secant predictor
  in the parameter from the last two converged states.
* :meth:`Continuation.reach` — find the parameter at which the response equals
  a target by a secant iteration (power law through the origin for the first
  update); a failed trial restores the state and moves the parameter halfway
  back to the last converged value (and gives up once the trial is that value
  to round-off: the solve there is the one that failed).

Each converged step is committed (histories such as the Lagrangian slip move on).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, NoReturn, Protocol, TypeAlias, cast

import numpy as np
import numpy.typing as npt

from .problem import NewtonDivergence

#: relative distance below which a trial of :meth:`Continuation.reach` is the converged
#: parameter itself (about 4500 ulp): a failure there is final
ROUNDOFF = 1e-12

if TYPE_CHECKING:
    from dolfinx import fem

    from .bordered import Border
    from .hold import HoldReport
    from .reports import NewtonReport

    #: Newton iterations of an accepted step: a count, or the counts of its trials (a
    #: list; nested when the problem is itself a search, a Hold)
    Iterations: TypeAlias = int | list["Iterations"]
    #: the measured response of a response-controlled continuation
    Response: TypeAlias = Callable[[], float]

    class Solvable(Protocol):
        """What a continuation drives: a :class:`tribofx.problem.Problem`, a Hold, ..."""

        @property
        def u(self) -> list[fem.Function]:
            """The unknowns (the secant predictor's)."""

        def solve(self, verbose: bool = False) -> NewtonReport | HoldReport:
            """Solve at the current parameter (raises NewtonDivergence)."""

        def state(self) -> list:
            """Copy of the state."""

        def restore(self, state: list) -> None:
            """Restore a :meth:`state`."""

        def commit(self) -> None:
            """Accept the converged state."""

    class Parameter(Protocol):
        """The driven scalar: a :class:`ConstantParameter`, a Hold's target, ..."""

        def get(self) -> float:
            """Return the current value."""

        def set(self, value: float) -> None:
            """Set the value."""

__all__ = ["ConstantParameter", "Continuation"]


class ConstantParameter:
    """A scalar held by a ``dolfinx.fem.Constant`` (or one ``index`` of a vector Constant).

    ``on_set(value)``, if given, runs after each change (e.g. scales that depend on it).
    ``scale``: the Constant holds ``scale``·value (e.g. a plane sliding at 2U driven by
    the entrainment speed U).
    """

    def __init__(self, constant: fem.Constant, index: int | None = None,
                 on_set: Callable[[float], object] | None = None, scale: float = 1.0) -> None:
        self.constant, self.index, self.on_set = constant, index, on_set
        self.scale = float(scale)

    def get(self) -> float:
        """Return the current value."""
        v = self.constant.value
        return float(v if self.index is None else v[self.index]) / self.scale

    def set(self, value: float) -> None:
        """Set the value (and run ``on_set``)."""
        if self.index is None:
            # (DOLFINx types Constant.value's setter NDArray; it takes a float)
            self.constant.value = self.scale * float(value)  # type: ignore[assignment]
        else:
            self.constant.value[self.index] = self.scale * float(value)
        if self.on_set is not None:
            self.on_set(float(value))


class Continuation:
    """Continuation of ``problem`` in ``parameter``, optionally controlled by ``response``.

    Args:
        problem: the problem (``solve(verbose)``, ``state()``, ``restore()``, ``commit()``).
        parameter: ``get()``/``set(value)`` of the driven scalar.
        response: callable → float, the measured response (for :meth:`reach`).
        on_accept: called after every converged step, once its response is measured
            (a record, a checkpoint of the step).
        verbose: print Newton histories.
        rtol: relative tolerance of :meth:`reach` on the response.
        max_trials: secant trials of one :meth:`reach` (a :meth:`march` step is cut
            down to its ``min_fraction`` instead).
        record: list receiving the Newton iteration counts of each converged step.
        admissible: callable → bool; a converged solve whose state it rejects (e.g. a
            film with h ≤ 0) is treated as a failed one (restored, step cut).
        max_step: largest parameter change of one trial of :meth:`reach` (None: any),
            which then runs as a step-limited secant (see there); it gives up
            (NewtonDivergence) once the bound on the step falls below
            ``min_bound``·``max_step`` (1e-4): every trial near the last successful
            state fails, so more trials only repeat it.

    Attributes:
        regrow: steps a cut increment of :meth:`march` converges at before it
            doubles back (3).
        increments: the march in progress (see :meth:`march`).
    """

    def __init__(self, problem: Solvable, parameter: Parameter,
                 response: Response | None = None, verbose: bool = False,
                 rtol: float = 1e-6, max_trials: int = 25,
                 record: list[Iterations] | None = None,
                 admissible: Callable[[], bool] | None = None,
                 max_step: float | None = None,
                 on_accept: Callable[[], object] | None = None) -> None:
        self.problem, self.parameter, self.response = problem, parameter, response
        self.on_accept = on_accept
        self.verbose, self.rtol, self.max_trials = verbose, rtol, max_trials
        self.admissible, self.max_step = admissible, max_step
        self.min_bound = 1e-4   # step-limited secant: give up below min_bound·max_step
        # a cut increment of march() doubles after this many steps converged at its size
        self.regrow = 3
        self.record = record if record is not None else []
        # the report of every Newton solve, failed ones included
        self.reports: list[NewtonReport | HoldReport | None] = []
        self.done = parameter.get()
        # (parameter, response) of converged steps (response None: no response)
        self.history: list[tuple[float, float | None]] = []
        # (parameter, unknown arrays) of the last two converged steps
        self._states: list[tuple[float, list[npt.NDArray[Any]]]] = []
        # (first, next) increment of the march in progress, and the steps converged at
        # the next one's size (a cut size doubles after :attr:`regrow` of them)
        self.increments: tuple[float, float, int] | None = None

    # -- helpers -------------------------------------------------------------------

    def _give_up(self, saved: list, message: str) -> NoReturn:
        """Restore the entry state and parameter; raise NewtonDivergence(message)."""
        self.problem.restore(saved)
        self.parameter.set(self.done)
        raise NewtonDivergence(message)

    def solve_once(self, border: Border | None = None) -> NewtonReport | HoldReport:
        """One Newton solve of the problem at the current parameter; its report is kept.

        ``border``: a :class:`tribofx.bordered.Border` joined to the solve (the
        parameter an unknown).  Every report, of failed solves too, goes to
        :attr:`reports`.
        """
        kw: dict[str, Any] = {} if border is None else {"border": border}
        try:
            report = self.problem.solve(verbose=self.verbose, **kw)
        except NewtonDivergence as err:
            self.reports.append(err.report)
            raise
        self.reports.append(report)
        return report

    def _solve_at(self, value: float) -> Iterations:
        self.parameter.set(value)
        iterations = self.solve_once().iterations
        if self.admissible is not None and not self.admissible():
            raise NewtonDivergence(f"converged to an inadmissible state at {value:g}")
        return iterations

    def _distinct(self, ra: float, rb: float) -> bool:
        """Two responses differ by more than the tolerance (a secant through them is sound)."""
        return abs(rb - ra) > self.rtol * max(abs(ra), abs(rb))

    def history_slope(self) -> float | None:
        """Secant d(response)/d(parameter) of the last two converged steps (None if unknown).

        None also when their responses agree to the tolerance (steps of another
        parameter at a held response).
        """
        if len(self.history) < 2:
            return None
        # (responses are floats: a continuation that has a response)
        (pa, ra), (pb, rb) = cast("list[tuple[float, float]]", self.history[-2:])
        return (rb - ra) / (pb - pa) if pb != pa and self._distinct(ra, rb) else None

    def accept(self, iterations: Iterations) -> float | None:
        """Commit the converged state at the current parameter; record it; return the response."""
        self.problem.commit()
        self.done = self.parameter.get()
        self.record.append(iterations)   # before the response: it may checkpoint the record
        r = self.response() if self.response is not None else None
        if self.on_accept is not None:
            self.on_accept()
        self.history.append((self.done, r))
        unknowns = getattr(self.problem, "u", [])
        self._states = (self._states + [(self.done, [f.x.array.copy() for f in unknowns])])[-2:]
        return r

    def resume_from(self, value: float) -> None:
        """Take ``value`` as the converged parameter (a state restored from a checkpoint)."""
        self.parameter.set(value)
        self.done = self.parameter.get()

    def secant_state(self) -> dict[str, Any]:
        """Return what a resumed search needs (JSON): ``done`` and the last two points."""
        return {"done": self.done, "history": [list(h) for h in self.history[-2:]]}

    def set_secant_state(self, saved: dict[str, Any]) -> None:
        """Restore a :meth:`secant_state` (the trials of a resumed search are then the same)."""
        self.done = float(saved["done"])
        self.history = [tuple(h) for h in saved["history"]]

    def remember(self) -> None:
        """Take the current (converged) state as the first point of the secant predictor.

        A new Continuation predicts from its third step on (two accepted states);
        after ``remember()`` at a converged state it predicts from its second.
        """
        unknowns = getattr(self.problem, "u", [])
        self._states = (self._states + [(self.parameter.get(),
                                         [f.x.array.copy() for f in unknowns])])[-2:]

    def _predict(self, value: float) -> None:
        """Secant predictor of the unknowns at ``value`` from the last two converged states."""
        if len(self._states) < 2:
            return
        (p0, a0), (p1, a1) = self._states
        if p1 == p0:
            return
        s = (value - p1) / (p1 - p0)
        for f, x0, x1 in zip(self.problem.u, a0, a1):
            f.x.array[:] = x1 + s * (x1 - x0)

    # -- strategies ------------------------------------------------------------------
    def march(self, target: float, steps: int = 1, predictor: bool = True,
              min_fraction: float = 2.0**-10, geometric: bool = False,
              increments: Sequence[float] | None = None) -> list[float | None]:
        """Natural-parameter continuation from the current value to ``target``.

        ``steps`` equal increments; a failed step is cut in half (down to
        ``min_fraction`` of the first increment), and a cut increment doubles
        back (up to the first) after :attr:`regrow` (3) converged steps at its
        size.  Doubling after each converged step would retry, every other
        step, an increment too long for a stretch of the path (the O-ring's
        mount on the rough density-4 seal: 33 of 69 solves failed so, 13 of 59
        with 3; 181 s against 110 s).  A march that never cuts is the same for
        any ``regrow``.  Returns the responses (or None) of the
        converged steps.  ``geometric``: equal ratios instead (a positive
        parameter such as a speed; a failed ratio is replaced by its square root).

        During the march :attr:`increments` is (first increment, next
        increment, steps converged at the next one's size), in log(parameter)
        when geometric, as they stand after each converged step (a checkpoint
        keeps them); ``increments=`` continues an interrupted march on the same
        step sequence (a pair, as checkpoints before the count kept, counts 0).
        """
        if geometric and not (target > 0 and self.done > 0):
            raise ValueError("a geometric march needs positive parameter values")
        # the march runs in t = log(parameter) for geometric steps
        to, back = (np.log, np.exp) if geometric else (float, float)
        t_target = to(target)
        slack = 1e-12 * max(1.0, abs(t_target)) if geometric else 0.0  # exp(log(x)) ≠ x
        step0 = (t_target - to(self.parameter.get())) / steps
        step, run = step0, 0       # run: steps converged at a cut size since it was set
        if increments is not None:
            step0, step = (float(x) for x in increments[:2])
            run = int(increments[2]) if len(increments) > 2 else 0
        out = []
        while abs(t_target - to(self.done)) > 1e-14 * max(abs(t_target), abs(step0), 1e-300):
            t = to(self.done) + step
            last = (t - t_target) * np.sign(step0) > -slack
            value = target if last else back(t)
            saved = self.problem.state()
            if predictor:
                self._predict(value)
            try:
                its = self._solve_at(value)
            except NewtonDivergence:
                self.problem.restore(saved)
                self.parameter.set(self.done)
                step, run = 0.5 * step, 0
                if abs(step) < min_fraction * abs(step0):
                    raise
                continue
            run += 1
            if abs(step) < abs(step0) and run >= self.regrow:
                step, run = min(abs(step) * 2, abs(step0)) * np.sign(step0), 0
            self.increments = (step0, step, run)   # before accept: on_accept may checkpoint
            out.append(self.accept(its))
        return out

    def advance(self, target: float, step: float, growth: float = 1.5,
                min_fraction: float = 1e-4) -> float:
        """Response-controlled march: move the parameter until the response passes ``target``.

        Each step changes the parameter by ``step`` from the last converged state
        (its unknowns are the initial iterate, no extrapolation); a step whose
        solve fails, is inadmissible or does not move the response towards
        ``target`` is restored and halved, a converged one lets the step grow by
        ``growth`` (never beyond ``step``).  Once a step passes ``target`` it is hit
        by :meth:`reach` (secant through the two bracketing converged states).
        Displacement control: the response (e.g. a load) is an output of each
        step.  Raises NewtonDivergence (state: last converged) when the step falls
        below ``min_fraction``·``step``.  Returns the parameter reached.
        """
        # (self.response is set: a response-controlled march)
        r = cast("Response", self.response)()
        sign = np.sign(target - r)
        h = float(step)
        while (target - r) * sign > self.rtol * abs(target):
            saved = self.problem.state()
            try:
                its = self._solve_at(self.done + h)
                if (cast("Response", self.response)() - r) * sign <= 0:
                    raise NewtonDivergence("the response does not move towards the target")
            except NewtonDivergence:
                self.problem.restore(saved)
                self.parameter.set(self.done)
                h *= 0.5
                if abs(h) < min_fraction * abs(step):
                    raise NewtonDivergence(f"response-controlled march stalled at {r:g} "
                                           f"(step {h:.2e})") from None
                continue
            r = cast(float, self.accept(its))
            h = np.sign(step) * min(abs(step), growth * abs(h))
        if abs(r - target) <= self.rtol * abs(target):
            return self.done
        return self.reach(target, slope=self.history_slope())

    def reach(self, target: float, guess: float | None = None,
              slope: float | None = None) -> float:
        """Find the parameter at which the response equals ``target``; returns it.

        ``guess``: first trial value (default: secant extrapolation of the
        converged history, or the current value).  ``slope``: an estimate of
        d(response)/d(parameter) for the first update (default: a power law
        through the origin of the loading); the later updates are secants.
        Raises NewtonDivergence (state restored) when ``max_trials`` trials do
        not reach the target.

        With ``max_step`` (step-limited secant) a failed trial is restored to the
        last successful trial (or the entry state) and the bound on the step is
        halved; each success lets it grow by 1.5, up to ``max_step``.  Without it
        a failed trial restores the entry state and moves the parameter halfway
        back to the last converged value; a failed trial within :data:`ROUNDOFF`
        of that value gives up at once (halving towards it would repeat the same
        solve from the same state up to ``max_trials`` times).
        """
        saved = self.problem.state()
        iterations = []
        f0: float | None
        d0, f0 = self.done, None
        bound, base = self.max_step, (saved, self.parameter.get())
        if guess is None:
            # (the responses are floats: a response-controlled continuation)
            if len(self.history) >= 2 and self._distinct(cast(float, self.history[-2][1]),
                                                         cast(float, self.history[-1][1])):
                (pa, ra), (pb, rb) = cast("list[tuple[float, float]]", self.history[-2:])
                guess = pb + (target - rb) * (pb - pa) / (rb - ra)
            else:
                guess = self.done
        d1, stuck = guess, False
        for _ in range(self.max_trials):
            try:
                iterations.append(self._solve_at(d1))
            except NewtonDivergence:
                if bound is None:
                    if abs(d1 - self.done) <= ROUNDOFF * max(abs(d1), abs(self.done)):
                        # the trial is the converged parameter to round-off: halving
                        # towards it repeats the same solve from the same state
                        self._give_up(saved, f"response {target:g} not reached: the solve "
                                      f"fails at the converged parameter {self.done:g}")
                    self.problem.restore(saved)
                    d1 = 0.5 * (self.done + d1)
                else:
                    self.problem.restore(base[0])
                    bound = 0.5 * abs(d1 - base[1])
                    if bound < self.min_bound * cast(float, self.max_step):  # (bound: max_step)
                        stuck = True   # the trials have shrunk onto the base state: it fails
                        break
                    d1 = base[1] + np.sign(d1 - base[1]) * bound
                continue
            if bound is not None:
                base = (self.problem.state(), d1)
                bound = min(cast(float, self.max_step), 1.5 * bound)
            f1 = cast("Response", self.response)()
            if abs(f1 - target) <= self.rtol * abs(target):
                break
            if (f0 is None or f1 == f0) and slope is not None:
                d_new = d1 + (target - f1) / slope
            elif f0 is None or f1 == f0:
                # power-law update from the origin of the loading
                d_new = d1 * (target / f1) ** 0.7 if f1 > 0 else 2 * d1
            else:
                d_new = d1 - (f1 - target) * (d1 - d0) / (f1 - f0)
            if bound is not None and abs(d_new - d1) > bound:
                d_new = d1 + np.sign(d_new - d1) * bound
            d0, f0, d1 = d1, f1, d_new
        else:
            self._give_up(saved, f"response {target:g} not reached in {self.max_trials} trials")
        if stuck:
            self._give_up(saved, f"response {target:g} not reached: every trial within "
                          f"{bound:.1e} of the last successful one fails")
        self.accept(iterations)
        return d1

"""Continuation: drive one scalar parameter of a problem (load, position, speed, pressure).

The controller knows nothing of the physics.  It holds a :class:`tribofx.problem.Problem`
(anything with ``solve``, ``state``, ``restore`` and ``commit``), a parameter
(``get()``/``set(value)``, e.g. :class:`ConstantParameter` on a
``dolfinx.fem.Constant``) and, for response control, a measured response
(a callable returning a float, e.g. the normal contact force).

Two strategies:

* :meth:`Continuation.march` — natural-parameter continuation to a value in
  steps; a failed Newton solve restores the last converged state and halves the
  increment (step cutting); the initial iterate of a step is a secant predictor
  in the parameter from the last two converged states.
* :meth:`Continuation.reach` — find the parameter at which the response equals
  a target by a secant iteration (power law through the origin for the first
  update); a failed trial restores the state and moves the parameter halfway
  back to the last converged value.

Each converged step is committed (histories such as the Lagrangian slip move on).
"""

import numpy as np

from .problem import NewtonDivergence

__all__ = ["ConstantParameter", "Continuation"]


class ConstantParameter:
    """A scalar held by a ``dolfinx.fem.Constant`` (or one ``index`` of a vector Constant).

    ``on_set(value)``, if given, runs after each change (e.g. scales that depend on it).
    """

    def __init__(self, constant, index=None, on_set=None):
        self.constant, self.index, self.on_set = constant, index, on_set

    def get(self):
        """Return the current value."""
        v = self.constant.value
        return float(v if self.index is None else v[self.index])

    def set(self, value):
        """Set the value (and run ``on_set``)."""
        if self.index is None:
            self.constant.value = float(value)
        else:
            self.constant.value[self.index] = float(value)
        if self.on_set is not None:
            self.on_set(float(value))


class Continuation:
    """Continuation of ``problem`` in ``parameter``, optionally controlled by ``response``.

    Args:
        problem: the problem (``solve(verbose)``, ``state()``, ``restore()``, ``commit()``).
        parameter: ``get()``/``set(value)`` of the driven scalar.
        response: callable → float, the measured response (for :meth:`reach`).
        verbose: print Newton histories.
        rtol: relative tolerance of :meth:`reach` on the response.
        max_trials: secant trials of one :meth:`reach`, or cuts of one :meth:`march` step.
        record: list receiving the Newton iteration counts of each converged step.
    """

    def __init__(self, problem, parameter, response=None, verbose=False, rtol=1e-6,
                 max_trials=25, record=None):
        self.problem, self.parameter, self.response = problem, parameter, response
        self.verbose, self.rtol, self.max_trials = verbose, rtol, max_trials
        self.record = record if record is not None else []
        self.done = parameter.get()
        self.history = []  # (parameter, response) of converged steps
        self._states = []  # (parameter, unknown arrays) of the last two converged steps

    # -- helpers -------------------------------------------------------------------
    def _solve_at(self, value):
        self.parameter.set(value)
        return self.problem.solve(verbose=self.verbose).iterations

    def _accept(self, iterations):
        self.problem.commit()
        self.done = self.parameter.get()
        r = self.response() if self.response is not None else None
        self.history.append((self.done, r))
        self.record.append(iterations)
        unknowns = getattr(self.problem, "u", [])
        self._states = (self._states + [(self.done, [f.x.array.copy() for f in unknowns])])[-2:]
        return r

    def _predict(self, value):
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
    def march(self, target, steps=1, predictor=True, min_fraction=2.0**-10):
        """Natural-parameter continuation from the current value to ``target``.

        ``steps`` equal increments; a failed step is cut in half (down to
        ``min_fraction`` of the first increment).  Returns the responses (or None)
        of the converged steps.
        """
        start = self.parameter.get()
        step0 = (target - start) / steps
        step = step0
        out = []
        while abs(target - self.done) > 1e-14 * max(abs(target), abs(step0), 1e-300):
            value = self.done + step
            if (value - target) * np.sign(step0) > 0:
                value = target
            saved = self.problem.state()
            if predictor:
                self._predict(value)
            try:
                its = self._solve_at(value)
            except NewtonDivergence:
                self.problem.restore(saved)
                self.parameter.set(self.done)
                step *= 0.5
                if abs(step) < min_fraction * abs(step0):
                    raise
                continue
            out.append(self._accept(its))
            step = min(abs(step) * 2, abs(step0)) * np.sign(step0)
        return out

    def reach(self, target, guess=None, slope=None):
        """Find the parameter at which the response equals ``target``; returns it.

        ``guess``: first trial value (default: secant extrapolation of the
        converged history, or the current value).  ``slope``: an estimate of
        d(response)/d(parameter) for the first update (default: a power law
        through the origin of the loading); the later updates are secants.
        Raises NewtonDivergence (state restored) when ``max_trials`` trials do
        not reach the target.
        """
        saved = self.problem.state()
        iterations = []
        d0, f0 = self.done, None
        if guess is None:
            if len(self.history) >= 2 and self.history[-1][1] != self.history[-2][1]:
                (pa, ra), (pb, rb) = self.history[-2:]
                guess = pb + (target - rb) * (pb - pa) / (rb - ra)
            else:
                guess = self.done
        d1 = guess
        for _ in range(self.max_trials):
            try:
                iterations.append(self._solve_at(d1))
            except NewtonDivergence:
                self.problem.restore(saved)
                d1 = 0.5 * (self.done + d1)
                continue
            f1 = self.response()
            if abs(f1 - target) <= self.rtol * abs(target):
                break
            if (f0 is None or f1 == f0) and slope is not None:
                d_new = d1 + (target - f1) / slope
            elif f0 is None or f1 == f0:
                # power-law update from the origin of the loading
                d_new = d1 * (target / f1) ** 0.7 if f1 > 0 else 2 * d1
            else:
                d_new = d1 - (f1 - target) * (d1 - d0) / (f1 - f0)
            d0, f0, d1 = d1, f1, d_new
        else:
            self.problem.restore(saved)
            self.parameter.set(self.done)
            raise NewtonDivergence(f"response {target:g} not reached in {self.max_trials} "
                                   "trials")
        self._accept(iterations)
        return d1

"""Stability of a slow-time scheme: growth probes and the critical step by bisection.

The chapter gives only the scaling of the explicit scheme's critical step,
Δt_cr ∼ h/E (eq. 31); :func:`bisect_critical_step` finds it for a mesh and a
state from a measured growth (:func:`growth_probe` of a
:class:`tribofx.stepper.Stepper`).  Used by :mod:`tribofx.studies.wear_stability`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from .problem import NewtonDivergence

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable

    from .stepper import Stepper

__all__ = ["bisect_critical_step", "growth_probe"]


def growth_probe(stepper: Stepper, start: dict[str, Any], steps: int,
                 measure: Callable[[], float], probe: list[tuple[float, float]] | None = None,
                 settle: int = 0) -> Callable[[float], float]:
    """Stability probe of the slow-time scheme: ``growth(Δt)`` for :func:`bisect_critical_step`.

    ``growth(Δt)`` restores the state ``start`` (a :meth:`Stepper.state`), takes
    ``steps`` steps of Δt without cutting and returns |``measure()``| (e.g. the
    amplitude of a perturbation relative to its initial one); a failed step
    (Newton divergence, inverted mesh) gives ∞.  With ``settle`` > 0, ``settle``
    steps are taken first and the result is ``measure()`` after the ``steps``
    further steps divided by its value after the first ``settle`` (the growth
    from a state the scheme has already restarted from: a start that is not on
    the scheme's own path, e.g. an implicit state restored into the explicit
    scheme, jumps in its first step whatever Δt).  Each (Δt, growth) is appended
    to ``probe`` (a list).
    """
    def growth(dt: float) -> float:
        stepper.restore(start)
        try:
            for _ in range(settle):
                stepper.step(dt)
            m0 = measure() if settle else 1.0
            for _ in range(steps):
                stepper.step(dt)
        except NewtonDivergence:
            g = math.inf
        else:
            g = measure() / m0 if m0 > 0 else math.inf
        if probe is not None:
            probe.append((dt, g))
        return abs(g)

    return growth


def bisect_critical_step(growth: Callable[[float], float], lo: float, hi: float, iters: int,
                         tol: float = 1.0, probe: Iterable[tuple[float, float]] = ()) -> float:
    """Critical step by bisection on log Δt: ``growth(Δt) <= tol`` is stable.

    ``lo`` must be stable and ``hi`` unstable (both checked; ``probe``, the
    evaluations so far, goes into the error message).  Returns √(lo·hi) after
    ``iters`` halvings of the log-bracket.
    """
    if not growth(lo) <= tol or not growth(hi) > tol:
        raise ValueError(f"[{lo}, {hi}] s does not bracket the critical step: {list(probe)}")
    for _ in range(iters):
        mid = math.sqrt(lo * hi)
        if growth(mid) <= tol:
            lo = mid
        else:
            hi = mid
    return math.sqrt(lo * hi)

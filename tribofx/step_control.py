"""Step controllers of the slow time: which step :meth:`tribofx.stepper.Stepper.run` takes next.

:meth:`tribofx.stepper.Stepper.run` is the one slow-time loop; a controller
decides the steps:

* :class:`FixedStep` — the nominal step Δt; a step whose Newton solve fails
  is halved (up to the stepper's ``max_cuts`` times) and the step doubles back
  as soon as the time is aligned with the coarser step;
* :class:`ErrorControl` — BDF2 wear under error control: each evolving
  interface gives the error estimate of its last step (``step_error()``, of
  order ``error_order``); a step whose estimate per unit step exceeds tol/T
  (``per="unit_step"``; ``per="step"``: whose estimate exceeds tol) is
  rejected and retried with a smaller step, an accepted one proposes the next,
  by the elementary rule (``rule="i"``: the last estimate alone) or
  Gustafsson's PI rule (``rule="pi"``: the last two accepted estimates, which
  damps the oscillating step sequences of the elementary one near its
  stability limit; Gustafsson, ACM TOMS 17 (1991) 533; Hairer, Nørsett &
  Wanner, *Solving ODEs I*, §II.4).

A controller's state — the step it proposes (``dt``), the halving level
(``cuts``) and the PI rule's memory (``err_prev``) — is part of the stepper's
state and checkpoint (:meth:`StepController.state`), so a resumed run goes on
with the steps it would have taken.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import TYPE_CHECKING, Any, cast

from .reports import NewtonDivergence

if TYPE_CHECKING:
    from .stepper import Stepper, StepReport

__all__ = ["ERROR_MEASURES", "STEP_RULES", "ErrorControl", "FixedStep", "StepController",
           "step_factor"]

#: what tol bounds: the sum of the steps' estimates (per unit step), or each one
ERROR_MEASURES = ("unit_step", "step")
#: step-size rules: elementary (integral) or proportional-integral
STEP_RULES = ("i", "pi")


def step_factor(r: float, p: float, r_prev: float | None = None) -> float:
    """Return the factor of the next step from the normalized estimate ``r`` = E/allowed.

    ``p``: the order of r in Δt.  Both rules aim at r = 0.9^p (the safety factor
    0.9 on the step): with ρ = r/0.9^p, elementary ρ^(−1/p) = 0.9 r^(−1/p); with
    ``r_prev`` (the previous accepted step's r) Gustafsson's PI rule
    ρ^(−0.7/p) ρ_prev^(0.4/p), ρ_prev floored at 0.01 (a far smaller previous
    estimate, e.g. of a start-up step, would cut an accepted step by up to 5×).
    Limited to [0.2, 2]; r = 0 gives 2, a NaN 0.2.
    """
    if r == 0:
        return 2.0
    if r != r:
        return 0.2
    if r_prev is None:
        f = 0.9 * r ** (-1 / p)
    else:
        target = 0.9 ** p
        f = (r / target) ** (-0.7 / p) * max(r_prev / target, 1e-2) ** (0.4 / p)
    return min(2.0, max(0.2, f))


class StepController(ABC):
    """The step sequence of one slow-time run (see the module docstring).

    Attributes:
        dt: the step proposed next (s); None before a run.
        cuts: halvings of the step after Newton failures.
        err_prev: the PI rule's memory ``[r, p]`` (None: none).
    """

    #: whether an accepted solve may still be rejected (the loop then keeps its entry state)
    rejects = False

    def __init__(self, dt: float | None = None):
        self.dt = None if dt is None else float(dt)
        self.cuts = 0
        self.err_prev: list | None = None

    @property
    def nominal(self) -> float | None:
        """The step the progress bar counts in (s)."""
        return self.dt

    # -- state (the stepper's state and checkpoint) -----------------------------------
    def state(self) -> dict[str, Any]:
        """Return the controller's part of the stepper's state (JSON)."""
        return {"dt": self.dt, "cuts": self.cuts, "err_prev": self.err_prev}

    def restore(self, state: dict[str, Any]) -> None:
        """Restore a :meth:`state` (one without ``err_prev``: no PI memory)."""
        self.dt, self.cuts = state["dt"], state["cuts"]
        self.err_prev = state.get("err_prev")

    def take_over(self, state: dict[str, Any]) -> None:
        """Go on from the state of the controller this one replaces (a resumed run)."""
        self.cuts = state["cuts"]

    # -- the loop's questions -------------------------------------------------------------
    def start(self, stepper: Stepper, T: float) -> None:
        """Check that the controller can drive ``stepper`` to ``T``; set the first step."""
        if self.dt is None:
            raise ValueError("no step: give Stepper.run a step (s) or a step controller")

    @abstractmethod
    def next_step(self, t: float, T: float) -> float:
        """Return the step to try from ``t`` (s)."""

    @abstractmethod
    def failed(self, stepper: Stepper, h: float, error: NewtonDivergence) -> None:
        """Cut the step after a Newton failure of ``h`` (state restored), or raise ``error``."""

    def judge(self, stepper: Stepper, h: float, report: StepReport,
              saved: dict[str, Any] | None) -> bool:
        """Accept the converged step of ``h`` (True), or reject it (state back to ``saved``)."""
        return True


class FixedStep(StepController):
    """The nominal step ``dt`` (s), halved on Newton failures (see the module docstring)."""

    def next_step(self, t: float, T: float) -> float:
        """Return the nominal step at the current halving level (the last one up to T)."""
        return min(cast(float, self.dt) / 2**self.cuts, T - t)     # (start() checked dt)

    def failed(self, stepper: Stepper, h: float, error: NewtonDivergence) -> None:
        """Halve the step; raise ``error`` beyond ``stepper.max_cuts`` halvings."""
        self.cuts += 1
        if self.cuts > stepper.max_cuts:
            self.cuts -= 1
            raise error

    def judge(self, stepper: Stepper, h: float, report: StepReport,
              saved: dict[str, Any] | None) -> bool:
        """Accept; double the step back once t is aligned with the coarser step."""
        while self.cuts > 0 and _aligned(stepper.t, cast(float, self.dt) / 2 ** (self.cuts - 1)):
            self.cuts -= 1
        return True


class ErrorControl(StepController):
    """Error control of BDF2 wear: each step's estimate held within ``tol`` (mm).

    Args:
        dt: the first step (s).
        tol: the tolerance (mm): per unit step (``per="unit_step"``) each
            step's estimate E of order p may be at most tol·Δt/T, so that the
            steps' errors add up to about tol (a step above it is retried with
            Δt·max(0.2, 0.9 (tol Δt/(T E))^(1/(p−1)))); per step
            (``per="step"``) each estimate is held at tol itself (the local
            error control of ODE codes: where wear damps its own errors the
            final error stays near tol at far fewer steps, elsewhere it may add
            up to a multiple of tol).
        per: ``"unit_step"`` or ``"step"``.
        rule: ``"i"`` (elementary) or ``"pi"`` (Gustafsson) for the next step
            (:func:`step_factor`); a rejected step is retried by the elementary
            rule, and the step after a rejection or a Newton failure's halving
            does not grow (Gustafsson).
        filtered: each estimate is filtered through the step's implicit
            operator (:meth:`tribofx.stepper.Stepper.defect_filter`).

    A step at the smallest size Δt_min = 1e-6 T is accepted whatever its
    estimate (``report.forced``): across a jump of the rate (a node entering
    contact) the estimate per unit step does not vanish with Δt, and the step
    boundary at the jump is the best the scheme can do.  A NaN estimate is a
    rejection.  Newton failures halve the step as without control.
    """

    rejects = True

    def __init__(self, dt: float, tol: float, per: str = "unit_step", rule: str = "i",
                 filtered: bool = False):
        if per not in ERROR_MEASURES:
            raise ValueError(f"unknown error control per {per!r}: unit_step or step")
        if rule not in STEP_RULES:
            raise ValueError(f"unknown step-size rule {rule!r}: i or pi")
        super().__init__(dt)
        self.first, self.tol, self.per = float(dt), float(tol), per
        self.rule, self.filtered = rule, bool(filtered)
        self.rejected = 0      # rejections since the last accepted step
        self.T = self.dt_min = 0.0

    @property
    def nominal(self) -> float:
        """The first step (s): the progress bar counts in it."""
        return self.first

    def take_over(self, state: dict[str, Any]) -> None:
        """Go on with the proposed step, the cut level and the PI memory of ``state``."""
        self.restore(state)

    def start(self, stepper: Stepper, T: float) -> None:
        """Refuse wear other than BDF2; the first step unless resumed; Δt_min = 1e-6 T."""
        if not all(w.scheme.bdf2 for w in stepper.wears):
            raise ValueError("error control needs BDF2: Wear(..., scheme=BDF2)")
        if not stepper.steps:
            self.dt = self.first      # a resumed run goes on with its proposed step
        self.T, self.dt_min = T, 1e-6 * T
        self.rejected = 0

    def next_step(self, t: float, T: float) -> float:
        """Return the proposed step (the last one up to T)."""
        return min(cast(float, self.dt), T - t)     # (start() has set it)

    def failed(self, stepper: Stepper, h: float, error: NewtonDivergence) -> None:
        """Halve the step; raise ``error`` beyond ``stepper.max_cuts`` halvings."""
        self.cuts += 1
        if self.cuts > stepper.max_cuts:
            raise error
        self.dt = h / 2

    def judge(self, stepper: Stepper, h: float, report: StepReport,
              saved: dict[str, Any] | None) -> bool:
        """Accept or reject the step by its estimate; propose the next step."""
        errs = [(e, w.error_order) for w, e in
                ((w, w.step_error(stepper.defect_filter(w) if self.filtered else None))
                 for w in stepper.wears) if e is not None]
        err, order = max(errs) if errs else (None, 2)
        # error per unit step: a step may err by tol·Δt/T, so the errors of all
        # steps add up to tol; E ∝ Δt^p, so E/Δt ∝ Δt^(p−1).  Per step: E ≤ tol
        unit = self.per == "unit_step"
        allowed = self.tol * h / self.T if unit else self.tol
        p_eff = order - 1 if unit else order
        bad = err is not None and not err <= allowed        # NaN: rejected
        r = 0.0 if err is None else err / allowed
        # PI: the memory of the last accepted step of the same estimator (its order p)
        # on a step that follows neither a rejection nor a Newton failure's halving
        after_cut = self.rejected or self.cuts
        memory = self.err_prev
        pi = (self.rule == "pi" and not bad and not after_cut and memory is not None
              and memory[1] == p_eff)
        factor = step_factor(r, p_eff, cast(list, memory)[0] if pi else None)  # pi: a memory
        if self.rule == "pi" and after_cut and not bad:
            factor = min(factor, 1.0)
        at_min = h <= self.dt_min * (1 + 1e-9)
        forced = bad and err == err and at_min
        # (saved is the entry state: this controller rejects, so the loop saves it)
        if bad and err != err and at_min:
            stepper.restore(cast("dict[str, Any]", saved))
            raise NewtonDivergence(f"error control: NaN estimate at t = {stepper.t:g} s")
        if bad and not forced:
            stepper.restore(cast("dict[str, Any]", saved))
            self.rejected += 1
            self.dt = max(h * factor, self.dt_min)
            return False
        self.cuts = 0
        if h == self.dt:       # a last, shortened step keeps the memory as the proposal
            self.err_prev = None if forced or not r > 0 else [r, p_eff]
        report.error, report.rejected, self.rejected = err, self.rejected, 0
        report.forced = forced
        if h == self.dt or factor < 1:   # a last, shortened step keeps the proposal
            self.dt = max(h * factor, self.dt_min)
        return True


def _aligned(t: float, h: float) -> bool:
    return abs(t / h - round(t / h)) < 1e-9

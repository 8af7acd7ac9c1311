"""Error-controlled slow time: the accept/reject loop of :meth:`tribofx.stepper.Stepper.run`.

Each evolving interface gives the error estimate of its last step
(``step_error()``, of order ``error_order``); a step whose estimate per unit
step exceeds tol/T (``per="unit_step"``; ``per="step"``: whose estimate exceeds
tol) is rejected and retried with a smaller step, an accepted one proposes the
next (see :meth:`tribofx.stepper.Stepper.run`), by the elementary controller
(``"i"``: the last estimate alone) or Gustafsson's PI controller (``"pi"``: the
last two accepted estimates, which damps the oscillating step sequences of the
elementary one near its stability limit; Gustafsson, ACM TOMS 17 (1991) 533;
Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.4).
"""

from . import interrupt
from .problem import NewtonDivergence

__all__ = ["CONTROLLERS", "CONTROLS", "run_controlled", "step_factor"]

#: what tol bounds: the sum of the steps' estimates, or each one
CONTROLS = ("unit_step", "step")
#: step-size controllers: elementary (integral) or proportional-integral
CONTROLLERS = ("i", "pi")


def step_factor(r, p, r_prev=None):
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


def run_controlled(stepper, T, dt, on_step, progress, tol, per="unit_step", filtered=False,
                   controller="i"):
    """Run the error-controlled loop of :meth:`tribofx.stepper.Stepper.run` (``stepper``).

    ``filtered``: the estimates are filtered through each step's implicit
    operator (:meth:`tribofx.stepper.Stepper.defect_filter`).  ``controller``:
    ``"i"`` or ``"pi"`` (:func:`step_factor`); the PI controller's memory, the
    last accepted step's normalized estimate and its order ``[r, p]``, is the
    stepper's ``err_prev`` (in its state and checkpoint; None after a forced
    step or a zero estimate, and unused when the order changes, e.g. from the
    start-up estimate to Milne's); a rejected step is retried by the elementary
    rule, and the step after a rejection or a Newton failure's halving does not
    grow (Gustafsson).

    A step at the smallest size Δt_min = 1e-6 T is accepted whatever its
    estimate (``report.forced``): across a jump of the rate (a node entering
    contact) the estimate per unit step does not vanish with Δt, and the step
    boundary at the jump is the best the scheme can do.  A NaN estimate is
    a rejection.
    """
    if per not in CONTROLS:
        raise ValueError(f"unknown error control per {per!r}: unit_step or step")
    if controller not in CONTROLLERS:
        raise ValueError(f"unknown step-size controller {controller!r}: i or pi")
    if any(getattr(w, "scheme", None) != "bdf2" for w in stepper.wears):
        raise ValueError("error control (tol) needs BDF2 wear: Wear(scheme='bdf2')")
    if not stepper.steps:
        stepper.dt = dt            # a resumed run goes on with its proposed step
    dt_min = 1e-6 * T
    stepper._bar = (T, dt)
    stepper._progress(progress)     # resumed from a checkpoint: the bar goes on
    interrupt.arm()
    rejected = 0
    while stepper.t < T * (1 - 1e-12):
        h = min(stepper.dt, T - stepper.t)
        saved = stepper.state()
        try:
            report = stepper.step(h)
        except NewtonDivergence:
            stepper.restore(saved)
            stepper.cuts += 1
            if stepper.cuts > stepper.max_cuts:
                raise
            stepper.dt = h / 2
            continue
        errs = [(e, w.error_order) for w, e in
                ((w, w.step_error(stepper.defect_filter(w) if filtered else None))
                 for w in stepper.wears) if e is not None]
        err, order = max(errs) if errs else (None, 2)
        # error per unit step: a step may err by tol·Δt/T, so the errors of all
        # steps add up to tol; E ∝ Δt^p, so E/Δt ∝ Δt^(p−1).  Per step: E ≤ tol
        unit = per == "unit_step"
        allowed = tol * h / T if unit else tol
        p_eff = order - 1 if unit else order
        bad = err is not None and not err <= allowed        # NaN: rejected
        r = 0.0 if err is None else err / allowed
        # PI: the memory of the last accepted step of the same estimator (its order p)
        # on a step that follows neither a rejection nor a Newton failure's halving
        after_cut = rejected or stepper.cuts
        memory = stepper.err_prev
        pi = (controller == "pi" and not bad and not after_cut and memory is not None
              and memory[1] == p_eff)
        factor = step_factor(r, p_eff, memory[0] if pi else None)
        if controller == "pi" and after_cut and not bad:
            factor = min(factor, 1.0)
        forced = bad and err == err and h <= dt_min * (1 + 1e-9)
        if bad and err != err and h <= dt_min * (1 + 1e-9):
            stepper.restore(saved)
            raise NewtonDivergence(f"error control: NaN estimate at t = {stepper.t:g} s")
        if bad and not forced:
            stepper.restore(saved)
            rejected += 1
            stepper.dt = max(h * factor, dt_min)
            continue
        stepper.cuts = 0
        if h == stepper.dt:       # a last, shortened step keeps the memory as the proposal
            stepper.err_prev = None if forced or not r > 0 else [r, p_eff]
        report.error, report.rejected, rejected = err, rejected, 0
        report.forced = forced
        if h == stepper.dt or factor < 1:   # a last, shortened step keeps the proposal
            stepper.dt = max(h * factor, dt_min)
        stepper._accepted(report, on_step, progress)

"""Slow time of finite wear: θ-scheme, fast-time cycles, step cutting, state and checkpoints.

The stepper integrates the shape evolution law (28) of one or more evolving
interfaces (:class:`tribofx.interfaces.Wear`) on the slow time t (chapter
§4.4), with the deformation problem at each t solved as a standard contact
problem (§4.2–4.3).  It knows nothing of the physics: it builds the Problems
of the scheme from the components, moves the slow-time history on, solves,
checks the worn mesh, cuts failed steps and writes a checkpoint every step.

Schemes (chosen by the interface's ``scheme``, a :class:`tribofx.scheme.Scheme`,
and ``averaged``):

* θ = 1, instantaneous rate: one monolithic :class:`tribofx.problem.Problem` in
  all unknowns (deformation unknowns first, then the shape unknowns w, ζ);
* θ = 0, instantaneous rate: the shape step (w, ζ) with the rate of the known
  state, then the deformation problem (u, λ, ...) on the new shape;
* averaged rate (time-scale separation, eqs. 21–23): per slow step one fast-time
  loading cycle (:class:`ReciprocatingCycle`) at the fixed shape accumulates the
  wear increment ΔW = Σ_j K T_T·Δs_j node by node (eq. 22); W̄̇ = ΔW/Δτ (eq. 23)
  drives the shape step; θ > 0 by a fixed-point (Picard) iteration, each
  iterate re-solving a cycle on the predicted shape.

A *hold* (:class:`tribofx.hold.Hold`, the stepper's ``hold``) replaces the
plain Newton solve of the deformation problem by a solve with a response held
at its target (e.g. the countersurface position that carries a prescribed
force, by a secant of complete solves or the bordered Newton system), with its
first trial estimated at step entry (:meth:`tribofx.hold.Hold.begin`).

The steps: :meth:`Stepper.run` is the one slow-time loop, and a step
controller of :mod:`tribofx.step_control` chooses its steps — a fixed step
(:class:`~tribofx.step_control.FixedStep`: a step that fails, by Newton
divergence, a force not reached or an inverted cell, :class:`MeshInversion`,
restores the state at entry and is halved, up to ``max_cuts`` times, and
doubles back once the time is aligned with the coarser step) or the error
control of BDF2 wear (:class:`~tribofx.step_control.ErrorControl`).

The evolving interface (``wear``; a list of them for the wear of several
surfaces, e.g. both bodies of a two-body contact, advanced together with one
shape Problem) answers: ``scheme`` (a :class:`tribofx.scheme.Scheme`) and ``averaged``;
``shape_unknowns()`` (the unknowns of the shape step, e.g. [w, ζ]);
``begin_step(dt)`` (history w_n ← w and Δt set) and ``end_step()`` (Δt = 0);
``min_volume_factor()`` (smallest det(I + Grad w), collective); ``body.mesh.comm``;
and, for fast-time cycles, ``rate_bar`` (the nodal averaged rate it is driven
by), ``nodal_increment()`` (the wear increment of the last sub-step) and
``body.w``/``body.w_n``.  :class:`tribofx.interfaces.Wear` is such an interface, and
so is a transient :class:`tribofx.interfaces.Film` (``Film.transient``: no shape
unknowns, its squeeze term's histories move on in ``begin_step``);
one whose shape unknowns live elsewhere (e.g. on a cross-section extruded along
the sliding direction) needs only the same methods and, if its unknowns need
a different assembly, a ``problem_class`` with the constructor of
:class:`tribofx.problem.Problem`.

State: :meth:`Stepper.state` holds the time, the step count, the step
controller's state (the proposed Δt, the cut level, the PI step rule's memory
``err_prev``), every Function and Constant
of the components (unknowns, histories, countersurface positions) and the extra
``parameters`` (e.g. load factors).  A :class:`tribofx.checkpoint.Checkpoint`
writes it after every accepted step: one NumPy ``.npz`` of the local arrays per
rank and a JSON file of the scalars; a restore
needs the same mesh partition (the same number of ranks).  Units: s, mm.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeAlias, cast

import numpy as np
import numpy.typing as npt
from mpi4py import MPI

from . import interrupt
from .checkpoint import Checkpoint, assign_fields, field_arrays, field_names
from .cycles import ReciprocatingCycle
from .error_filter import filtered_defect
from .forms import wear as wf
from .problem import NewtonDivergence, Problem, _unique
from .step_control import FixedStep, StepController

if TYPE_CHECKING:
    from dolfinx import fem
    from tqdm import tqdm

    from .hold import Hold
    from .problem import ProblemComponent
    from .protocols import ComponentBase
    from .reports import NewtonReport

    #: an evolving interface: a tribofx.interfaces.Wear or SteadyWear, a transient Film,
    #: or the user's own; duck-typed (what the stepper asks: the module docstring)
    EvolvingInterface: TypeAlias = Any

__all__ = ["MeshInversion", "ReciprocatingCycle",
           "StepReport", "Stepper", "nominal_steps"]


class MeshInversion(NewtonDivergence):
    """The shape update inverted a cell (det(I + Grad w) ≤ 0); the step must be cut."""


@dataclass
class StepReport:
    """Outcome of one slow step.

    Attributes:
        dt: the step (s).
        reports: Newton reports of the shape and deformation solves of the step.
        iterations: all Newton iterations of the step (fast-time cycles included).
        cycle_iterations: Newton iterations of the fast-time cycles and restarts.
        picard: fixed-point iterations (θ > 0 with cycles).
        error: the step's error estimate (mm) under error control, else None.
        rejected: steps rejected by the error control before this one was accepted.
        forced: accepted at the error control's smallest step above the tolerance.
    """

    dt: float
    reports: list = field(default_factory=list)
    iterations: int = 0
    cycle_iterations: int = 0
    picard: int = 0
    error: float | None = None
    rejected: int = 0
    forced: bool = False


class Stepper:
    """Slow-time integration of the shape evolution of ``wear`` (see the module docstring).

    Args:
        components: bodies and interfaces of the problem (``wear`` among them).
        wear: the evolving interface (e.g. :class:`tribofx.interfaces.Wear`).
        cycle: a fast-time cycle (:class:`ReciprocatingCycle`) for time-scale
            separation (needs ``wear.averaged``), or None.
        parameters: further Constants of the state (e.g. load factors).
        max_cuts: step halvings allowed per step.
        checkpoint: directory of the checkpoint written every step (None: none).
        picard_tol, max_picard: fixed-point iteration of θ > 0 with cycles
            (relative change of the nodal shape increment, iterations).
        name: options prefix of the Problems (``tribofx_<name>_``, ``..._shape_``).
        verbose: print Newton histories.
        problem_kw: further keyword arguments of the Problems.
        problem_class: class of the Problems (default :class:`tribofx.problem.Problem`;
            same constructor, e.g. :class:`tribofx.reduced.ReducedProblem`).
        schedule: pairs (Constant, f) of time-dependent data (speeds, loads,
            positions): each step sets the Constant to f(t_{n+1}) after the
            interfaces' ``begin_step`` (their histories hold t_n); part of the state.
    """

    def __init__(self, components: Iterable[ComponentBase],
                 wear: EvolvingInterface | Sequence[EvolvingInterface],
                 cycle: ReciprocatingCycle | None = None,
                 parameters: Iterable[fem.Constant] = (), max_cuts: int = 6,
                 checkpoint: str | os.PathLike[str] | None = None, picard_tol: float = 1e-8,
                 max_picard: int = 20, name: str = "wear", verbose: bool = False,
                 problem_kw: Mapping[str, Any] | None = None,
                 problem_class: type[Problem] = Problem,
                 schedule: Iterable[tuple[fem.Constant,
                                          Callable[[float], float | npt.ArrayLike]]] = ()
                 ) -> None:
        self.wears: list[EvolvingInterface] = (list(wear) if isinstance(wear, (list, tuple))
                                               else [wear])
        wear = self.wears[0]
        if any((w.scheme, w.averaged) != (wear.scheme, wear.averaged) for w in self.wears):
            raise ValueError("the evolving interfaces of one stepper need the same scheme "
                             "(scheme, averaged)")
        if cycle is not None and not wear.averaged:
            raise ValueError("fast-time cycles need a wear interface with averaged=True")
        if wear.averaged and cycle is None:
            raise ValueError("an averaged wear rate needs a fast-time cycle")
        # (ComponentBase; the Component protocol is the contract, as in Problem)
        self.components, self.wear, self.cycle = (
            cast("list[ProblemComponent]", list(components)), wear, cycle)
        self.schedule = list(schedule)
        self.parameters = list(parameters) + [c for c, _ in self.schedule]
        self.max_cuts, self.verbose = int(max_cuts), verbose
        self.picard_tol, self.max_picard = picard_tol, max_picard
        kw = problem_kw or {}
        shape = [u for w in self.wears for u in w.shape_unknowns()]
        every = _unique([u for c in self.components for u in c.unknowns()])
        deformation = [u for u in every if not any(u is s for s in shape)]
        self.monolithic = wear.scheme.implicit and not wear.averaged
        self.shape: Problem | None       # the shape step's problem (None: monolithic)
        if self.monolithic:
            self.problem = problem_class(self.components, deformation + shape, name=name, **kw)
            self.shape = None
        else:
            self.problem = problem_class(self.components, deformation, name=name, **kw)
            self.shape = problem_class(self.components, shape, name=f"{name}_shape", **kw)
        # a tribofx.hold.Hold: the deformation solved with a response held
        self.hold: Hold | None = None
        self.comm = wear.body.mesh.comm
        self.checkpoint = None if checkpoint is None else Checkpoint(checkpoint, self.comm)
        self.t, self.steps = 0.0, 0
        #: the step controller of the last (or next) run: its state is the stepper's too
        self.controller: StepController = FixedStep()
        self.history: dict[str, Any] = {}   # the case's JSON-able records, in the checkpoint
        self.last_increment: npt.NDArray[np.float64] | None = None
        self.last_increments: list[npt.NDArray[np.float64]] | None = None

    # -- set-up ------------------------------------------------------------------
    def shape_unknown_fraction(self) -> float:
        """Fraction of all unknowns that belong to the shape step (w and ζ)."""
        def n(f: fem.Function) -> int:
            im = f.function_space.dofmap.index_map
            return im.size_global * f.function_space.dofmap.index_map_bs
        shape = sum(n(f) for w in self.wears for f in w.shape_unknowns())
        total = sum(n(f) for f in self.problem.u) + (0 if self.monolithic else shape)
        return shape / total

    # -- state -------------------------------------------------------------------
    def _fields(self) -> list[fem.Function | fem.Constant]:
        return self.problem.state_fields() + self.parameters

    def field_names(self) -> list:
        """Names of the state fields (Functions by name, Constants by position)."""
        return field_names(self._fields())

    def state(self) -> dict:
        """Copy of the full state: t, steps, the step controller's (Δt, cuts, PI memory), fields."""
        return {"t": self.t, "steps": self.steps, **self.controller.state(),
                "fields": field_arrays(self._fields())}

    def restore(self, state: dict) -> None:
        """Restore a state from :meth:`state` (or :meth:`Checkpoint.read`)."""
        fields = self._fields()
        if len(fields) != len(state["fields"]):
            raise ValueError("state does not match the stepper's fields")
        for f, a in zip(fields, state["fields"]):
            if hasattr(f, "x") and f.x.array.shape != np.shape(a):
                raise ValueError(f"state of {cast('fem.Function', f).name!r} has shape "
                                 f"{np.shape(a)}")
        assign_fields(fields, state["fields"])
        self.t, self.steps = state["t"], state["steps"]
        self.controller.restore(state)
        self.problem.refresh()

    def load_checkpoint(self, directory: str | os.PathLike[str] | None = None) -> None:
        """Restore the state of the checkpoint in ``directory`` (default: this stepper's)."""
        ck = self.checkpoint if directory is None else Checkpoint(directory, self.comm)
        if ck is None:
            raise ValueError("load_checkpoint: this stepper writes no checkpoint; give the "
                             "directory (load_checkpoint(path)) or build it with checkpoint=")
        state = ck.read()
        self.restore(state)
        self.history = state["history"]

    # -- one slow step -------------------------------------------------------------
    def _check_mesh(self) -> None:
        m = min(w.min_volume_factor() for w in self.wears)
        if not m > 0:
            raise MeshInversion(f"shape update inverts the mesh (min det(I + Grad w) = {m:.3e})")

    def _deform(self) -> list[NewtonReport]:
        """Solve the deformation problem (plainly or with the hold's response held); reports."""
        if self.hold is not None:
            return self.hold.solve().reports
        return [self.problem.solve(verbose=self.verbose)]

    def step(self, dt: float) -> StepReport:
        """Advance by Δt (s) without cutting; returns a :class:`StepReport`.

        On failure the state at entry is restored and :class:`NewtonDivergence`
        (or :class:`MeshInversion`) raised.
        """
        saved = self.state()
        out = StepReport(dt=dt)
        for w in self.wears:
            w.begin_step(dt)
        for c, f in self.schedule:
            # (DOLFINx types Constant.value's setter NDArray; it takes a float)
            c.value = f(self.t + dt)  # type: ignore[assignment]
        if self.hold is not None:
            self.hold.begin(dt)
        try:
            if self.cycle is not None:
                self._cycle_step(dt, out)
            elif self.monolithic:
                out.reports += self._deform()
                self._check_mesh()
            else:
                assert self.shape is not None       # a staggered scheme has a shape problem
                out.reports.append(self.shape.solve(verbose=self.verbose))
                self._check_mesh()
                # warm start: the deformed configuration x = X̂ + u is kept (gaps and
                # active set stay), only the worn reference has changed
                out.reports += self._deform()
        except NewtonDivergence:
            self.restore(saved)
            raise
        finally:
            for w in self.wears:
                w.end_step()
        self.problem.commit()
        self.t += dt
        self.steps += 1
        out.iterations += sum(r.iterations for r in out.reports)
        return out

    # -- fast-time cycles (time-scale separation) --------------------------------------
    def start(self) -> int:
        """Settle the deformation problem before the first step; returns Newton iterations.

        With a fast-time cycle: erase the contact memory and slide the
        countersurface to the centre (:meth:`restart`); else nothing.
        """
        return self.restart() if self.cycle is not None else 0

    def restart(self) -> int:
        """Erase the contact memory, start the cycle and run in (no wear); Newton iterations."""
        # (with a fast-time cycle, as every method of this section)
        P, cyc = self.problem, cast(ReciprocatingCycle, self.cycle)
        cyc.start()
        P.commit()
        its = P.solve_by_homotopy(verbose=self.verbose).iterations
        P.commit()
        for pos in cyc.run_in:
            cyc.move(pos)
            its += P.solve_by_homotopy(verbose=self.verbose).iterations
            P.commit()
        return its

    def run_cycle(self) -> tuple[list[npt.NDArray[np.float64]], int]:
        """One loading cycle at the current shape; returns (ΔW nodal (mm) per interface, its).

        ΔW = Σ_j K T_T·Δs_j (eq. 22) over the cycle's sub-steps (not the run-in),
        one array per evolving interface (:attr:`wears` order).
        """
        P, cyc = self.problem, cast(ReciprocatingCycle, self.cycle)
        its = self.restart()
        cyc.begin_work()
        dW = [np.zeros_like(w.rate_bar.x.array) for w in self.wears]
        for pos in cyc.positions:
            cyc.move(pos)
            its += P.solve_by_homotopy(verbose=self.verbose).iterations
            cyc.record_work()
            for d, w in zip(dW, self.wears):
                d += w.nodal_increment()
            P.commit()
        return dW, its

    def _shape_step(self, rates: Sequence[npt.NDArray[np.float64]],
                    w0: Sequence[npt.NDArray[np.float64]],
                    out: StepReport) -> list[npt.NDArray[np.float64]]:
        """Shape step (28) from w0 with the nodal rates (mm/s), one per interface."""
        for w, r, a in zip(self.wears, rates, w0):
            w.body.w.x.array[:] = a
            w.rate_bar.x.array[:] = r
        assert self.shape is not None       # fast-time cycles: a staggered scheme
        out.reports.append(self.shape.solve(verbose=self.verbose))
        self._check_mesh()
        return [w.body.w.x.array - a for w, a in zip(self.wears, w0)]

    def _max(self, arrays: Iterable[npt.NDArray[np.float64]]) -> float:
        return self.comm.allreduce(max((float(np.max(np.abs(a), initial=0.0)) for a in arrays),
                                       default=0.0), op=MPI.MAX)

    def _cycle_step(self, dt: float, out: StepReport) -> None:
        theta, tau = self.wear.scheme.theta, cast(ReciprocatingCycle, self.cycle).period
        dW, its = self.run_cycle()
        rate_n = [wf.cycle_average_rate(d, tau) for d in dW]  # eq. 23
        for w, r in zip(self.wears, rate_n):
            w.set_start_rate(r)     # BDF2's first-step error estimate: the rate at t_n
        w0 = [w.body.w.x.array.copy() for w in self.wears]
        dw_prev = self._shape_step(rate_n, w0, out)
        if theta > 0:
            for it in range(1, self.max_picard + 1):
                dW1, its1 = self.run_cycle()
                its += its1
                rate = [(1 - theta) * r + theta * wf.cycle_average_rate(d, tau)
                        for r, d in zip(rate_n, dW1)]
                dw = self._shape_step(rate, w0, out)
                change = self._max([a - b for a, b in zip(dw, dw_prev)])
                scale = self._max(dw)
                dw_prev = dw
                out.picard = it
                if change <= self.picard_tol * max(scale, 1e-300):
                    break
            else:
                raise NewtonDivergence(f"Picard iteration of the θ-scheme did not converge in "
                                       f"{self.max_picard} cycles")
            dW = dW1
        for w, a in zip(self.wears, w0):
            w.body.w_n.x.array[:] = a
        # deformation on the new shape (at the centre, fully developed sliding)
        its += self.restart()
        out.iterations += its
        out.cycle_iterations = its
        self.last_increments = dW
        self.last_increment = dW[0]

    # -- slow time -------------------------------------------------------------------
    def run(self, T: float, controller: StepController | float | None = None,
            on_step: Callable[[Stepper, StepReport], object] | None = None,
            progress: tqdm | None = None) -> None:
        """Advance from the current time to ``T`` (s), the steps chosen by ``controller``.

        ``controller``: a :class:`tribofx.step_control.StepController` (e.g.
        :class:`~tribofx.step_control.ErrorControl` for BDF2 wear under error
        control), a number (s: :class:`~tribofx.step_control.FixedStep` of that
        nominal step) or None (the stepper's :attr:`controller`).  A new
        controller takes over the state of the one it replaces (the cut level;
        under error control also the proposed step and the PI memory), so a run
        resumed from a checkpoint goes on with its steps.

        ``on_step(stepper, report)`` is called after every accepted step, then
        the checkpoint is written (with :attr:`history`) and a SIGINT/SIGTERM
        received meanwhile stops the run (:func:`tribofx.interrupt.check`).
        Raises the last failure when a step still fails after ``max_cuts``
        halvings (the state is the last accepted one).
        """
        if controller is not None:
            if not isinstance(controller, StepController):
                controller = FixedStep(float(controller))
            controller.take_over(self.controller.state())
            self.controller = controller
        ctl = self.controller
        ctl.start(self, T)
        bar = (T, cast(float, ctl.nominal))     # (a step: start() has checked it)
        self._progress(progress, bar)   # resumed from a checkpoint: the bar goes on
        interrupt.arm()
        while self.t < T * (1 - 1e-12):
            h = ctl.next_step(self.t, T)
            saved = self.state() if ctl.rejects else None
            try:
                report = self.step(h)
            except NewtonDivergence as err:
                ctl.failed(self, h, err)
                continue
            if not ctl.judge(self, h, report, saved):
                continue
            if on_step is not None:
                on_step(self, report)
            if self.checkpoint is not None:
                self.checkpoint.write(self.state(), self.field_names(), self.history)
            self._progress(progress, bar)
            interrupt.check(self.comm, self.t)

    def defect_filter(
            self, wear: EvolvingInterface
    ) -> Callable[[npt.NDArray[np.float64]], npt.NDArray[np.float64]]:
        """Return the filter of ``wear``'s error estimate through the step's implicit operator.

        A callable taking the nodal defect to :func:`tribofx.error_filter.filtered_defect`
        (the force held by the hold's border, if any); monolithic steps only.
        """
        if not self.monolithic or self.cycle is not None:
            raise ValueError("the filtered error estimate needs a monolithic implicit step")
        border = None if self.hold is None else self.hold.border
        if self.hold is not None and border is None:
            raise ValueError("the filtered error estimate needs the hold's border "
                             "(the response held in the filter's solve)")
        return lambda d: filtered_defect(self.problem, wear, d, border, self.wears)

    def _progress(self, progress: tqdm | None, bar: tuple[float, float]) -> None:
        """Move the bar to the nominal steps (``bar`` = (T, Δt)) that t has completed.

        By time, so that cut steps and the steps of error control count as the
        nominal steps they make up: the bar ends at its total, ⌈T/Δt⌉.
        """
        if progress is None or not hasattr(progress, "n"):
            return
        T, d = bar
        n = nominal_steps(T, d) if self.t >= T * (1 - 1e-12) else math.floor(self.t / d + 1e-9)
        if n > progress.n:
            progress.update(n - progress.n)


def nominal_steps(T: float, dt: float) -> int:
    """Return the number of steps of ``dt`` to ``T`` without cuts (the last may be shorter)."""
    return math.ceil(T / dt - 1e-9)


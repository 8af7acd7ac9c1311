"""Fast-time loading cycles of time-scale separation (chapter §4.2, eqs. 21–23; §5.1).

A cycle moves a contact's countersurface through a loading programme at the
fixed worn shape; :class:`tribofx.stepper.Stepper` runs one per slow step (or
per Picard iterate) and accumulates the wear increments of its sub-steps.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, cast

import numpy as np

if TYPE_CHECKING:
    from .interfaces import Contact, TwoBodyContact
    from .obstacles import AnalyticObstacle, MeshedObstacle

__all__ = ["ReciprocatingCycle"]


class ReciprocatingCycle:
    """One fast-time reciprocating stroke cycle of a contact's countersurface (chapter §5.1).

    At the start of every cycle the contact memory is erased (friction
    multiplier 0) and the countersurface put at −A (A = stroke/2); a run-in
    stage slides it to the centre (fully developed sliding), then the cycle
    +A, −2A (to −A), +A (back to the centre) follows: sliding distance
    2·stroke, Δτ = 2·stroke/V.

    Args:
        contact: the :class:`tribofx.interfaces.Contact` (Lagrangian friction).
        stroke: peak-to-peak travel 2A (mm).
        fast_steps: sub-steps per cycle (multiple of 4; the run-in uses a quarter).
        V: sliding speed (mm/s).
        axis: direction of the motion (component of the counterpart's ``offset``).
        drive: callable ``drive(position)`` that moves the counterpart (mm), e.g. the
            prescribed displacement of a deformable master body; default: the
            rigid counterpart's ``offset`` along ``axis``.
        force: callable → the force (N; N/mm in plane strain) the drive exerts on
            the counterpart along ``axis`` at the solved state, or None.  With it
            every cycle measures the drive's work ∮ F dx by the trapezoidal rule
            (:attr:`work`), the bound ½ Σ |ΔF| |Δx| of that rule's error for a
            force monotone within each sub-step (:attr:`work_bound`) and the
            forces of the sub-steps (:attr:`forces`).  Over a closed cycle at
            steady state the work equals the frictional dissipation.
    """

    position: float | None      # None until the first move
    work: float | None          # None without a force, or before the first cycle
    work_bound: float | None

    def __init__(self, contact: Contact | TwoBodyContact, stroke: float, fast_steps: int, V: float,
                 axis: int = 0, drive: Callable[[float], None] | None = None,
                 force: Callable[[], float] | None = None) -> None:
        if fast_steps % 4 or fast_steps < 4:
            raise ValueError(f"fast_steps = {fast_steps} must be a positive multiple of 4")
        if stroke <= 0 or V <= 0:
            raise ValueError("stroke and V must be positive")
        if contact.lam_t is None or contact.slip_kind != "lagrangian":
            raise ValueError("a fast-time cycle needs Lagrangian friction on the contact")
        self.contact, self.stroke, self.fast_steps, self.V, self.axis = (
            contact, stroke, fast_steps, V, axis)
        self.drive, self.force = drive, force
        self.position = None
        self.work = self.work_bound = None
        self.forces: list[tuple[float | None, float]] = []
        A, m = stroke / 2, fast_steps // 4
        self.run_in = -A + A * np.arange(1, m + 1) / m  # −A → 0
        up = A * np.arange(1, m + 1) / m
        self.positions = np.concatenate([up, A - A * np.arange(1, 2 * m + 1) / m, -A + up])

    @property
    def period(self) -> float:
        """Δτ (s)."""
        return 2 * self.stroke / self.V

    @property
    def distance(self) -> float:
        """Sliding distance of the countersurface per cycle, 2·stroke (mm)."""
        return 2 * self.stroke

    def start(self) -> None:
        """Erase the contact memory and put the countersurface at −A."""
        assert self.contact.lam_t is not None     # Lagrangian friction (checked on creation)
        self.contact.lam_t.x.array[:] = 0.0
        self.move(-self.stroke / 2)

    def move(self, position: float) -> None:
        """Put the countersurface at ``position`` (mm) along the axis."""
        if self.drive is not None:
            self.drive(position)
        else:
            # no drive: the counterpart of a Contact is rigid (tribofx.obstacles): its offset
            cast("AnalyticObstacle | MeshedObstacle", cast("Contact", self.contact).counterpart
                 ).offset.value[self.axis] = position
        self.position = float(position)

    def begin_work(self) -> None:
        """Start measuring the drive's work at the current (solved) state."""
        if self.force is not None:
            self.work, self.work_bound = 0.0, 0.0
            self.forces = [(self.position, float(self.force()))]

    def record_work(self) -> None:
        """Add the sub-step just solved to the drive's work (trapezoidal rule)."""
        if self.force is not None:
            # begin_work() has set the work, and move() the positions, before
            x0, f0 = self.forces[-1]
            f1 = float(self.force())
            dx = cast(float, self.position) - cast(float, x0)
            self.work = cast(float, self.work) + 0.5 * (f0 + f1) * dx
            self.work_bound = cast(float, self.work_bound) + 0.5 * abs(f1 - f0) * abs(dx)
            self.forces.append((self.position, f1))

    def sliding_force_ratio(self, normal_force: float) -> float | None:
        """Return max |F| of the last cycle over ``normal_force`` (μ in gross sliding)."""
        if not self.forces:
            return None
        return max(abs(f) for _, f in self.forces) / normal_force

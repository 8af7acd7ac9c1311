"""The variable-step BDF2 history of a worn surface's nodal swept volumes, and its error estimate.

An evolving interface (:class:`tribofx.interfaces.Wear`, the groove's
:class:`tribofx.interfaces.SteadyWear`) writes the shape law (28) per node in
swept volumes s (per unit initial area, or length):

    c₀ s_{n+1} + c₁ s_n + Δt_{n+1} Ẇ_{n+1} = 0,   (c₀, c₁) = forms.wear.bdf2_coefficients(ω),

ω = Δt_{n+1}/Δt_n (backward Euler, (1, 0), on the first step).  :class:`SweptHistory`
keeps s_n (a nodal Function, part of the interface's state with the step sizes),
sets the weights at the start of each step and estimates the step's error for
the step controller :class:`tribofx.step_control.ErrorControl`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import numpy.typing as npt
from dolfinx import fem
from mpi4py import MPI

from .forms import wear as wf

__all__ = ["SweptHistory"]


class SweptHistory:
    """BDF2 weights, the last two steps' nodal swept volumes and sizes, and the error estimate.

    Args:
        Q: the nodal (P1) space of the swept volumes, on the worn surface's mesh.
        name: prefix of the Functions' names (checkpoints find them by name).

    ``c0``, ``c1`` (Constants) and ``swept_old`` (s_n) enter the residual
    (:func:`tribofx.forms.wear.shape_update_residual`, ``bdf2=``:attr:`weights`).
    """

    _omega: float | None                      # Δt_{n+1}/Δt_n (None on a first step)
    _rate0: npt.NDArray[np.float64] | None    # the rate at the start of a first step
    _pred: npt.NDArray[np.float64] | None     # the predictor s^P (from the third step)

    def __init__(self, Q: fem.FunctionSpace, name: str) -> None:
        msh = Q.mesh
        self.c0, self.c1 = fem.Constant(msh, 1.0), fem.Constant(msh, 0.0)
        self.swept_old = fem.Function(Q, name=f"{name}_previous_swept_volume")
        self.swept_old2 = fem.Function(Q, name=f"{name}_second_previous_swept_volume")
        self.dt_prev = fem.Constant(msh, 0.0)
        self.dt_prev2 = fem.Constant(msh, 0.0)
        self._omega = self._rate0 = self._pred = None
        self.error_order = 2

    @property
    def weights(self) -> tuple[fem.Constant, fem.Constant, fem.Function]:
        """``(c0, c1, swept_old)`` of the BDF2 residual."""
        return self.c0, self.c1, self.swept_old

    def state_fields(self) -> list[fem.Function | fem.Constant]:
        """s_n, Δt_n, s_{n−1}, Δt_{n−1} (restored with a failed step)."""
        return [self.swept_old, self.dt_prev, self.swept_old2, self.dt_prev2]

    def begin_step(self, dt: float, swept: Callable[[], npt.NDArray[np.float64]],
                   rate: Callable[[], npt.ArrayLike]) -> None:
        """Start a step of Δt (s), before the interface's history moves on.

        ``swept()``: nodal swept volumes of the step just ended (called when there
        was one); ``rate()``: nodal rate at the step's start (called on a first
        step, whose backward-Euler result is checked against forward Euler).
        """
        prev, prev2 = float(self.dt_prev.value), float(self.dt_prev2.value)
        self._pred = None
        if prev > 0:
            self.swept_old2.x.array[:] = self.swept_old.x.array
            self.swept_old.x.array[:] = swept()
            if prev2 > 0:   # rates of the last two steps, linear in time: O(Δt³)
                r1 = self.swept_old.x.array / prev
                r0 = self.swept_old2.x.array / prev2
                self._pred = dt * (r1 + (r1 - r0) * (dt + prev) / (prev + prev2))
        # (DOLFINx types Constant.value's setter NDArray; it takes a float)
        self.dt_prev2.value = prev  # type: ignore[assignment]
        self._omega = dt / prev if prev > 0 else None
        self._rate0 = None if prev > 0 else np.asarray(rate(), dtype=float)
        self.c0.value, self.c1.value = wf.bdf2_coefficients(self._omega or 0.0)
        self.dt_prev.value = float(dt)  # type: ignore[assignment]  # (as above)

    def set_start_rate(self, rate: npt.ArrayLike) -> None:
        """Nodal rate at the start of a first step, when it is known only then (cycles)."""
        if self._rate0 is not None:
            self._rate0 = np.array(rate, dtype=float)

    def error(self, swept: npt.NDArray[np.float64], comm: MPI.Comm,
              filter: Callable[[npt.NDArray[np.float64]], npt.NDArray[np.float64]]
              | None = None) -> float | None:
        """Return the error estimate (mm) of the step just solved (all ranks), or None.

        ``swept``: the step's nodal swept volumes (owned entries); ``filter``: None,
        or a callable taking the nodal defect d below to the filtered one
        (:func:`tribofx.error_filter.filtered_defect`).  The max over
        the nodes of s_{n+1} against a predictor, with its order in
        :attr:`error_order`: from the third step Milne's device, (2/11)|s_{n+1} − s^P|
        with s^P from the rates of the last two steps extrapolated linearly in time
        (2/11: BDF2's error constant 2/9 against the predictor's 1, constant
        steps), O(Δt³); the first step (backward Euler) ½|s₁ + Δt Ẇ₀| against
        forward Euler and the second |s₂ − ω s₁| against the linear predictor, O(Δt²).
        """
        if self._omega is None and self._rate0 is None:
            return None
        n = len(swept)
        if self._omega is None:
            assert self._rate0 is not None      # the test above: set on a first step
            d, self.error_order = 0.5 * (swept + float(self.dt_prev.value) * self._rate0[:n]), 2
        elif self._pred is None:
            d, self.error_order = swept - self._omega * self.swept_old.x.array[:n], 2
        else:
            d, self.error_order = (2 / 11) * (swept - self._pred[:n]), 3
        if filter is not None:
            d = filter(d)
        return comm.allreduce(float(np.max(np.abs(d), initial=0.0)), op=MPI.MAX)

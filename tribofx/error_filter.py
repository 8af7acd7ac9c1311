"""Damping-aware (filtered) error estimate of a monolithic implicit wear step.

The BDF2 estimate d of :class:`tribofx.bdf2.SweptHistory` (Milne's device, per
node, in swept volume per unit initial area) is the local error of the step as if
it persisted.  Wear damps its own errors: a node worn too deep carries less
pressure and wears slower, within a relaxation time τ of the order of the
explicit critical step (eq. 31, ≈ 0.1 s for §5.2).  A node entering the contact
gives a large d that is gone a few τ later, while the scar's overall shape
relaxes slowly and keeps its error.  As in the estimate of stiff integrators
(Hairer & Wanner, *Solving ODEs II*, §IV.8, after Shampine: RADAU5's
(I − hγJ)⁻¹ filter), d is filtered through the step's own implicit operator.
The converged step's nodal law c₀ s + c₁ s_n + Δt Ẇ = 0 is given c₀ d on its
right side, and the linearized response of the whole coupled system
(deformation, contact, the force held by a :class:`tribofx.bordered.Border`) is
the filtered estimate e = Δs:

    (c₀ I + Δt ∂Ẇ/∂s) e = c₀ d,

∂Ẇ/∂s the sensitivity of the rate through the coupled system.  Components that
the wear damps within the step (Δt ≫ τ) are reduced by about τ/Δt; those it
does not damp keep d.  Cost: a solve with the preconditioner of the problem's
last Newton iteration (:func:`tribofx.bordered.solve_like`: with a direct solver
a back-substitution; two with a border, and its vectors), the swept volume twice
and the lumped weights.  If a solve fails the raw d is returned.  The border is
evaluated at the committed state: exact where the slip history does not enter
the residual (Eulerian slip, frictionless contact), an approximation with
Lagrangian slip.  Units: mm.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt
from dolfinx import fem

from .bordered import solve_like

if TYPE_CHECKING:
    from .bordered import Border
    from .interfaces import Wear
    from .problem import Problem

__all__ = ["filtered_defect"]


def filtered_defect(problem: Problem, wear: Wear, defect: npt.NDArray[np.float64],
                    border: Border | None = None,
                    wears: Iterable[Wear] | None = None) -> npt.NDArray[np.float64]:
    """Return the filtered estimate e (owned nodal swept volumes, mm) of the ``defect`` d.

    ``problem``: the monolithic :class:`tribofx.problem.Problem` just converged
    (unknowns at the step's solution, its KSP holding the last factorization);
    ``wear``: the :class:`tribofx.interfaces.Wear` whose shape law and w are
    unknowns of it; ``defect``: d at the owned nodes of the worn surface (its ζ
    rows' order); ``border``: the force control's border, if the force is held;
    ``wears``: every evolving interface of the step (default: ``wear``).  The
    forms see the step's Δt (:attr:`SweptHistory.dt_prev`) meanwhile.
    """
    # the step has ended (Δt = 0 in the forms): its Δt again for the border's ∂R/∂δ
    wears = [wear] if wears is None else list(wears)
    ended = [float(w.dt.value) for w in wears]
    for w in wears:
        # (DOLFINx types Constant.value's setter NDArray; it takes a float)
        w.dt.value = float(w.bdf.dt_prev.value)  # type: ignore[assignment]
    try:
        return _filtered(problem, wear, defect, border)
    finally:
        for w, dt in zip(wears, ended):
            w.dt.value = dt  # type: ignore[assignment]  # (as above)


def _filtered(problem: Problem, wear: Wear, defect: npt.NDArray[np.float64],
              border: Border | None) -> npt.NDArray[np.float64]:
    zeta, w = wear.zeta, wear.body.w
    n = problem.owned_size(zeta)
    weight = wear.lumped_weight()[:n]
    rhs = problem.snes.getFunction()[0].duplicate()  # type: ignore[index]  # stub: (Vec, ...)
    rhs.set(0.0)
    arr = rhs.getArray()
    arr[problem.block_slice(zeta)] = weight * float(wear.bdf.c0.value) * defect[:n]
    del arr
    ksp = problem.snes.getKSP()
    dx = rhs.duplicate()
    solved = solve_like(ksp, rhs, dx)
    if border is not None and solved:
        solved = border.condense(dx) is not None       # the force held
    if not solved:
        for v in (rhs, dx):
            v.destroy()
        return defect[:n]
    dw = fem.Function(w.function_space)
    nw = problem.owned_size(w)
    dw.x.array[:nw] = dx.getArray(readonly=True)[problem.block_slice(w)]
    dw.x.scatter_forward()
    for v in (rhs, dx):
        v.destroy()
    s0 = wear.swept_volume()[:n]
    kept = w.x.array.copy()
    w.x.array[:] += dw.x.array
    try:
        s1 = wear.swept_volume()[:n]
    finally:
        w.x.array[:] = kept          # bit for bit: the accepted step stays as solved
    return s1 - s0

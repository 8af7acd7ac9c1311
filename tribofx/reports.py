"""Newton outcomes: per-block stopping tolerances, reports with observed orders, divergence."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["BlockTolerance", "NewtonDivergence", "NewtonReport", "RunStop",
           "convergence_orders"]


class RunStop(RuntimeError):
    """An exception that ends a run before its end, with what the caller writes.

    ``model``: the run's model (a case's run object, a stepper) at its last
    converged state, set by the run that gives up, so that the runner writes
    that state (VTX); None until then.
    """

    model: object = None


class NewtonDivergence(RunStop):
    """Raised when the Newton iteration does not converge (the unknowns are restored).

    ``report``: the :class:`NewtonReport` of the failed solve (None when the
    failure is not one Newton solve's, e.g. a search that gives up).
    """

    def __init__(self, message: str, report: "NewtonReport | None" = None):
        super().__init__(message)
        self.report = report


@dataclass
class BlockTolerance:
    """Stopping tolerance of one block of rows, in the block's physical unit.

    Attributes:
        atol: tolerance on ``max |r / w|`` (in ``unit``).
        unit: unit of ``r / w`` (for reports), e.g. "N", "mm".
        weight: UFL linear form whose assembled vector is the lumped row measure
            ``w`` (None: 1, the rows already carry the unit).
    """

    atol: float
    unit: str = "-"
    weight: object = None


@dataclass
class NewtonReport:
    """Outcome of one Newton solve: iterations, residual 2-norms and per-block norms.

    ``blocks[k]`` are the per-block stopping measures max |r/w| at iteration k,
    ``increments[k]`` the per-block max |Δx| of the Newton correction that led to
    iterate k + 1 (in the unknowns' units); ``linear_iterations`` the Krylov
    iterations of the whole solve (1 per Newton step for a direct solve).
    """

    iterations: int = 0
    residuals: list = field(default_factory=list)
    blocks: list = field(default_factory=list)
    increments: list = field(default_factory=list)
    reason: int = 0
    linear_iterations: int = 0
    names: list = field(default_factory=list)
    linear_fallbacks: list = field(default_factory=list)

    def rates(self, floor: float = 1e-13) -> npt.NDArray[np.float64]:
        """Observed convergence orders of the residual history (see :func:`convergence_orders`)."""
        return convergence_orders(self.residuals, floor)

    def increment_orders(self, block: int | str = 0,
                         floor: float = 1e-13) -> npt.NDArray[np.float64]:
        """Observed orders of the corrections max |Δx| of one block (index or unknown name).

        With an ill-conditioned Jacobian (film rows whose conductivity h³ spans
        orders of magnitude) the residual is a poor measure of the error, its
        dominant rows change from one iterate to the next; the correction
        Δx_k ≈ x_k − x* is the error itself once Newton converges, so
        |Δx_{k+1}| ≤ C |Δx_k|² shows quadratic convergence directly.
        """
        if isinstance(block, str):
            block = self.names.index(block)
        return convergence_orders([d[block] for d in self.increments], floor)


def convergence_orders(residuals: npt.ArrayLike,
                       floor: float = 1e-13) -> npt.NDArray[np.float64]:
    """Observed orders log(r_{k+1}/r_k) / log(r_k/r_{k-1}) of a residual history.

    Residuals below ``floor`` × r₀ are at round-off and are dropped first.
    """
    r = np.asarray(residuals, dtype=float)
    r = r[r > floor * r[0]] if len(r) else r
    if len(r) < 3:
        return np.array([])
    lr = np.log(r)
    return (lr[2:] - lr[1:-1]) / (lr[1:-1] - lr[:-2])

"""Reference (Eulerian) velocity fields of a body's material along its surface, eq. (26).

A body at rest in an Eulerian frame whose material moves through its mesh
(a rolling cylinder, a sliding block) has the background velocity V(X) at
its reference points; its current surface velocity is F V.  Here
V(X) = U V̂(X) with the speed U (mm/s, the continuation parameter) kept apart
from the shape V̂ (dimensionless), which evaluates on a UFL vector (the film's
forms) and on NumPy points (n, 2) or (n, 3) (the two-body film kernel's master data).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import TYPE_CHECKING, overload

import numpy as np
import ufl

if TYPE_CHECKING:
    import numpy.typing as npt
    import ufl.core.expr

__all__ = ["Motion", "Rolling", "Sliding"]


class Motion(ABC):
    """A shape V̂ of the reference velocity: on NumPy points (n, 2) or a UFL vector.

    A motion writes :meth:`on_points` and :meth:`on_ufl`; calling it picks the one
    for its argument.
    """

    @overload
    def __call__(self, X: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...

    @overload
    def __call__(self, X: ufl.core.expr.Expr) -> ufl.core.expr.Expr: ...

    def __call__(self, X: npt.NDArray[np.float64] | ufl.core.expr.Expr
                 ) -> npt.NDArray[np.float64] | ufl.core.expr.Expr:
        """Return V̂ at X: a UFL vector, or (n, 2) for NumPy points (n, 2)."""
        return self.on_points(X) if isinstance(X, np.ndarray) else self.on_ufl(X)

    @abstractmethod
    def on_points(self, X: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Return V̂ at the points X (n, 2)."""

    @abstractmethod
    def on_ufl(self, X: ufl.core.expr.Expr) -> ufl.core.expr.Expr:
        """Return V̂ at the UFL position X."""


class Rolling(Motion):
    """Rigid rotation about ``center`` with surface speed U at ``radius``: V̂ = e_z × (X − C)/R.

    Counter-clockwise for U > 0: the lowest point of a cylinder moves along +x.
    In 3D, ``axis`` (a vector, normalised) is the axis of rotation: V̂ = a × (X − C)/R
    (a ball about C = (0, 0, R) with a = −e_y: its lowest point moves along +x).
    """

    def __init__(self, center: npt.ArrayLike, radius: float,
                 axis: npt.ArrayLike | None = None) -> None:
        self.radius = float(radius)
        self.axis = None if axis is None else np.asarray(axis, float) / np.linalg.norm(axis)
        self.center = np.asarray(center, float)[:2 if axis is None else 3]

    def on_points(self, X: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Return V̂ at the points X (n, 2; n, 3 with an axis)."""
        c, R = self.center, self.radius
        if self.axis is not None:
            return np.cross(self.axis, X - c) / R
        return np.c_[-(X[:, 1] - c[1]), X[:, 0] - c[0]] / R

    def on_ufl(self, X: ufl.core.expr.Expr) -> ufl.core.expr.Expr:
        """Return V̂ at the UFL position X."""
        c, R = self.center, self.radius
        if self.axis is not None:
            a = ufl.as_vector([float(x) for x in self.axis])
            return ufl.cross(a, X - ufl.as_vector([float(x) for x in c])) / R
        return ufl.as_vector([-(X[1] - c[1]) / R, (X[0] - c[0]) / R])


class Sliding(Motion):
    """Uniform translation along ``direction`` (a unit vector): V̂ = direction."""

    def __init__(self, direction: npt.ArrayLike) -> None:
        d = np.asarray(direction, float)
        self.direction = d / np.linalg.norm(d)

    def on_points(self, X: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Return V̂ at the points X (n, 2)."""
        return np.tile(self.direction[:X.shape[1]], (len(X), 1))

    def on_ufl(self, X: ufl.core.expr.Expr) -> ufl.core.expr.Expr:
        """Return V̂ at the UFL position X."""
        return ufl.as_vector([float(c) for c in self.direction[:len(X)]])

"""The slow-time scheme of an evolving interface: one value for wear and transient films.

A :class:`Scheme` is what :class:`tribofx.interfaces.Wear`,
:class:`tribofx.interfaces.SteadyWear` and a transient film
(:meth:`tribofx.interfaces.Film.transient`) integrate their slow time with,
and what :class:`tribofx.stepper.Stepper` and the error control of
:mod:`tribofx.step_control` read:

* the θ-scheme of eq. (28): θ = 1 (:data:`IMPLICIT`, backward Euler: the rate
  at the unknown state; ``"euler"`` names it for films), θ = 0
  (:data:`EXPLICIT`: the rate at the known state), or θ ∈ (0, 1) for an
  averaged rate of fast-time cycles (``Scheme(theta=0.5)``);
* the variable-step BDF2 (:data:`BDF2`, implicit, started by one backward
  Euler step; :mod:`tribofx.bdf2`), which carries an error estimate for the
  error control.

Everywhere a scheme is asked for, its name is accepted too (:meth:`Scheme.of`):
``"explicit"``, ``"implicit"``, ``"euler"`` or ``"bdf2"``.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["BDF2", "EXPLICIT", "IMPLICIT", "SCHEME_NAMES", "Scheme"]


@dataclass(frozen=True)
class Scheme:
    """A slow-time scheme: θ of the θ-scheme (28), or BDF2 (θ = 1).

    Attributes:
        theta: weight of the rate at the new state (1 implicit, 0 explicit).
        bdf2: the variable-step BDF2 formula instead of the θ-scheme (θ = 1).
    """

    theta: float = 1.0
    bdf2: bool = False

    def __post_init__(self) -> None:
        if not 0.0 <= self.theta <= 1.0:
            raise ValueError(f"theta = {self.theta}: a weight in [0, 1]")
        if self.bdf2 and self.theta != 1.0:
            raise ValueError("BDF2 is implicit: theta = 1")

    @property
    def implicit(self) -> bool:
        """Whether the rate is taken at the unknown state alone (θ = 1 or BDF2)."""
        return self.theta == 1.0

    @property
    def name(self) -> str:
        """``"bdf2"``, ``"implicit"``, ``"explicit"`` or ``"theta=<θ>"``."""
        if self.bdf2:
            return "bdf2"
        if self.theta in (0.0, 1.0):
            return "implicit" if self.theta == 1.0 else "explicit"
        return f"theta={self.theta:g}"

    @staticmethod
    def of(value: "Scheme | str") -> "Scheme":
        """Return ``value`` as a Scheme (a Scheme, or one of :data:`SCHEME_NAMES`)."""
        if isinstance(value, Scheme):
            return value
        try:
            return _BY_NAME[value]
        except (KeyError, TypeError):
            raise ValueError(f"unknown scheme {value!r}: a Scheme or one of "
                             f"{', '.join(SCHEME_NAMES)}") from None


#: θ = 0: the rate of the known state
EXPLICIT = Scheme(0.0)
#: θ = 1, backward Euler: the rate of the unknown state
IMPLICIT = Scheme(1.0)
#: the variable-step BDF2 (implicit), with an error estimate
BDF2 = Scheme(1.0, bdf2=True)

_BY_NAME = {"explicit": EXPLICIT, "implicit": IMPLICIT, "euler": IMPLICIT, "bdf2": BDF2}
#: the names :meth:`Scheme.of` accepts
SCHEME_NAMES = tuple(_BY_NAME)

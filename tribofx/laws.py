"""Laws of a component as UFL functions with their parameters in the component's state.

A :class:`Law` is a pure UFL function of :mod:`tribofx.forms` (e.g.
:func:`tribofx.forms.fluid.barus_viscosity`) and the values of its parameters.
A component *binds* it to its mesh: every parameter becomes a ``fem.Constant``
(part of the component's ``state_fields()``, so ``restore()`` resets it and a
continuation may drive it), and the bound law is called on the component's UFL
fields wherever the law appears.  A researcher's own law is any function
``f(p, **parameters)`` returning UFL::

    from tribofx.laws import Law
    mu = Law(lambda p, mu0, a, b: mu0 * (1 + a * p + b * p**2), mu0=1e-9, a=0.01, b=1e-4)
    film = RigidFilm(mesh, gap, vbar, Fluid(mu))

A number is the constant law (the chapter's isoviscous fluid).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from dolfinx import fem

from .forms import contact as contact_forms
from .forms import fluid, wear

if TYPE_CHECKING:
    from collections.abc import Callable

    import ufl.core.expr
    from dolfinx import mesh as dmesh

__all__ = [
    "DENSITY_LAWS",
    "VISCOSITY_LAWS",
    "BoundLaw",
    "Law",
    "density_law",
    "friction_law",
    "is_constant",
    "named_density",
    "named_viscosity",
    "viscosity_law",
    "wear_coefficient_law",
]

#: the density laws a case selects by name (``density=``)
DENSITY_LAWS = ("incompressible", "dowson-higginson")

#: the viscosity laws a case selects by name (``viscosity=``)
VISCOSITY_LAWS = ("constant", "barus", "roelands")


class Law:
    """A UFL function ``function(x, **parameters)`` and its parameter values (floats).

    ``reference``: the name of the parameter that is the law's reference value
    (the viscosity μ₀ that scales the film's tolerances), default the first.
    """

    def __init__(self, function: Callable[..., ufl.core.expr.Expr], reference: str | None = None,
                 **parameters: float) -> None:
        if not parameters:
            raise ValueError("a law needs at least its reference parameter")
        self.function = function
        self.parameters = {k: float(v) for k, v in parameters.items()}
        self.reference = reference or next(iter(parameters))

    @property
    def reference_value(self) -> float:
        """Value of the reference parameter (e.g. μ₀, MPa·s)."""
        return self.parameters[self.reference]

    def bind(self, mesh: dmesh.Mesh) -> BoundLaw:
        """Return the law with its parameters as Constants on ``mesh``."""
        return BoundLaw(self, mesh)


class BoundLaw:
    """A :class:`Law` bound to a mesh: ``law(x)`` is UFL, ``constants`` its parameters."""

    def __init__(self, law: Law, mesh: dmesh.Mesh) -> None:
        self.law = law
        self.constants = {k: fem.Constant(mesh, v) for k, v in law.parameters.items()}

    def __call__(self, x: ufl.core.expr.Expr) -> ufl.core.expr.Expr:
        """Return the law at the UFL field ``x`` with the bound parameters."""
        return self.law.function(x, **self.constants)

    def state_fields(self) -> list[fem.Constant]:
        """Return the parameter Constants (for a component's ``state_fields()``)."""
        return list(self.constants.values())


def viscosity_law(mu: float | Law) -> Law:
    """Return a viscosity :class:`Law` from a number (isoviscous) or a Law (as is)."""
    if isinstance(mu, Law):
        return mu
    return Law(fluid.constant_viscosity, mu0=float(mu))


def named_viscosity(name: str, mu0: float, alpha: float = 0.0, z: float | None = None) -> Law:
    """Return the viscosity :class:`Law` ``name`` of :data:`VISCOSITY_LAWS`.

    ``alpha`` (1/MPa): Barus' coefficient, and for Roelands the slope its index
    matches when ``z`` is None (:func:`tribofx.forms.fluid.roelands_index`).
    """
    if name == "constant":
        return Law(fluid.constant_viscosity, mu0=mu0)
    if name == "barus":
        return Law(fluid.barus_viscosity, mu0=mu0, alpha=alpha)
    if name == "roelands":
        z = fluid.roelands_index(mu0, alpha) if z is None else z
        return Law(fluid.roelands_viscosity, mu0=mu0, z=z)
    raise ValueError(f"unknown viscosity law {name!r}; expected one of {VISCOSITY_LAWS}")


def density_law(rho: float | Law | None) -> Law:
    """Return a density :class:`Law` (ρ/ρ₀): None or a number is constant, a Law as is."""
    if isinstance(rho, Law):
        return rho
    return Law(fluid.constant_density, rho=1.0 if rho is None else float(rho))


def named_density(name: str) -> Law:
    """Return the density :class:`Law` ``name`` of :data:`DENSITY_LAWS`."""
    if name == "incompressible":
        return density_law(None)
    if name == "dowson-higginson":
        return Law(fluid.dowson_higginson_density, a=fluid.DOWSON_HIGGINSON_A, b=1.34)
    raise ValueError(f"unknown density law {name!r}; expected one of {DENSITY_LAWS}")


def is_constant(law: Law) -> bool:
    """Whether ``law`` is one of the constant laws (the chapter's fluid)."""
    return law.function in (fluid.constant_viscosity, fluid.constant_density,
                            contact_forms.constant_friction, wear.constant_coefficient)


def friction_law(mu: float | Law) -> Law:
    """Return a friction :class:`Law` μ(p) from a number (Coulomb) or a Law (as is)."""
    if isinstance(mu, Law):
        return mu
    return Law(contact_forms.constant_friction, mu=float(mu))


def wear_coefficient_law(k: float | Law) -> Law:
    """Return a wear-coefficient :class:`Law` k(p) from a number (Archard's constant k)."""
    if isinstance(k, Law):
        return k
    return Law(wear.constant_coefficient, k=float(k))

"""The typed protocols of the core: what a component and a counterpart answer.

:class:`Component` is what :class:`tribofx.problem.Problem` asks of a body or an
interface (the module docstring of :mod:`tribofx.problem` explains each method);
:class:`Counterpart` is what a contact or a film asks of its rigid countersurface
(:mod:`tribofx.obstacles`).  They are ``typing.Protocol`` classes
(``isinstance`` checks them at run time).  A component derives
:class:`ComponentBase`, which gives the optional hooks their defaults:
``reductions()`` and ``algebraic_rows()`` (:class:`tribofx.reduced.ReducedProblem`),
``add_residual`` / ``add_jacobian`` / ``couplings`` (terms assembled outside UFL,
as the two-body contact), ``reset_iterate`` / ``accept_iterate`` (a Newton-iterate
history) and ``admissible()`` (the "admissible" line search).  ``docs/architecture.md``,
"Write your own component", walks through one.

:class:`WearDriver` is what a :class:`tribofx.interfaces.Wear` asks of the
interface (or interfaces) whose load wears the surface: ``Contact``, ``Film``,
a side of a ``TwoBodyContact`` (cycle-averaged wear only) or the user's own.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol, runtime_checkable

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt
    import ufl.core.expr
    from petsc4py import PETSc

    from .forms.contact import ContactGeometry
    from .forms.wear import WearLoad
    from .problem import Problem

__all__ = ["Component", "ComponentBase", "Counterpart", "WearDriver"]


@runtime_checkable
class Component(Protocol):
    """A body or an interface of a :class:`tribofx.problem.Problem`."""

    def unknowns(self) -> list:
        """Its ``fem.Function`` unknowns, in order."""

    def contributions(self) -> list:
        """``(unknown, form)`` pairs: residual terms (from :mod:`tribofx.forms`) by row."""

    def bcs(self) -> list:
        """Dirichlet conditions on any unknown."""

    def bcs_by_unknown(self) -> dict:
        """Return the same conditions as ``{unknown: [DirichletBC]}``."""

    def entity_maps(self) -> list:
        """Entity maps of its mixed-dimensional forms."""

    def refresh(self) -> None:
        """Compute data outside UFL, before every residual and Jacobian evaluation."""

    def tolerances(self) -> dict:
        """``{unknown: BlockTolerance}``: the stopping test of its rows."""

    def state_fields(self) -> list:
        """Functions and Constants of its state (restore() resets them)."""

    def commit(self) -> None:
        """Accept a converged step."""


class ComponentBase:
    """The optional hooks of a component, with their defaults; every component derives it.

    A :class:`tribofx.problem.Problem` calls each hook on every component, so a
    component overrides only what it does:

    * ``assembles`` (class attribute, default False): it adds terms outside UFL,
      ``add_residual(b, problem)`` / ``add_jacobian(A, problem)`` into the
      assembled block vector and matrix (the two-body kernels), and
      ``couplings(problem)``, the (rows, cols) of the entries it may add in the
      next solve (None: none beyond UFL's pattern);
    * ``iterates`` (class attribute, default False): it keeps a Newton-iterate
      history, ``reset_iterate()`` at the start of a solve or a restore and
      ``accept_iterate()`` → whether the accepted iterate moved it (the residual is
      then evaluated again);
    * ``admissible()``: the "admissible" line search's test of a trial (True);
    * ``reductions()`` / ``algebraic_rows()``: the maps of a
      :class:`tribofx.reduced.ReducedProblem` (none).

    It also answers the protocol's ``bcs()``, ``bcs_by_unknown()``,
    ``entity_maps()``, ``refresh()`` and ``commit()`` with "none", so that a
    component writes only ``unknowns()``, ``contributions()``, ``tolerances()`` and
    ``state_fields()`` and what it actually has.
    """

    assembles = False
    iterates = False

    # the protocol's methods whose usual answer is "none": a component overrides them
    # where it has conditions, mixed-dimensional forms, data outside UFL or a history
    def bcs(self) -> list:
        """Dirichlet conditions on any unknown (none)."""
        return []

    def bcs_by_unknown(self) -> dict:
        """Return the same conditions as ``{unknown: [DirichletBC]}`` (none)."""
        return {}

    def entity_maps(self) -> list:
        """Entity maps of its mixed-dimensional forms (none)."""
        return []

    def refresh(self) -> None:
        """Compute data outside UFL before every evaluation (nothing)."""

    def commit(self) -> None:
        """Accept a converged step (nothing to move on)."""

    def add_residual(self, b: PETSc.Vec, problem: Problem) -> None:
        """Add terms assembled outside UFL to the block residual ``b`` (none)."""

    def add_jacobian(self, A: PETSc.Mat, problem: Problem) -> None:
        """Add terms assembled outside UFL to the block Jacobian ``A`` (none)."""

    def couplings(self, problem: Problem
                  ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]] | None:
        """Return (rows, cols) of the entries it may add in the next solve, or None."""
        return None

    def reset_iterate(self) -> None:
        """Start a Newton solve (or a restore) from the committed iterate history."""

    def accept_iterate(self) -> bool:
        """Move the iterate history to the accepted iterate; whether it changed."""
        return False

    def admissible(self) -> bool:
        """Whether the current state is admissible (the "admissible" line search)."""
        return True

    def reductions(self) -> list:
        """Reductions of a :class:`tribofx.reduced.ReducedProblem` (none)."""
        return []

    def algebraic_rows(self) -> list:
        """Algebraic rows of a :class:`tribofx.reduced.ReducedProblem` (none)."""
        return []


@runtime_checkable
class Counterpart(Protocol):
    """A rigid countersurface of a contact or a film (built by a factory of ``V_sub``)."""

    def geometry(self, x: ufl.core.expr.Expr) -> ContactGeometry:
        """Closest-point geometry (gap, normal, projection) at the UFL position ``x``."""

    def update(self, x_nodes: npt.NDArray[np.float64]) -> None:
        """Refresh kernel data at the slave nodes ``x_nodes`` (n, gdim)."""

    def unknowns(self) -> list:
        """Its unknowns (none for a prescribed motion)."""

    def state_fields(self) -> list:
        """Its state (position, motion history)."""

    def motion_since_commit(self) -> ufl.core.expr.Expr:
        """Its rigid motion since the last commit (UFL vector; the Lagrangian slip's)."""

    def commit(self) -> None:
        """Accept a converged step."""


@runtime_checkable
class WearDriver(Protocol):
    """An interface that supplies the load of Archard wear on a body's boundary.

    ``Wear(driver, k, ...)`` or ``Wear([driver, ...], k, ...)`` (a sum of loads on
    the same boundary, the rates added).  Attributes: ``body`` (the worn
    :class:`tribofx.body.Body`) and ``surface`` (its boundary as a
    :class:`tribofx.interfaces.surface.Surface`: the wear multiplier's space,
    the vertex-rule measure and the nodal maps).
    """

    def wear_load(self, slip: ufl.core.expr.Expr | None = None) -> WearLoad:
        """UFL :class:`tribofx.forms.wear.WearLoad` (per unit initial area) of the state.

        ``slip``: a slip increment instead of the slip velocity (the wear increment
        of a fast-time sub-step); an interface without one raises ValueError.
        """

    def entity_maps(self) -> list:
        """Entity maps of the forms its load is written in."""

"""A dry start for a film: a lubricated boundary under a prescribed pressure."""

from __future__ import annotations

from typing import TYPE_CHECKING

import ufl
from dolfinx import fem

from ..forms import ehl as ef
from ..forms import film_traction as ft
from ..forms import hyperelastic as hf
from ..protocols import ComponentBase

if TYPE_CHECKING:
    from dolfinx import mesh as dmesh

    from ..body import Body
    from ..problem import BlockTolerance
    from .film import Film

__all__ = ["BoundaryPressure", "PrescribedPressure"]


class PrescribedPressure(ComponentBase):
    """The lubricated boundary of a :class:`Film` under a prescribed pressure (no film).

    Component of a dry problem ``Problem([body, PrescribedPressure(film)])``: the
    pressure ``p`` (P1 on Γ_l, MPa) loads the body through the pressure part of
    the fluid traction (46) (a follower load for ``model="finite"``), and the
    film's trace u_s follows u (trace rows), so the film starts from the
    deformed state.
    """

    def __init__(self, film: Film) -> None:
        self.film = film
        self.p = fem.Function(film.Q, name=f"{film.name}_prescribed_pressure")
        f, body = film, film.body
        gdim = body.gdim
        F = ufl.Identity(gdim) + ufl.grad(body.u)
        self.traction = ft.fluid_traction(self.p, ufl.zero(gdim), f.kin_bulk, F,
                                          ufl.FacetNormal(body.mesh), f.T_b, f.mu_p,
                                          shear=False, model=f.model)

    def unknowns(self) -> list[fem.Function]:
        """Return the film's trace u_s."""
        return [self.film.u_s]

    def contributions(self) -> list[tuple[fem.Function, ufl.Form]]:
        """Prescribed-pressure work on u, trace rows on u_s."""
        f, body = self.film, self.film.body
        return [(body.u, ft.film_virtual_work(self.traction, body.v, f.ds, f.w_solid)),
                (f.u_s, f.trace_scale * ef.trace_constraint(f.u_s, body.u, ufl.TestFunction(f.Vs),
                                                     f.ds))]

    def bcs(self) -> list[fem.DirichletBC]:
        """Return no conditions."""
        return []

    def bcs_by_unknown(self) -> dict[fem.Function, list[fem.DirichletBC]]:
        """Return no conditions."""
        return {}

    def entity_maps(self) -> list[dmesh.EntityMap]:
        """Return the film's entity map."""
        return [self.film.emap]

    def refresh(self) -> None:
        """Nothing to refresh (the pressure part of the traction needs no countersurface)."""

    def tolerances(self) -> dict[fem.Function, BlockTolerance]:
        """Return the film's trace tolerance."""
        return {self.film.u_s: self.film.tolerances()[self.film.u_s]}

    def state_fields(self) -> list[fem.Function]:
        """Return the prescribed pressure and the trace."""
        return [self.p, self.film.u_s]

    def commit(self) -> None:
        """Nothing to accept."""


class BoundaryPressure(ComponentBase):
    """A boundary of a body under a prescribed follower pressure (no film, no unknowns).

    Component of a dry problem ``Problem([body, BoundaryPressure(body, name)])``:
    ``p`` (P1 on the body, MPa; set it, e.g. ``p.interpolate(f)``) loads the
    boundary ``name`` as T = −p J F⁻ᵀ N (Nanson; :meth:`tribofx.body.Body.add_follower_pressure`
    for a permanent one).  The master's side of a two-body dry start
    (:meth:`tribofx.interfaces.TwoBodyFilm.start_from_pressure`).
    """

    def __init__(self, body: Body, boundary: str) -> None:
        self.body = body
        self.p = fem.Function(fem.functionspace(body.mesh, ("Lagrange", 1)),
                              name=f"{body.name}_{boundary}_prescribed_pressure")
        self._work = hf.follower_pressure_work(self.p, body.u, body.v, body.kind,
                                               body.ds(body.tag(boundary)))

    def unknowns(self) -> list[fem.Function]:
        """Return none (the body's u carries the load)."""
        return []

    def contributions(self) -> list[tuple[fem.Function, ufl.Form]]:
        """Return minus the pressure's virtual work on the body's u."""
        return [(self.body.u, -self._work)]

    def tolerances(self) -> dict[fem.Function, BlockTolerance]:
        """Return none."""
        return {}

    def state_fields(self) -> list[fem.Function]:
        """Return the prescribed pressure."""
        return [self.p]

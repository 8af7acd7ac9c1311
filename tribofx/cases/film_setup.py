"""Film set-up shared by the EHL cases.

The rim ∂Γ_l of the lubricated surface, point locators for pressure conditions,
the ``speeds`` parameter of a speed continuation, the fluid's laws from the
parameters, and the 1D film of a prescribed gap (:func:`rigid_film`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple, Protocol

import numpy as np
from dolfinx import mesh as dmesh

from ..interfaces import FilmScales, Fluid, RigidFilm
from ..interfaces.film_options import named_cavitation
from ..laws import DENSITY_LAWS, VISCOSITY_LAWS, named_density, named_viscosity
from ..params import CaseParams, InputError, number_list, param
from ..problem import Problem

if TYPE_CHECKING:
    from collections.abc import Callable

    import numpy.typing as npt
    from mpi4py import MPI

    from ..interfaces.reynolds_film import ReynoldsFilm
    from ..laws import Law

    class _Viscous(Protocol):
        """Values with a viscosity law (:class:`FluidParams`) and its μ₀ ``mu`` (MPa·s)."""

        @property
        def viscosity(self) -> str: ...
        @property
        def mu(self) -> float: ...
        @property
        def alpha_p(self) -> float: ...
        @property
        def z(self) -> float: ...

    class _Speeds(Protocol):
        """Values with the comma-separated ``speeds`` (mm/s) of a speed continuation."""

        @property
        def speeds(self) -> str: ...

__all__ = ["FilmModel", "FluidParams", "at_points", "density",
           "film_boundary", "formulation_param", "quadrature_param", "rigid_film",
           "speed_list", "viscosity"]


def formulation_param(default: str) -> Any:
    """Return the ``formulation`` field of a film case: the solid's (u) or (u, p) form.

    ``mixed`` (:class:`tribofx.body.Body`, ``formulation="mixed"``) is locking-free
    for nearly incompressible solids: a locked P1 surface makes the film zig-zag.
    """
    return param(default, "-",
                 "solid: displacement (u only) or mixed (u and a P1 volumetric stress: "
                 "locking-free, no film zig-zag for nearly incompressible solids)",
                 choices=("displacement", "mixed"))

def quadrature_param(default: str = "gauss") -> Any:
    """Return the ``quadrature`` field of a film case: the rule of the film's integrals.

    Offered by ``ehl-ball`` only (verified there): with the vertex rule Newton does
    not converge on the plane-strain layer and the O-ring, which keep the Gauss rule.

    ``vertex`` evaluates h, its conductance h³ and every film term at the nodes of
    Γ_l, where the P1 surface is exact: a Gauss point inside a facet sees the
    chord, below the curved surface by up to h_e²/(8R), which in a thin film
    (h ≲ h_e²/R) is a node-to-node ripple of h (:class:`tribofx.interfaces.Film`).
    ``default="auto"`` offers ``auto`` too, a rule the case chooses (``ehl-ball``:
    :func:`tribofx.cases.ehl_ball.film_rule`).
    """
    auto = default == "auto"
    return param(default, "-",
                 "rule of the film integrals: gauss, or vertex (film terms at the nodes: no "
                 "chord sag h_e²/8R of the faceted surface in a thin film; not with a kinked "
                 "meshed countersurface; not with cavitation=jfo)"
                 + ("; auto: vertex, gauss with cavitation=jfo or on mesh=0" if auto else ""),
                 choices=("auto", "gauss", "vertex") if auto else ("gauss", "vertex"))


@dataclass(frozen=True)
class FluidParams(CaseParams):
    """The lubricant's pressure–viscosity and density laws, parameters of every case with a film."""

    viscosity: str = param(
        "constant", "-",
        "viscosity law μ(p): constant (the chapter's), barus mu exp(alpha_p p), roelands "
        "(index z)", choices=VISCOSITY_LAWS)
    alpha_p: float = param(
        0.0, "1/MPa",
        "pressure-viscosity coefficient of barus, and the slope roelands matches when z = 0 "
        "(0.02 1/MPa = 2e-8 1/Pa, a mineral oil; up to 100 for studies of a strong pressure "
        "dependence at soft-EHL pressures)", lower=0.0, upper=100.0, closed=True)
    z: float = param(0.0, "-", "Roelands' index (0: from alpha_p)", lower=0.0, upper=2.0,
                     closed=True)
    density: str = param(
        "incompressible", "-",
        "density law ρ(p): incompressible (the chapter's) or dowson-higginson (compressible "
        "Reynolds; not with jfo)", choices=DENSITY_LAWS)


def viscosity(v: _Viscous) -> Law:
    """Return the viscosity law of the values ``v`` (``mu`` is its μ₀, MPa·s)."""
    if v.viscosity != "constant" and not v.alpha_p > 0 and not v.z > 0:
        raise InputError(f"viscosity={v.viscosity} needs alpha_p > 0 (or z > 0 for "
                         f"roelands)")
    return named_viscosity(v.viscosity, v.mu, v.alpha_p, v.z or None)


def speed_list(v: _Speeds) -> list[float]:
    """Return the positive speeds (mm/s) of the comma-separated parameter ``speeds``."""
    speeds = number_list(v.speeds, "speeds", allow_empty=True)
    if any(not U > 0 for U in speeds):
        raise InputError("speeds must be positive (mm/s)")
    return speeds


def film_boundary(film: ReynoldsFilm,
                  keep: Callable[[npt.NDArray[np.float64]], npt.ArrayLike] | None = None
                  ) -> npt.NDArray[np.float64]:
    """Return the reference coordinates (n, 3) of the vertices of ∂Γ_l, on every rank.

    ∂Γ_l are the facets of the film submesh with one adjacent cell of Γ_l
    (:meth:`~tribofx.interfaces.reynolds_film.ReynoldsFilm.boundary_facets`): the
    end points of a curve, the rim edges of a surface.  ``keep(X)``, X the
    (k, vertices per facet, 3) coordinates of the local boundary facets, returns a
    mask of the facets to keep (e.g. not the edges on a symmetry line).  A vertex
    of two facets or on two ranks is listed once (its coordinates are identical).
    """
    sub = film.sub
    facets = film.boundary_facets()
    fdim = sub.topology.dim - 1
    X = np.zeros((0, 1, 3))
    if len(facets):
        X = sub.geometry.x[dmesh.entities_to_geometry(sub, fdim, facets, False)]
        if keep is not None:
            X = X[np.asarray(keep(X), dtype=bool)]
    pts = np.concatenate([x.reshape(-1, 3) for x in sub.comm.allgather(X)])
    return np.unique(pts, axis=0)


def at_points(points: npt.NDArray[np.float64], tol: float
              ) -> Callable[[npt.NDArray[np.float64]], npt.NDArray[np.bool_]]:
    """Locator (for ``add_pressure_bc``, ``fem.locate_dofs_geometrical``) of ``points``.

    Returns ``where(X)``, X of shape (3, n): True at the columns within ``tol``
    (mm) of one of the (k, 3) ``points``.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)

    def where(X: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
        if not len(points):
            return np.zeros(X.shape[1], dtype=bool)
        d = np.linalg.norm(X.T[:, None, :] - points[None, :, :], axis=2)
        return d.min(axis=1) < tol

    return where


def density(v: FluidParams, cavitation: str | None = None) -> Law:
    """Return the density law ρ(p)/ρ₀ of the values ``v`` (refused with ``cavitation`` jfo)."""
    if v.density != "incompressible" and cavitation == "jfo":
        raise InputError("density=dowson-higginson is implemented with penalty or no "
                         "cavitation, not jfo")
    return named_density(v.density)


class FilmModel(NamedTuple):
    """A film and its :class:`Problem` (:func:`rigid_film`)."""

    film: RigidFilm
    problem: Problem


def rigid_film(comm: MPI.Comm, x0: float, x1: float, n: int, degree: int,
               gap: Callable[[Any], Any], vbar: float, mu: float | Law,
               cavitation: str = "none", supg: bool = False, p_c: float = 1.0,
               eps: float | None = None, h_ref: float = 1e-2, lam_in: float = 0.0,
               density: Law | None = None, supply: bool = False) -> FilmModel:
    """Return the film of a 1D gap on [x0, x1] (flow entering at x0) and its :class:`Problem`.

    Penalty or no cavitation: p = 0 at both ends.  JFO: inlet at x0 with void
    fraction λ_in (flooded, λ_in = 0: also p = 0), natural outlet (no
    Poiseuille flux, p = 0 there by complementarity).  ``h_ref`` (mm) is the
    film scale of the tolerances and, times v̄, the flux scale of the JFO
    complementarity rows.  ``supply`` (JFO): the inlet is an open end supplied with
    the content (1 − λ_in) h(x0) (:meth:`~tribofx.interfaces.reynolds_film.ReynoldsFilm.add_inflow`)
    instead of the Dirichlet conditions on λ and p.  Returns a :class:`FilmModel`.
    """
    msh = dmesh.create_interval(comm, n, [x0, x1])
    film = RigidFilm(msh, gap, vbar, Fluid(mu, density), degree=degree,
                     cavitation=named_cavitation(cavitation, eps), supg=supg,
                     scales=FilmScales(pressure=p_c, film=h_ref, speed=vbar))
    if cavitation == "jfo":
        at_inlet = lambda y: np.isclose(y[0], x0)   # noqa: E731
        if supply:
            film.add_inflow(at_inlet, (1 - lam_in) * gap(np.array(x0)))
        else:
            film.add_inlet(at_inlet, void=lam_in)
        film.jfo_initial_guess()
    else:
        film.add_pressure_bc()
    return FilmModel(film, Problem([film], name="reynolds", max_it=50, max_backtracks=8))

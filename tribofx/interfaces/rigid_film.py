"""A film between rigid surfaces: the Reynolds equation in the plane (chapter §6.6)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal, cast, overload

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..forms import ehl as ef
from ..laws import viscosity_law
from .film_options import JFO, Cavitation, FilmScales, Fluid, Penalty
from .reynolds_film import ReynoldsFilm, global_extent

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping

    import numpy.typing as npt
    import ufl.core.expr
    from dolfinx import mesh as dmesh

    from ..problem import BlockTolerance
    from .reynolds_film import Profile

__all__ = ["RigidFilm"]


class RigidFilm(ReynoldsFilm):
    """A film between rigid surfaces: the Reynolds equation in the plane (§6.6), 1D or 2D.

    The variant of :class:`Film` without a body: the lubrication surface is the
    reference mesh itself (:func:`tribofx.forms.ehl.planar_kinematics`, A = I),
    the film thickness h(x) and the mean velocity v̄ are given, and the rows are
    the same Reynolds forms (49)/(57) with SUPG, penalty or JFO cavitation, the
    same pressure and inlet conditions (:meth:`add_pressure_bc`,
    :meth:`add_inlet`), tolerances and JFO tools (:meth:`jfo_initial_guess`,
    :meth:`consistent_fluxes`).  All its rows are volume fluxes (mm²/s in 1D), so
    it needs no row scales.

    Args:
        mesh: the mesh of the film (e.g. ``dolfinx.mesh.create_interval``), mm.
        gap: callable x (UFL spatial coordinate) → h (UFL, mm).
        vbar: mean velocity v̄ (mm/s): a number (1D) or a vector.
        fluid: the lubricant, a :class:`~tribofx.interfaces.film_options.Fluid`: its
            viscosity μ(p) and density ρ(p)/ρ₀ (a variable density: the
            compressible Reynolds equation; penalty or no cavitation).
        degree: Lagrange degree of p (JFO and the nodal penalty: 1).
        cavitation: None, :class:`~tribofx.interfaces.film_options.Penalty` or
            :class:`~tribofx.interfaces.film_options.JFO`, as for :class:`Film`.
        supg: as for :class:`Film`.
        scales: as for :class:`Film`; film × speed is the flux scale of the JFO
            complementarity rows; None derives them from the gap
            (:meth:`FilmScales.hydrodynamic`).
        quadrature_degree: Gauss degree of the integrals, default 4·degree + 6
            (h is not polynomial in general).
        rtol: relative size of the stopping tolerances.
    """

    def __init__(self, mesh: dmesh.Mesh,
                 gap: Callable[[ufl.core.expr.Expr], ufl.core.expr.Expr],
                 vbar: npt.ArrayLike, fluid: Fluid, degree: int = 1,
                 cavitation: Cavitation | None = None, supg: bool = False,
                 scales: FilmScales | None = None, quadrature_degree: int | None = None,
                 name: str = "film", rtol: float = 1e-10) -> None:
        if not isinstance(fluid, Fluid):
            raise TypeError(f"fluid: a Fluid(viscosity, density), not {fluid!r}")
        if cavitation is not None and not isinstance(cavitation, (Penalty, JFO)):
            raise TypeError(f"cavitation: None, Penalty(eps) or JFO(), not {cavitation!r}")
        if isinstance(cavitation, JFO) and degree != 1:
            raise ValueError("JFO cavitation needs P1 pressure (nodal complementarity)")
        mu, density = fluid.viscosity, fluid.density
        eps = cavitation.eps if isinstance(cavitation, Penalty) else None
        cavitation_name = "none" if cavitation is None else cavitation.name
        self.sub, self.name, self.rtol = mesh, name, float(rtol)
        self.cavitation = cavitation_name
        gdim = mesh.geometry.dim
        self.Q = fem.functionspace(mesh, ("Lagrange", degree))
        self.p = fem.Function(self.Q, name="pressure")
        self.lam = None
        if cavitation_name == "jfo":
            # λ on its own (identical) space so that Dirichlet conditions find their block
            self.Ql = fem.functionspace(mesh, ("Lagrange", 1))
            self.lam = fem.Function(self.Ql, name="void_fraction")
        x = ufl.SpatialCoordinate(mesh)
        self.h = gap(x[0]) if gdim == 1 else gap(x)
        self.vbar_c = fem.Constant(mesh, np.atleast_1d(np.asarray(vbar, dtype=float)))
        self.kin = ef.planar_kinematics(x, self.h, self.vbar_c)
        self.grad_gamma, self._supg, self._jumps = ufl.grad, supg, False
        self.T = ufl.as_vector([1.0] + [0.0] * (gdim - 1))
        law = viscosity_law(mu)
        self.mu = law.reference_value
        self.viscosity = law.bind(mesh)
        self.mu_p = self.viscosity(self.p)      # μ(p): the one viscosity of every form
        self._bind_density(density, mesh)
        lo, hi = global_extent(mesh.geometry.x[:, :gdim], mesh.comm)
        self.length = float(np.linalg.norm(hi - lo))
        self.h_fun = fem.Function(self.Q, name="film_thickness")
        self.h_fun.interpolate(fem.Expression(self.h, self.Q.element.interpolation_points,
                                              comm=mesh.comm))
        if scales is None:
            scales = self._derived_scales()
        self.p_c = fem.Constant(mesh, float(scales.pressure))
        self.eps = None
        if eps is not None:
            self.eps = fem.Constant(mesh, float(eps))
        qd = 4 * degree + 6 if quadrature_degree is None else quadrature_degree
        self.dx = ufl.Measure("dx", mesh, metadata={"quadrature_degree": qd})
        self.nodal_dx = (ufl.Measure("dx", mesh, metadata={"quadrature_rule": "vertex",
                                                           "quadrature_degree": 1})
                         if degree == 1 else self.dx)
        self.h_ref, self.U_ref = float(scales.film), float(scales.speed)
        self._c_p = 1
        self._q_ref = fem.Constant(mesh, self.h_ref * self.U_ref)
        self.w_film = 1
        self._init_rows()

    def _derived_scales(self) -> FilmScales:
        """Return the scales of a film given none: :meth:`FilmScales.hydrodynamic` of its gap.

        h: the least positive gap at the nodes; ℓ: the half extent of the nodes where
        the gap is below 2h (√(2Rh) for a cylinder); U: |v̄|.
        """
        comm, gdim = self.sub.comm, self.sub.geometry.dim
        h = self.h_fun.x.array[: self.Q.dofmap.index_map.size_local]
        x = self.Q.tabulate_dof_coordinates()[: len(h), :gdim]
        h_min = comm.allreduce(float(np.min(h[h > 0], initial=np.inf)), op=MPI.MIN)
        if not np.isfinite(h_min):
            raise ValueError("RigidFilm: the gap is nowhere positive: give scales=FilmScales(...)")
        lo, hi = global_extent(x[h <= 2 * h_min], comm)
        ell = max(0.5 * float(np.max(hi - lo)), 1e-12 * self.length)
        U = float(np.linalg.norm(self.vbar_c.value))
        return FilmScales.hydrodynamic(self.mu, U, h_min, ell)

    # -- component protocol --------------------------------------------------------------
    def unknowns(self) -> list[fem.Function]:
        """Return p (and λ)."""
        return [self.p] + ([self.lam] if self.lam is not None else [])

    def contributions(self) -> list[tuple[fem.Function, ufl.Form]]:
        """Reynolds (or JFO transport) rows on p, complementarity rows on λ."""
        R_p, C = self._reynolds(ufl.TestFunction(self.Q))
        # C is the JFO complementarity: λ exists
        return [(self.p, R_p)] + ([(cast("fem.Function", self.lam), C)] if C is not None else [])

    def entity_maps(self) -> list[dmesh.EntityMap]:
        """Return no entity maps: the film lives on its own mesh."""
        return []

    def refresh(self) -> None:
        """Nothing computed outside UFL."""

    def tolerances(self) -> dict[fem.Function, BlockTolerance]:
        """Reynolds rows (mm/s) and complementarity rows (-) over lumped measures."""
        if not self._tol:
            self._tol_out = self._pressure_tolerances()
            self.set_scales()
        return self._tol_out

    def state_fields(self) -> list[fem.Function | fem.Constant]:
        """Return p (and λ) and the viscosity law's parameters."""
        return self.unknowns() + self.viscosity.state_fields() + self.density.state_fields()

    def commit(self) -> None:
        """Nothing to accept."""

    # -- outputs -------------------------------------------------------------------------
    def integral(self, expr: ufl.core.expr.Expr, dx: ufl.Measure | None = None) -> float:
        """Global integral of the UFL expression ``expr`` over the film (default ``dx``)."""
        return self._sum(fem.form(expr * (dx or self.dx)))

    @overload
    def profile(self, everywhere: Literal[True]) -> Profile: ...

    @overload
    def profile(self, everywhere: bool = False) -> Profile | None: ...

    def profile(self, everywhere: bool = False) -> Profile | None:
        """Nodal x, p, h (and λ) sorted by x on rank 0 (None elsewhere) or ``everywhere``."""
        n = self.Q.dofmap.index_map.size_local
        d = {"x": self.Q.tabulate_dof_coordinates()[:n, 0], "p": self.p.x.array[:n],
             "h": self.h_fun.x.array[:n]}
        if self.lam is not None:
            d["lam"] = self.lam.x.array[:n]
        return self._gather(d, "x", everywhere)

    def set_from_profile(self, prof: Mapping[str, npt.NDArray[np.float64]]) -> None:
        """Set p (and λ) by interpolation of a (coarser) nodal profile (dict, all ranks)."""
        for fun, key in ((self.p, "p"), (self.lam, "lam")):
            if fun is not None:
                xs = fun.function_space.tabulate_dof_coordinates()[:, 0]
                fun.x.array[:] = np.interp(xs, prof["x"], prof[key])

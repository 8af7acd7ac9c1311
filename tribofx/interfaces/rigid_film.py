"""A film between rigid surfaces: the Reynolds equation in the plane (chapter §6.6)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal, cast, overload

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..forms import ehl as ef
from ..laws import viscosity_law
from .reynolds_film import ReynoldsFilm

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping

    import numpy.typing as npt
    import ufl.core.expr
    from dolfinx import mesh as dmesh

    from ..laws import Law
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
        mu: viscosity (MPa·s), or a viscosity :class:`tribofx.laws.Law` μ(p)
            (:mod:`tribofx.forms.fluid`).
        density: None (incompressible) or a density :class:`tribofx.laws.Law`
            ρ(p)/ρ₀ (the compressible Reynolds equation; penalty or no cavitation).
        degree: Lagrange degree of p (JFO and the nodal penalty: 1).
        cavitation: "none", "penalty" or "jfo".
        supg, eps, p_c: as for :class:`Film`.
        film_scale, speed_scale: h_ref (mm), U (mm/s) of the tolerances; their
            product is the flux scale of the JFO complementarity rows.
        quadrature_degree: default 4·degree + 6 (h is not polynomial in general).
        rtol: relative size of the stopping tolerances.
    """

    CAVITATION = ("none", "penalty", "jfo")

    def __init__(self, mesh: dmesh.Mesh,
                 gap: Callable[[ufl.core.expr.Expr], ufl.core.expr.Expr],
                 vbar: npt.ArrayLike, mu: float | Law, degree: int = 1, cavitation: str = "none",
                 supg: bool = False, eps: float | None = None, p_c: float = 1.0,
                 film_scale: float = 1e-2, speed_scale: float = 1.0,
                 quadrature_degree: int | None = None, name: str = "film", rtol: float = 1e-10,
                 density: float | Law | None = None) -> None:
        if cavitation not in self.CAVITATION:
            raise ValueError(f"unknown cavitation model {cavitation!r}")
        if cavitation == "jfo" and degree != 1:
            raise ValueError("cavitation='jfo' needs P1 pressure (nodal complementarity)")
        if cavitation == "penalty" and eps is None:
            raise ValueError("cavitation='penalty' needs the penalty parameter eps (MPa·s/mm)")
        self.sub, self.name, self.rtol, self.cavitation = mesh, name, float(rtol), cavitation
        gdim = mesh.geometry.dim
        self.Q = fem.functionspace(mesh, ("Lagrange", degree))
        self.p = fem.Function(self.Q, name="pressure")
        self.lam = None
        if cavitation == "jfo":
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
        self.p_c = fem.Constant(mesh, float(p_c))
        self.eps = None
        if eps is not None and cavitation == "penalty":
            self.eps = fem.Constant(mesh, float(eps))
        qd = 4 * degree + 6 if quadrature_degree is None else quadrature_degree
        self.dx = ufl.Measure("dx", mesh, metadata={"quadrature_degree": qd})
        self.nodal_dx = (ufl.Measure("dx", mesh, metadata={"quadrature_rule": "vertex",
                                                           "quadrature_degree": 1})
                         if degree == 1 else self.dx)
        self.h_ref, self.U_ref = float(film_scale), float(speed_scale)
        self._c_p = 1
        self._q_ref = fem.Constant(mesh, self.h_ref * self.U_ref)
        self.w_film = 1
        lo = mesh.geometry.x[:, :gdim].min(axis=0, initial=np.inf)
        hi = mesh.geometry.x[:, :gdim].max(axis=0, initial=-np.inf)
        mesh.comm.Allreduce(MPI.IN_PLACE, lo, op=MPI.MIN)
        mesh.comm.Allreduce(MPI.IN_PLACE, hi, op=MPI.MAX)
        self.length = float(np.linalg.norm(hi - lo))
        self.h_fun = fem.Function(self.Q, name="film_thickness")
        self.h_fun.interpolate(fem.Expression(self.h, self.Q.element.interpolation_points,
                                              comm=mesh.comm))
        self._init_rows()

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

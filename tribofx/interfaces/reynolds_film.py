"""Reynolds rows of a lubricating film: pressure conditions, scales, tolerances, JFO tools.

:class:`ReynoldsFilm` is the part shared by :class:`tribofx.interfaces.Film`
(the film on a deformable body's boundary) and
:class:`tribofx.interfaces.RigidFilm` (between rigid surfaces): the Reynolds
(49) or JFO (57) rows of :mod:`tribofx.forms.ehl`, the pressure and inlet
conditions on ∂Γ_l, the stopping tolerances, the JFO starting guess and the
consistent end fluxes.

Stopping test (:class:`tribofx.problem.BlockTolerance`, lumped reference
measures of Γ_l): Reynolds rows as a nodal volume flux imbalance (mm²/s per
unit length on a curve, mm³/s on a surface) ≤ rtol·U·h_ref·b, b the width of
the film (1, the diameter ℓ_l of Γ_l, or 2πr), i.e. rtol of the Couette flux
through the film; trace rows as a displacement (mm) ≤ rtol·h_ref, g rows (MPa/mm)
≤ rtol·p_c/ℓ_l, complementarity rows (dimensionless) ≤ rtol; U, h_ref and p_c are
the speed, film and pressure scales of :meth:`Film.set_scales`.  A transient
film adds to U the speed ℓ_e/Δt of its mean element ℓ_e over the step
(:meth:`tribofx.interfaces.Film.begin_step`): a content
error of rtol·h_ref at a node is a flux imbalance of that size, and the
rounding of the content's rate grows like 1/Δt as a step is cut.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np
import ufl
from dolfinx import fem, la
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..forms import ehl as ef
from ..forms import jfo, mixed
from ..laws import density_law, is_constant
from ..problem import BlockTolerance
from ..protocols import ComponentBase

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping, Sequence

    import numpy.typing as npt
    import ufl.core.expr

    from ..body import Body
    from ..forms.ehl import LubricationKinematics
    from ..laws import BoundLaw, Law
    from ..roughness import Roughness

    #: where a condition holds: reference coordinates (3, n) → bool (n,), as the
    #: marker of ``fem.locate_dofs_geometrical``
    Where: TypeAlias = Callable[[npt.NDArray[np.float64]], npt.NDArray[np.bool_]]
    #: a rough film's bound laws (φ_x, Φ_s, p_a, shear) (:meth:`tribofx.roughness.Roughness.bind`)
    RoughLaws: TypeAlias = tuple[BoundLaw | None, BoundLaw | None, BoundLaw | None,
                                 tuple[BoundLaw | None, ...] | None]
    #: nodal profile arrays by name (:meth:`ReynoldsFilm._gather`)
    Profile: TypeAlias = dict[str, npt.NDArray[Any]]

__all__ = ["ReynoldsFilm", "global_extent"]


def global_extent(points: npt.NDArray[np.float64], comm: MPI.Comm
                  ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Return the corners (lo, hi) of the bounding box of every rank's ``points`` (n × d)."""
    lo, hi = points.min(axis=0, initial=np.inf), points.max(axis=0, initial=-np.inf)
    comm.Allreduce(MPI.IN_PLACE, lo, op=MPI.MIN)
    comm.Allreduce(MPI.IN_PLACE, hi, op=MPI.MAX)
    return lo, hi


class ReynoldsFilm(ComponentBase):
    """Pressure rows, boundary conditions, scales and JFO tools shared by the films.

    A subclass sets ``sub`` (the mesh of the film), ``Q``/``Ql`` and ``p``/``lam``,
    the kinematics ``kin`` (:class:`tribofx.forms.ehl.LubricationKinematics`),
    ``grad_gamma``, ``T`` (curve tangent), the measures ``dx``/``nodal_dx``, the
    constants ``mu_p`` (the viscosity μ(p)), ``p_c``, ``eps``, ``_c_p``, ``_q_ref``, and ``w_film``,
    ``kin_reynolds`` and ``film_rate`` (None, or those of a transient film),
    ``_supg``, ``_jumps``, ``rtol``, ``h_ref``, ``U_ref``, ``length``, then calls
    :meth:`_init_rows`.
    """

    # the lubricated body (None: a film between rigid surfaces)
    body: Body | None = None
    # a rough film's Roughness, and its laws bound to the film
    roughness: Roughness | None = None
    _rough: RoughLaws | None = None
    # a transient film's kinematics relative to S(t)
    kin_reynolds: LubricationKinematics | None = None
    # a transient film's rate of the fluid content
    film_rate: ufl.core.expr.Expr | None = None
    # a transient JFO film's nodal content rate (forms.jfo)
    lumped: bool = False
    # its vertex-rule share of the cavitated Couette flux
    vertex_couette: fem.Constant | None = None
    # (where, c_in) of the weak inflow end (add_inflow)
    _inflow: tuple[Where, fem.Constant] | None = None
    _symmetry: Where | None = None
    _rate_speed: float = 0.0   # ℓ_e/Δt of a transient film's step (mm/s; the p tolerance)
    _round_off: float = 0.0    # the Reynolds rows' round-off floor (a transient film's step)
    # {inlet: compiled rows (end dofs, form) and Couette flux of consistent_fluxes}
    _flux_forms: dict[Where, tuple[list[tuple[npt.NDArray[np.int32], fem.Form]],
                                   fem.Expression | None]] | None = None

    # set by the subclass before _init_rows (see the class docstring)
    sub: dmesh.Mesh
    name: str
    cavitation: str
    Q: fem.FunctionSpace
    Ql: fem.FunctionSpace
    p: fem.Function
    lam: fem.Function | None
    kin: LubricationKinematics
    grad_gamma: Callable[[ufl.core.expr.Expr], ufl.core.expr.Expr]
    T: ufl.core.expr.Expr | None
    dx: ufl.Measure
    nodal_dx: ufl.Measure
    mu_p: ufl.core.expr.Expr
    p_c: fem.Constant
    eps: fem.Constant | None
    _c_p: fem.Constant | float
    _q_ref: fem.Constant
    w_film: ufl.core.expr.Expr | float
    _supg: bool
    _jumps: bool
    rtol: float
    h_ref: float
    U_ref: float
    length: float
    # set here
    density: BoundLaw
    rho_p: ufl.core.expr.Expr
    _bcs: list[fem.DirichletBC]
    _bc_on: list[fem.Function]
    _inlet: Where | None
    _void_in: float
    _tol: dict[str, BlockTolerance]
    _tol_out: dict[fem.Function, BlockTolerance]
    _h_expr: fem.Expression | None
    _bfacets: npt.NDArray[np.int32] | None

    def _init_rows(self) -> None:
        self._bcs, self._inlet, self._tol, self._h_expr = [], None, {}, None
        self._bc_on = []      # the unknown each of _bcs prescribes
        self._bfacets = None
        self.set_scales()

    # -- boundary conditions of the film ---------------------------------------------
    def boundary_facets(self) -> npt.NDArray[np.int32]:
        """Facets of the submesh on ∂Γ_l (vertices of a curve, edges of a surface), local.

        A facet on ∂Γ_l has one adjacent cell of Γ_l in the whole mesh; the cells
        per facet are counted in a space with one dof per facet (P1 on a curve,
        Crouzeix–Raviart on a surface) and summed over the ranks, because the
        facet submesh has no ghost cells (``exterior_facet_indices`` would also
        return the facets on the partition boundary).
        """
        if self._bfacets is None:
            sub = self.sub
            tdim = sub.topology.dim
            sub.topology.create_entities(tdim - 1)
            sub.topology.create_connectivity(tdim, tdim - 1)
            sub.topology.create_connectivity(tdim - 1, tdim)
            space = fem.functionspace(sub, ("Lagrange" if tdim == 1 else "CR", 1))
            count = fem.Function(space)
            nc = sub.topology.index_map(tdim).size_local
            cell_dofs = space.dofmap.list[:nc]
            np.add.at(count.x.array, cell_dofs.ravel(), 1.0)
            count.x.scatter_reverse(la.InsertMode.add)
            count.x.scatter_forward()
            c2f = sub.topology.connectivity(tdim, tdim - 1)
            ncells = nc + sub.topology.index_map(tdim).num_ghosts
            entities = np.array([c2f.links(c) for c in range(ncells)], dtype=np.int32)
            dofs = space.dofmap.list[:ncells]
            self._bfacets = np.unique(entities[np.isclose(count.x.array[dofs], 1.0)])
        return self._bfacets

    def _boundary_dofs(self, V: fem.FunctionSpace, where: Where | None) -> npt.NDArray[np.int32]:
        if where is not None:
            return fem.locate_dofs_geometrical(V, where)
        return fem.locate_dofs_topological(V, self.sub.topology.dim - 1, self.boundary_facets())

    def add_pressure_bc(self, where: Where | None = None, value: float = 0.0) -> fem.Constant:
        """Prescribe p = ``value`` (MPa) where the film opens to a reservoir; returns the Constant.

        ``where``: callable of the reference coordinates (3, n) → bool, as for
        ``fem.locate_dofs_geometrical``; None: the whole boundary ∂Γ_l (the ends
        of a rigid 1D film).  The rest
        of ∂Γ_l has zero flux (natural), e.g. a symmetry line.
        """
        c = fem.Constant(self.sub, float(value))
        self._bcs.append(fem.dirichletbc(c, self._boundary_dofs(self.Q, where), self.Q))
        self._bc_on.append(self.p)
        return c

    def add_inlet(self, where: Where, void: float = 0.0,
                  pressure: float = 0.0) -> fem.Constant | None:
        """JFO inlet: λ = ``void`` and, flooded (``void`` = 0), p = ``pressure`` at ``where``.

        The rest of ∂Γ_l is a natural outlet (no Poiseuille flux; p = 0 there by
        complementarity in the cavitated zone) unless it is a reservoir
        (:meth:`add_reservoir`).  Returns the inlet pressure's Constant (MPa), None
        for a starved inlet.  The inlet is where :meth:`jfo_initial_guess` takes
        the supplied film from.
        """
        if void > 0 and pressure != 0:
            raise ValueError("a starved inlet (void > 0) is at the cavity pressure 0")
        self._void_bc(where, void)
        self._inlet, self._void_in = where, float(void)
        return self.add_pressure_bc(where, pressure) if void == 0 else None

    def add_inflow(self, where: Where, content: float = 0.0) -> fem.Constant:
        """Open ends ``where`` of a JFO film, supplied with the content c_in (mm).

        The ends of a curve, or the edges of ∂Γ_l of a surface whose midpoints
        ``where`` selects.  Where the Couette flux enters, c_in replaces the end
        node's own content θh in the flux (a lubricant layer of thickness t carried
        in by a surface moving at 2v̄ is c_in = 2t: a starved inlet for c_in below
        the gap there, a flooded one above it); where it leaves, the end is a
        natural outlet; a film that arrives full leaves through a Robin leak κp,
        p = 0 weakly (:func:`tribofx.forms.jfo.jfo_inflow`).  For a film whose flow
        reverses (a reciprocating rod), or a ball's rim, whose inflow and outflow
        parts follow from v̄.  Call before the Problem is built; returns c_in's
        Constant (mm).
        """
        if self.lam is None:
            raise ValueError("a weak inflow is for a JFO film (cavitation='jfo')")
        if self.sub.topology.dim == 2 and not self._jumps:
            raise ValueError("a weak inflow on a plane RigidFilm is not built (it is for a "
                             "curve, or a Film on a body's surface)")
        self._inflow = (where, fem.Constant(self.sub, float(content)))
        return self._inflow[1]

    def add_symmetry(self, where: Where) -> None:
        """Mark the ends ``where`` of Γ_l on a plane of symmetry: no JFO content crosses them.

        The ends of a curve, or the edges of ∂Γ_l of a surface whose midpoints
        ``where`` selects (reference coordinates).  JFO's Couette rows carry the
        flux θ h v_n out through the ends of Γ_l (:func:`tribofx.forms.jfo.jfo_on_surface`);
        on a plane of symmetry it vanishes, but v_n, taken on the element's chord or
        facet, does not where S moves across its tangent plane (two bodies that
        approach or separate): these ends are then left out, so that the rows keep
        the flux zero there.  Call before the Problem is built.
        """
        self._symmetry = where

    def add_reservoir(self, where: Where, pressure: float) -> fem.Constant:
        """JFO outlet into a reservoir: the end is flooded, p = ``pressure`` and λ = 0.

        λ needs its condition there: the p row replaces the transport row, and a
        node with p > 0 has λ = 0.  Returns the pressure's Constant (MPa).
        """
        self._void_bc(where, 0.0)
        return self.add_pressure_bc(where, pressure)

    def _void_bc(self, where: Where, void: float) -> None:
        if self.lam is None:
            raise ValueError("an inlet or reservoir condition on λ needs cavitation='jfo'")
        self._bcs.append(fem.dirichletbc(fem.Constant(self.sub, float(void)),
                                         self._boundary_dofs(self.Ql, where), self.Ql))
        self._bc_on.append(self.lam)

    def has_fluid(self) -> bool:
        """Whether every node holds fluid, λ < 1 (always without JFO; collective).

        At λ ≥ 1 the clamped transport row of a cavitated node has no derivative,
        and the Newton matrix is singular.
        """
        if self.lam is None:
            return True
        lam_max = float(self.lam.x.array.max(initial=0.0))
        return self.sub.comm.allreduce(lam_max, op=MPI.MAX) < 1.0

    def set_scales(self, p_c: float | None = None, eps: float | None = None,
                   film_scale: float | None = None, speed_scale: float | None = None) -> None:
        """Change the SUPG/complementarity pressure scale, the penalty and the tolerance scales.

        ``p_c`` (MPa) and ``eps`` (MPa·s/mm) change the discrete problem (SUPG
        Péclet number, penalty); ``film_scale`` h_ref (mm) and ``speed_scale`` U
        (mm/s) only the stopping tolerances (the row scales stay those of the
        construction).
        """
        if p_c is not None:
            self.p_c.value = float(p_c)  # type: ignore[assignment]  # dolfinx types it NDArray
        if eps is not None and self.eps is not None:
            self.eps.value = float(eps)  # type: ignore[assignment]  # (a float works)
        if film_scale is not None:
            self.h_ref = float(film_scale)
        if speed_scale is not None:
            self.U_ref = float(speed_scale)
        atol = {"p": self.rtol * (self.U_ref + self._rate_speed) * self.h_ref
                * self._flux_width() + self._round_off,
                "u_s": self.rtol * self.h_ref,
                "g": self.rtol * float(self.p_c.value) / self.length, "lam": self.rtol}
        for key, a in atol.items():
            if key in self._tol:
                self._tol[key].atol = a

    def scale_values(self) -> dict[str, float | None]:
        """Return the current scales as keyword arguments of :meth:`set_scales`."""
        return {"p_c": float(self.p_c.value),
                "eps": None if self.eps is None else float(self.eps.value),
                "film_scale": self.h_ref, "speed_scale": self.U_ref}

    def _bind_density(self, density: float | Law | None, mesh: dmesh.Mesh) -> None:
        """Bind the density law ρ(p)/ρ₀ (``rho_p``); a variable one is not done with JFO."""
        law = density_law(density)
        if self.cavitation == "jfo" and not is_constant(law):
            raise ValueError("a pressure-dependent density is implemented for penalty or no "
                             "cavitation (not JFO)")
        self.density = law.bind(mesh)
        self.rho_p = self.density(self.p)

    def _reynolds(self, dp: ufl.core.expr.Expr,
                  open_end: bool = True) -> tuple[ufl.Form, ufl.Form | None]:
        """Reynolds (or JFO transport) residual tested by ``dp``, and the JFO constraint.

        ``open_end=False`` leaves out the terms of :meth:`add_inflow` (the fluxes
        through the open end, for :meth:`consistent_fluxes`).
        """
        h_e = ufl.CellDiameter(self.sub)
        kin, mu = self._flux_kinematics()
        rate = self.film_rate
        if self.lam is None:
            def weighted(measure: ufl.Measure) -> ufl.Measure | ef.WeightedMeasure:
                return measure if self.w_film == 1 else ef.WeightedMeasure(self.w_film, measure)

            return ef.reynolds_on_surface(self.p, dp, kin, mu, weighted(self.dx),
                                          eps=self.eps, supg=self._supg, p_c=self.p_c, h_e=h_e,
                                          nodal_dx=weighted(self.nodal_dx),
                                          grad_gamma=self.grad_gamma, rho=self.rho_p,
                                          rate=rate), None
        # JFO: the weight (2π r_S, axisymmetric) enters the divergence of the fluxes
        ds_ends, ds_in = self._ds_ends()
        inflow = None if self._inflow is None or not open_end else (ds_in, self._inflow[1])
        return jfo.jfo_on_surface(self.p, self.lam, dp, ufl.TestFunction(self.Ql), kin,
                                 mu, self.dx, self.p_c, self._q_ref, h_e, self.nodal_dx,
                                 supg=self._supg, grad_gamma=self.grad_gamma, T=self.T,
                                 ds_ends=ds_ends if self._jumps else None,
                                 weight=self.w_film, rate=rate, lumped=self.lumped,
                                 inflow=inflow, vertex=self.vertex_couette)

    def _flux_kinematics(self) -> tuple[LubricationKinematics, ufl.core.expr.Expr]:
        """Kinematics and viscosity of the fluxes in the rows: (kin, μ).

        A transient film (:meth:`tribofx.interfaces.Film.transient`)
        takes the mean velocity relative to the moving surface S(t); a mixed film
        the average-flow gap and velocity (:func:`tribofx.forms.mixed.average_flow`).
        """
        kin, mu = self.kin_reynolds or self.kin, self.mu_p
        rough = self._rough
        if rough is not None and rough[0] is not None:
            assert self.roughness is not None       # bound together with _rough
            kin, mu = mixed.average_flow(kin, mu, self.roughness.sigma, rough[0], rough[1],
                                         self.roughness.share)
        return kin, mu

    def bcs(self) -> list[fem.DirichletBC]:
        """Pressure (and inlet void fraction) Dirichlet conditions."""
        return list(self._bcs)

    def bcs_by_unknown(self) -> dict[fem.Function, list[fem.DirichletBC]]:
        """Dirichlet conditions sorted by unknown: p's and λ's (each space has its own)."""
        out = {self.p: [bc for bc, on in zip(self._bcs, self._bc_on) if on is self.p]}
        if self.lam is not None:
            out[self.lam] = [bc for bc, on in zip(self._bcs, self._bc_on) if on is self.lam]
        return out

    def _flux_width(self) -> float:
        """Width (mm) across which the flux scale U·h_ref passes.

        1 on a curve (fluxes per unit length), the diameter of a surface Γ_l,
        2π r_max for an axisymmetric film.
        """
        if self.body is not None and self.body.kind == "axisymmetric":
            r = self.sub.geometry.x[:, 0].max(initial=0.0)
            return 2 * np.pi * self.sub.comm.allreduce(float(r), op=MPI.MAX)
        return 1.0 if self.sub.topology.dim == 1 else self.length

    def _pressure_tolerances(self) -> dict[fem.Function, BlockTolerance]:
        """Tolerances of the Reynolds rows (a nodal flux) and complementarity rows (-).

        The Reynolds rows are nodal volume fluxes (mm²/s on a curve, mm³/s on a
        surface); a row scale c is divided out by the weight c·φ/m (m the lumped
        vertex measure of the node, so that the vertex rule assembles exactly c).
        """
        weight = None
        if not (isinstance(self._c_p, (int, float)) and self._c_p == 1):
            q = ufl.TestFunction(self.Q)
            m = fem.assemble_vector(fem.form(q * self.nodal_dx))
            m.scatter_reverse(la.InsertMode.add)
            m.scatter_forward()
            inv = fem.Function(self.Q)
            inv.x.array[:] = np.divide(1.0, m.array, out=np.zeros_like(m.array),
                                       where=m.array > 0)
            weight = self._c_p * q * inv * self.nodal_dx
        unit = "mm²/s" if self.sub.topology.dim == 1 else "mm³/s"
        self._tol["p"] = BlockTolerance(0.0, unit, weight)
        out = {self.p: self._tol["p"]}
        w = self.w_film
        if self.lam is not None:
            h_e = ufl.CellDiameter(self.sub)
            self._tol["lam"] = BlockTolerance(0.0, "-", self._c_p * self._q_ref / h_e
                                              * ufl.TestFunction(self.Ql) * w * self.nodal_dx)
            out[self.lam] = self._tol["lam"]
        return out

    def _film_thickness(self) -> npt.NDArray[np.float64]:
        """Nodal film thickness h (mm) at the P1 pressure nodes (local, with ghosts)."""
        if self._h_expr is None:
            self._h_expr = fem.Expression(self.kin.h, self.Q.element.interpolation_points)
        h: fem.Function = fem.Function(self.Q)
        h.interpolate(self._h_expr)
        return h.x.array

    # -- JFO -----------------------------------------------------------------------------
    def _ds_ends(self) -> tuple[ufl.Measure, ufl.Measure]:
        """Measures of the end points of Γ_l and of the weak inflow's ends among them.

        The ends are the submesh's true boundary, tagged explicitly (in parallel
        the untagged ``ds`` of the facet submesh also contains the vertices on
        the partition boundary); one tag set for both (one form takes one), the
        inflow ends tagged 2, the symmetry ends (:meth:`add_symmetry`) 0, the others 1.
        """
        sub = self.sub
        fdim = sub.topology.dim - 1
        ends = self.boundary_facets()
        values = np.full(len(ends), 1, dtype=np.int32)
        if (self._inflow is not None or self._symmetry is not None) and len(ends):
            # the ends' points, or the midpoints of the edges of a surface
            X = sub.geometry.x[dmesh.entities_to_geometry(sub, fdim, ends, False)].mean(axis=1)
            if self._inflow is not None:
                values[np.asarray(self._inflow[0](X.T), dtype=bool)] = 2
            if self._symmetry is not None:     # no flux: left out of ds((1, 2))
                values[np.asarray(self._symmetry(X.T), dtype=bool)] = 0
        tags = dmesh.meshtags(sub, fdim, ends, values)
        # a point's integral is its value: the vertex rule (no points on a point) is not needed
        md = {k: v for k, v in self.dx.metadata().items() if k != "quadrature_rule"}
        ds = ufl.Measure("ds", sub, subdomain_data=tags, metadata=md)
        return ds((1, 2)), ds(2)

    def _at_dofs(self, values: npt.NDArray[np.float64], dofs: npt.NDArray[np.int32]) -> float:
        """Value of a nodal array at the first of ``dofs`` owned by some rank (all ranks)."""
        own = dofs[dofs < self.Q.dofmap.index_map.size_local]
        val = float(values[own[0]]) if len(own) else None
        return next(v for v in self.sub.comm.allgather(val) if v is not None)

    def jfo_initial_guess(self, downstream: Sequence[float] = (1.0, 0.0)) -> None:
        """Void fraction of a film that keeps its flux across the cavitated zones.

        Downstream (along ``downstream``) of the minimum film h_m the film ruptures,
        λ = max(0, 1 − h_m/h); upstream the film supplied at the inlet, (1 − λ_in)
        h_in, is advected, λ = max(0, 1 − (1 − λ_in) h_in/h) (0 for a flooded inlet
        of a converging gap), and λ = 0 wherever p > 0 (complementarity); from the
        current film h, p left as it is.  The
        semismooth Newton iteration then only moves the free boundaries.
        """
        if self.lam is None:
            return
        self.refresh()
        h = self._film_thickness()
        gdim = self.sub.geometry.dim
        X = self.Q.tabulate_dof_coordinates()[:, :gdim] @ np.asarray(downstream)[:gdim]
        n = self.Q.dofmap.index_map.size_local
        loc = (float(h[:n].min(initial=np.inf)), float(X[np.argmin(h[:n])]) if n else 0.0)
        h_m, X_m = min(self.sub.comm.allgather(loc))
        supplied = 0.0
        if self._inlet is not None:
            supplied = (1 - self._void_in) * self._at_dofs(
                h, self._boundary_dofs(self.Q, self._inlet))
        elif self._inflow is not None:
            supplied = float(self._inflow[1].value)
        # λ and p share the P1 layout of the same mesh; λ = 0 where p > 0 (complementarity)
        lam = np.maximum(np.where(X > X_m, 1 - h_m / h, 1 - supplied / h), 0.0)
        self.lam.x.array[:] = np.where(self.p.x.array > 0, 0.0, lam)
        self.lam.x.scatter_forward()

    def consistent_fluxes(self, inlet: Where | None = None) -> tuple[float, float]:
        """Volume fluxes (mm²/s, mm³/s revolved) into and out of the film from the residual.

        φ are the hat functions of the end nodes (``inlet``: where the flow enters,
        default the JFO inlet), R(φ) the Reynolds rows tested by them.  JFO (57),
        Couette part in divergence form, w = θ h v̄·t_S the Couette flux along S
        (:func:`tribofx.forms.jfo.couette_flux`; times 2π r_S on an axisymmetric
        film, whose rows are weighted by it: fluxes in mm³/s): q_in = w(inlet) + R(φ_in),
        q_out = w(outlet) − R(φ_out); the weak form (49) carries the whole flux in
        its rows: q_in = R(φ_in), q_out = −R(φ_out).  The hat functions sum to one,
        so q_out − q_in is the sum of the interior rows: zero to solver tolerance
        for a conservative model (the penalty is not).  At an open end
        (:meth:`add_inflow`, the default inlet without an :meth:`add_inlet`) R
        leaves out the end's own terms: q_in is what the supply and the leak carry.
        """
        if inlet is None:
            inlet = self._inlet if self._inlet is not None or self._inflow is None \
                else self._inflow[0]
        if inlet is None:
            raise ValueError("consistent fluxes need the inlet (add_inlet or inlet=)")
        self.refresh()
        if self._flux_forms is None:
            self._flux_forms = {}
        if inlet not in self._flux_forms:     # compiled once per inlet (called every step)
            ends, dofs_in = self._boundary_dofs(self.Q, None), self._boundary_dofs(self.Q, inlet)
            rows = []
            for dofs in (dofs_in, np.setdiff1d(ends, dofs_in)):
                phi = fem.Function(self.Q)
                phi.x.array[dofs] = 1.0
                rows.append((dofs, fem.form(self._reynolds(phi, open_end=False)[0],
                                            entity_maps=self.entity_maps() or None)))
            couette = None if self.lam is None else fem.Expression(
                self.w_film * jfo.couette_flux(self._flux_kinematics()[0],
                                               ufl.min_value(self.lam, 1.0), self.T),
                self.Q.element.interpolation_points)
            self._flux_forms[inlet] = (rows, couette)
        rows, couette = self._flux_forms[inlet]
        wf: fem.Function = fem.Function(self.Q)
        if couette is not None:
            wf.interpolate(couette)
        (d_in, R_in), (d_out, R_out) = [(d, self._sum(form)) for d, form in rows]
        return (self._at_dofs(wf.x.array, d_in) + R_in,
                self._at_dofs(wf.x.array, d_out) - R_out)

    def surface_books(self) -> dict[str, float]:
        """Return the oil's books of a JFO film on a surface: fluxes (mm³/s) through ∂Γ_l.

        With v_n the outward speed of v̄ through ∂S (:func:`tribofx.forms.jfo.boundary_speed`)
        and θh the content: ``out`` ∫ max(v_n, 0) θh dL, the Couette outflow;
        ``entered`` ∫ −min(v_n, 0) θh dL, the content carried in through the ends
        that have no supply; ``supplied`` ∫ −min(v_n, 0) c_in dL through the open
        ends of :meth:`add_inflow`; ``leak`` ∫ κ p dL, their Robin outflow.  The
        transport rows tested by δp = 1 are supplied and entered against out and
        leak: on a steady film without pressure conditions (every row solved)
        ``supplied + entered = out + leak`` to the solver's tolerance.
        """
        if self.lam is None or self.sub.topology.dim != 2 or self.T is not None:
            raise ValueError("surface_books: a JFO film on a surface (gdim = 3)")
        kin = self._flux_kinematics()[0]
        ds_ends, ds_in = self._ds_ends()
        content = (1 - ufl.min_value(self.lam, 1.0)) * kin.h
        v_n = jfo.boundary_speed(kin, ds_ends)
        forms = {"out": ufl.max_value(v_n, 0) * content * ds_ends,
                 "entered": -ufl.min_value(v_n, 0) * content * ds_ends.reconstruct(
                     subdomain_id=1)}
        if self._inflow is not None:
            h_e = ufl.CellDiameter(self.sub)
            forms["supplied"] = -ufl.min_value(v_n, 0) * self._inflow[1] * ds_in
            forms["leak"] = jfo.leak_conductance(kin, self.mu_p, h_e) * self.p * ds_in
        self.refresh()
        out = {k: self._sum(fem.form(f, entity_maps=self.entity_maps() or None))
               for k, f in forms.items()}
        return {"supplied": 0.0, "leak": 0.0} | out

    def _gather(self, data: Mapping[str, npt.ArrayLike], key: str,
                everywhere: bool) -> Profile | None:
        """Concatenate the ranks' nodal ``data`` on rank 0 (or everywhere), sorted by ``key``."""
        comm = self.sub.comm
        allp = comm.gather({k: np.asarray(v).copy() for k, v in data.items()}, root=0)
        out: Profile | None = None
        if comm.rank == 0:
            assert allp is not None                 # the root's gather is the list
            out = {k: np.concatenate([a[k] for a in allp]) for k in data}
            x = out[key] if out[key].ndim == 1 else out[key][:, 0]
            order = np.argsort(x, kind="stable")
            out = {k: v[order] for k, v in out.items()}
        return comm.bcast(out, root=0) if everywhere else out

    def _sum(self, form: fem.Form) -> float:
        return self.sub.comm.allreduce(fem.assemble_scalar(form), op=MPI.SUM)

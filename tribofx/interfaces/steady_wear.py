"""Quasi-steady wear in an Eulerian frame: a groove whose shape lives on one cross-section.

Chapter §4.3 and §5.3.  A counterpart slides steadily over a body along x; in
the frame attached to it the worn shape does not depend on x, so the shape
mapping Ψ is a 2D field w₂(y, z) on a cross-section mesh, extruded to the body
by w₃ = P w₂ (a :class:`tribofx.reduced.Reduction`; the body is a
:class:`tribofx.body.Body` with ``shape="image"`` or an image Function).  The
wear rate is averaged along the sliding path of length L per cycle, so the
groove depth rate at y is (1/L) ∫ Ẇ(x, y) dx.

Residuals (all from :mod:`tribofx.forms`):

* auxiliary plane elasticity for w₂ on the cross-section with the shape-update
  multiplier ζ on its top line (:func:`tribofx.forms.ale.aux_elasticity`,
  :func:`tribofx.forms.ale.shape_multiplier_work`);
* the lumped shape update (28) on the top line with the path-averaged rate,
  ∫ η (w₂ − w₂ₙ)·a dŝ + (Δt/L) (P_cᵀ r)_η = 0 (:func:`tribofx.forms.wear.shape_update_residual`
  without its rate term, and an :class:`tribofx.reduced.AlgebraicRow` with the
  nodal wear rate r_i = ∫_Γ̂c Ẇ j_w φ_i dŜ, Ẇ j_w = k(d) |T_N| ‖v_T‖, eq. 14, v = F V,
  eqs. 26–27; ``law="spatial"``: divided by J, eqs. 15–16); a is the mid-step
  Nanson vector of the line (exact swept area), while ζ's reaction acts along
  the line's Nanson vector at the step's end (as in :class:`tribofx.interfaces.Wear`:
  the nodes' positions along the line depend on the groove's shape alone);
  ``scheme=BDF2`` (:mod:`tribofx.scheme`): the variable-step BDF2 law in swept areas
  (:class:`tribofx.bdf2.SweptHistory`, with its error estimate ``step_error``).

The cross-section mesh is replicated on every rank (``COMM_SELF``); its
unknowns are owned by rank 0 in the :class:`tribofx.reduced.ReducedProblem`
(``problem_class``, which the slow-time stepper :class:`tribofx.stepper.Stepper`
builds for this interface).  Stepper protocol: ``scheme`` (θ = 1 implicit, θ = 0
explicit: the rate of the known state, frozen by :meth:`begin_step`; or BDF2),
``averaged = False``, :meth:`shape_unknowns`, :meth:`begin_step`,
:meth:`end_step`, :meth:`min_volume_factor`, ``body``.
Units: mm, N, s, MPa.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, cast

import numpy as np
import ufl
from dolfinx import fem, la
from mpi4py import MPI
from petsc4py import PETSc

from ..bdf2 import SweptHistory
from ..forms import ale
from ..forms import hyperelastic as hf
from ..forms import wear as wf
from ..forms import wear_groove as gf
from ..problem import BlockTolerance
from ..protocols import ComponentBase
from ..reduced import AlgebraicRow, ReducedProblem, Reduction
from ..scheme import IMPLICIT, Scheme
from ..submesh import facet_submesh

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping, Sequence

    import numpy.typing as npt
    import ufl.core.expr
    from dolfinx import mesh as dmesh

    from .contact import Contact

    #: the extrusion of a mesh: P[rows, cols] = 1, shape (n3, n2)
    #: (:func:`tribofx.meshes.halfspace.prolongation`)
    ExtrusionMap = tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], tuple[int, int]]

__all__ = ["Extrusion", "SteadyWear"]


class Extrusion:
    """The 0/1 extrusion matrix P (one unit entry per row): index arrays and PETSc (MPI)AIJ.

    Args:
        rows, cols, shape: entries P[rows, cols] = 1 (see
            :func:`tribofx.meshes.halfspace.prolongation`); ``rows`` are local body
            dofs (owned and ghost), ``cols`` cross-section dofs.
        comm: the body's communicator.
        n_own, n_glob: owned and global numbers of body dofs.

    The PETSc matrix holds the owned rows; its columns are owned by rank 0.
    """

    def __init__(self, rows: npt.NDArray[np.int64], cols: npt.NDArray[np.int64],
                 shape: tuple[int, int], comm: MPI.Comm, n_own: int, n_glob: int) -> None:
        self.rows, self.cols, self.shape, self.comm = rows, cols, shape, comm
        own = rows < n_own
        self.rows_own, self.cols_own = rows[own], cols[own]
        indptr = np.zeros(n_own + 1, dtype=PETSc.IntType)
        np.add.at(indptr, self.rows_own + 1, 1)
        indptr = np.cumsum(indptr).astype(PETSc.IntType)
        order = np.argsort(self.rows_own, kind="stable")
        n2 = shape[1]
        self.mat = PETSc.Mat().createAIJ(
            size=((n_own, n_glob), (n2 if comm.rank == 0 else 0, n2)),
            # petsc4py's stub types csr as Sequences and comm as a PETSc.Comm; arrays and
            # an mpi4py communicator are what it takes
            csr=(indptr, self.cols_own[order].astype(PETSc.IntType),  # type: ignore[arg-type]
                 np.ones(len(self.rows_own))), comm=comm)  # type: ignore[arg-type]
        self.mat.assemble()

    def apply(self, v2: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """P v₂ on the local body dofs (owned and ghost)."""
        out = np.zeros(self.shape[0])
        out[self.rows] = v2[self.cols]
        return out

    def transpose(self, v3: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Pᵀ v₃ (sum over the x layers of the owned entries, summed over the ranks)."""
        loc = np.bincount(self.cols_own, weights=v3[self.rows_own], minlength=self.shape[1])
        return self.comm.allreduce(loc, op=MPI.SUM) if self.comm.size > 1 else loc

    @property
    def T(self) -> _Transposed:  # noqa: N802 - matrix-like transpose for forms.wear_groove.path_averaged_rate
        """Object whose ``@`` applies Pᵀ."""
        return _Transposed(self)


class _Transposed:
    def __init__(self, P: Extrusion) -> None:
        self.P = P

    def __matmul__(self, v: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        return self.P.transpose(v)


class SteadyWear(ComponentBase):
    """Quasi-steady wear of ``contact``'s body, shape on the cross-section ``section``.

    Args:
        contact: the :class:`tribofx.interfaces.Contact` (frictionless; its body has
            an image shape field ``body.w``).
        section, section_tags: replicated (``COMM_SELF``) cross-section mesh (y, z) and
            its facet tags; ``section_names`` maps "top" (the worn line) and the
            boundaries with zero normal motion to tags.
        prolongation: callable (X3, X2, components) → (rows, cols, shape), the
            extrusion of the mesh (:func:`tribofx.meshes.halfspace.prolongation`).
        k: Archard coefficient (mm³/(N·mm)), a float or a UFL expression (e.g. graded).
        V: sliding speed of the counterpart relative to the body along −x (mm/s).
        L: sliding length per cycle (mm).
        law: "nominal" (eq. 14) or "spatial" (eqs. 15–16).
        aux: (E, ν) of the auxiliary plane elasticity (MPa, -).
        fixed: {section boundary name: components with zero shape change}.
        scheme: the slow-time scheme (:class:`tribofx.scheme.Scheme` or its name):
            implicit (θ = 1 of (28), the rate at the unknown state), explicit
            (θ = 0, the rate of the known state, frozen at :meth:`begin_step`), or
            BDF2: the variable-step BDF2 law in swept areas with its error
            estimate (:class:`tribofx.bdf2.SweptHistory`).
        rtol: relative size of the stopping tolerances.
    """

    problem_class = ReducedProblem  # the problem class the stepper builds
    averaged = False  # no fast-time cycles: the rate is path-averaged in closed form

    _lumped: fem.Form | None
    _line_forms: tuple[fem.Form, npt.NDArray[np.float64]] | None

    def __init__(self, contact: Contact, section: dmesh.Mesh, section_tags: dmesh.MeshTags,
                 section_names: Mapping[str, int], prolongation: Callable[..., ExtrusionMap],
                 k: float | ufl.core.expr.Expr, V: float, L: float,
                 law: str = "nominal", aux: tuple[float, float] = (1.0, 0.3),
                 fixed: Mapping[str, Sequence[int]] | None = None,
                 scheme: Scheme | str = IMPLICIT, rtol: float = 1e-10) -> None:
        scheme = Scheme.of(scheme)
        if scheme.theta not in (0, 1):
            raise ValueError(f"theta = {scheme.theta}: 0 (explicit) or 1 (implicit)")
        self.scheme = scheme
        body = contact.body
        if body.w is None or body.shape_is_unknown:
            raise ValueError("SteadyWear needs a body with an image shape field (shape='image')")
        if section.comm.size > 1:
            raise ValueError("the cross-section mesh must be replicated (created on COMM_SELF)")
        self.contact, self.body, self.L, self.rtol = contact, body, float(L), rtol
        self.section, self.section_tags, self.names = section, section_tags, dict(section_names)
        self.line, self.emap2, _ = facet_submesh(section, section_tags, self.names["top"],
                                                 "groove line")
        self.V2 = fem.functionspace(section, ("Lagrange", 1, (2,)))
        self.Q2 = fem.functionspace(self.line, ("Lagrange", 1))
        self.w2: fem.Function = fem.Function(self.V2, name="shape_change")
        self.w2n: fem.Function = fem.Function(self.V2, name="shape_change_old")
        self.zeta: fem.Function = fem.Function(self.Q2, name="shape_multiplier")
        self.dt = fem.Constant(section, 0.0)
        self.dsl = ufl.Measure("ds", section, subdomain_data=section_tags,
                               subdomain_id=self.names["top"],
                               metadata={"quadrature_rule": "vertex", "quadrature_degree": 1})
        self.dx2 = ufl.Measure("dx", section)
        self.a = ale.nanson_vector(0.5 * (self.w2 + self.w2n), ufl.FacetNormal(section))
        self.a_end = ale.nanson_vector(self.w2, ufl.FacetNormal(section))   # the reaction's
        self.bdf = SweptHistory(self.Q2, "groove")
        self._aux = hf.lame_parameters(*aux)
        # wear rate per unit initial area (eq. 14, Eulerian slip speed, eqs. 26-27)
        t_n, _ = contact.tractions()
        slip = gf.groove_slip_speed(body.u, contact.geometry, ufl.as_vector([-V, 0.0, 0.0]))
        J = ufl.det(ale.deformation_gradient_worn(body.u, body.w, "3d")) \
            if law == "spatial" else None
        self.rate_density = gf.groove_rate_density(k, t_n, slip, J)
        self.rate_form = gf.nodal_rate_form(self.rate_density, ufl.TestFunction(contact.Q),
                                            contact.dsc)
        # extrusion maps: shape (w_y, w_z) → body (u_y, u_z); line → contact nodes
        V3 = body.w.function_space
        im3, imQ = V3.dofmap.index_map, contact.Q.dofmap.index_map
        bs3 = V3.dofmap.index_map_bs
        self.Pw = Extrusion(*prolongation(V3.tabulate_dof_coordinates(),
                                          self.V2.tabulate_dof_coordinates()[:, :2],
                                          components=[(1, 0), (2, 1)]),
                            body.mesh.comm, im3.size_local * bs3, im3.size_global * bs3)
        self.Pc = Extrusion(*prolongation(contact.Q.tabulate_dof_coordinates(),
                                          self.Q2.tabulate_dof_coordinates()[:, :2]),
                            body.mesh.comm, imQ.size_local, imQ.size_global)
        self._rate_fixed: npt.NDArray[np.float64] | None = None
        fdim = section.topology.dim - 1
        self._bcs = []
        for name, comps in (fixed or {}).items():
            facets = section_tags.find(self.names[name])
            for c in comps:
                Vc = self.V2.sub(c)
                dofs = fem.locate_dofs_topological(Vc, fdim, facets)
                self._bcs.append(fem.dirichletbc(fem.Constant(section, 0.0), dofs, Vc))
        G2 = ale.shape_gradient(self.w2)
        self._area = fem.form((1 - ufl.det(G2)) * self.dx2)
        DG0 = fem.functionspace(section, ("DG", 0))
        self._detG = fem.Function(DG0)
        self._detG_expr = fem.Expression(ufl.det(G2), DG0.element.interpolation_points)
        X2 = self.V2.tabulate_dof_coordinates()[:, :2]
        self._top2 = np.flatnonzero(np.isin(np.arange(len(X2)), fem.locate_dofs_topological(
            self.V2, fdim, section_tags.find(self.names["top"]))))
        self._X2 = X2
        self._X_line = self.Q2.tabulate_dof_coordinates()[:, 0]
        self._rate_compiled = fem.form(self.rate_form, entity_maps=[contact.emap])
        self._lumped = self._line_forms = None

    # -- scheme controls ---------------------------------------------------------------
    def begin_step(self, dt: float, freeze: bool | None = None) -> None:
        """Start a step of Δt (s): w₂ₙ ← w₂; ``freeze`` (default: θ = 0) the current rate.

        BDF2: the area swept in the previous step is kept before w₂ₙ moves on
        (:class:`tribofx.bdf2.SweptHistory`).
        """
        if self.scheme.bdf2:
            self.bdf.begin_step(dt, self._swept, self._nodal_rate)
        self.w2n.x.array[:] = self.w2.x.array
        freeze = self.scheme.theta == 0 if freeze is None else freeze
        self._rate_fixed = self.rate_vector() if freeze else None
        self.dt.value = float(dt)  # type: ignore[assignment]  # dolfinx types it NDArray

    def end_step(self) -> None:
        """No wear in later plain contact solves."""
        self.dt.value = 0.0  # type: ignore[assignment]  # (a float works)
        self._rate_fixed = None

    # -- component protocol ------------------------------------------------------------
    def unknowns(self) -> list[fem.Function]:
        """Return w₂ and ζ."""
        return [self.w2, self.zeta]

    def contributions(self) -> list[tuple[fem.Function, ufl.Form]]:
        """Auxiliary elasticity with the ζ term on w₂'s row; eq. (28) without its rate on ζ's."""
        dw, eta = ufl.TestFunction(self.V2), ufl.TestFunction(self.Q2)
        mu_a, lmbda_a = (fem.Constant(self.w2.function_space.mesh, c) for c in self._aux)
        R_w = (ale.aux_elasticity(self.w2, dw, mu_a, lmbda_a, self.dx2)
               + ale.shape_multiplier_work(self.zeta, dw, self.a_end, self.dsl))
        R_z = wf.shape_update_residual(self.w2, self.w2n, self.a, 0.0, 0.0, eta, self.dsl,
                                       bdf2=self.bdf.weights if self.scheme.bdf2 else None)
        return [(self.w2, R_w), (self.zeta, R_z)]

    def shape_unknowns(self) -> list[fem.Function]:
        """Return the unknowns of the shape step (28): w₂ and ζ."""
        return [self.w2, self.zeta]

    def reductions(self) -> list[Reduction]:
        """Return the reduction: the body's shape field is the extruded section field."""
        assert self.body.w is not None      # an image shape field (__init__)
        return [Reduction(self.body.w, self.w2, self.Pw)]

    def algebraic_rows(self) -> list[AlgebraicRow]:
        """Return the path-averaged rate (Δt/L) P_cᵀ r on ζ's rows."""
        return [AlgebraicRow(self.zeta, self.rate_form, self.Pc,
                             lambda: float(self.dt.value) / self.L,
                             lambda: self._rate_fixed)]

    def bcs(self) -> list[fem.DirichletBC]:
        """Zero normal motion of the cross-section boundaries."""
        return list(self._bcs)

    def bcs_by_unknown(self) -> dict[fem.Function, list[fem.DirichletBC]]:
        """Dirichlet conditions sorted by unknown."""
        return {self.w2: list(self._bcs)}

    def entity_maps(self) -> list[dmesh.EntityMap]:
        """Return the contact's entity map (the rate form) and the line's."""
        return [self.contact.emap, self.emap2]

    def refresh(self) -> None:
        """w₃ = P w₂ is kept by the problem; nothing else."""

    def tolerances(self) -> dict[fem.Function, BlockTolerance]:
        """Shape rows: rtol·E_a·L (aux); update rows over the line measure: rtol·L mm."""
        Lb = self.body.length
        w = ufl.TestFunction(self.Q2) * self.dsl
        return {self.w2: BlockTolerance(self.rtol * 2 * self._aux[0] * Lb, "aux"),
                self.zeta: BlockTolerance(self.rtol * Lb, "mm", w)}

    def state_fields(self) -> list[fem.Function | fem.Constant]:
        """Shape, its history, the multiplier and the BDF2 history."""
        return [self.w2, self.w2n, self.zeta] + self.bdf.state_fields()

    def commit(self) -> None:
        """Nothing beyond the state."""

    # -- BDF2 -------------------------------------------------------------------------
    def _line(self) -> tuple[fem.Form, npt.NDArray[np.float64]]:
        """Return the compiled swept-area form ∫η (w₂ − w₂ₙ)·a dŝ and the weights ∫η dŝ.

        Compiled on first use; the weights once (the initial line does not move;
        the line is replicated, so its vectors are whole on every rank).
        """
        if self._line_forms is None:
            eta = ufl.TestFunction(self.Q2)
            swept = fem.form(eta * ufl.dot(self.w2 - self.w2n, self.a) * self.dsl,
                             entity_maps=[self.emap2])
            ones = fem.form(eta * fem.Constant(self.section, 1.0) * self.dsl,
                            entity_maps=[self.emap2])
            self._line_forms = (swept, fem.assemble_vector(ones).array)
        return self._line_forms

    def _per_length(self, num: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Return ``num`` per unit initial line length, num_j / ∫η_j dŝ."""
        w = self._line()[1]
        return np.divide(num, w, out=np.zeros_like(num), where=w > 0)

    def _swept(self) -> npt.NDArray[np.float64]:
        """Nodal area swept per unit initial line length, ∫η(w₂ − w₂ₙ)·a dŝ / ∫η dŝ."""
        return self._per_length(fem.assemble_vector(self._line()[0]).array)

    def _nodal_rate(self) -> npt.NDArray[np.float64]:
        """Nodal rate of the swept area per unit line length, (1/L)(P_cᵀ r)_j / ∫η_j dŝ."""
        return self._per_length(self.Pc.transpose(self.rate_vector()) / self.L)

    def step_error(
            self,
            filter: Callable[[npt.NDArray[np.float64]], npt.NDArray[np.float64]] | None = None,
    ) -> float | None:
        """Return the error estimate of the last BDF2 step (mm, all ranks), or None.

        :meth:`tribofx.bdf2.SweptHistory.error` of the nodal swept areas per unit
        line length (the groove's depth where it is flat).  No ``filter``: the
        shape unknowns are not those of one monolithic problem here.
        """
        if filter is not None:
            raise ValueError("the filtered error estimate needs a monolithic Wear step")
        if not self.scheme.bdf2:
            return None
        return self.bdf.error(self._swept(), self.body.mesh.comm)

    @property
    def error_order(self) -> int:
        """Order in Δt of the last :meth:`step_error`."""
        return self.bdf.error_order

    # -- outputs -----------------------------------------------------------------------
    def rate_vector(self) -> npt.NDArray[np.float64]:
        """Nodal 3D wear rate r_i = ∫_Γ̂c Ẇ j_w φ_i dŜ (mm³/s) at the current state (owned)."""
        assert self.body.w is not None      # an image shape field (__init__)
        self.body.w.x.array[:] = self.Pw.apply(self.w2.x.array)
        vec = fem.assemble_vector(self._rate_compiled)
        vec.scatter_reverse(la.InsertMode.add)
        return vec.array[:self.contact.Q.dofmap.index_map.size_local].copy()

    def min_volume_factor(self) -> float:
        """Smallest det(I + Grad w₂) over the cross-section cells (≤ 0: inverted)."""
        self._detG.interpolate(self._detG_expr)
        return float(np.min(self._detG.x.array))

    def groove_area(self) -> float:
        """Worn cross-section area of the modelled part, ∫ (1 − det G₂) dÂ (mm²)."""
        return float(cast("float", fem.assemble_scalar(self._area)))   # a real build

    def averaged_rate_integral(self) -> float:
        """(1/L) ∫_Γ̂c Ẇ j_w dŜ: growth rate of the groove area (mm²/s) at the current state."""
        comm = self.body.mesh.comm
        return comm.allreduce(float(np.sum(self.rate_vector())), op=MPI.SUM) / self.L

    def line_profile(self) -> dict[str, npt.NDArray[np.float64]]:
        """Top line of the cross-section: initial Ŷ, worn (Y, Z) and depth −w_z, sorted by Ŷ."""
        X2 = self._X2[self._top2]
        w = self.w2.x.array.reshape(-1, 2)[self._top2]
        o = np.argsort(X2[:, 0])
        return {"Y_hat": X2[o, 0], "worn": (X2 + w)[o], "depth": -w[o, 1]}

    def averaged_pressure(self) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """Nominal pressure integrated along the sliding path, ∫ p dx (N/mm), per line node.

        Lumped: (P_cᵀ(p_i w_i))_j / ∫ φ_j dy with p = −λ_N (nominal) and w_i = ∫ φ_i dŜ
        the initial lumped area of the surface node i.  Returns (y, ∫ p dx) sorted by y.
        """
        comm = self.body.mesh.comm
        x = self.contact.X_sub[:, 0]
        xlen = comm.allreduce(float(x.max(initial=-np.inf)), op=MPI.MAX) \
            - comm.allreduce(float(x.min(initial=np.inf)), op=MPI.MIN)
        if self._lumped is None:
            self._lumped = fem.form(ufl.TestFunction(self.contact.Q) * self.contact.dsc,
                                    entity_maps=[self.contact.emap])
        ww = self.contact.nodal(self._lumped)
        pw = np.maximum(-self.contact.lam_n.x.array, 0.0) * ww
        num, den = self.Pc.transpose(pw), self.Pc.transpose(ww)
        o = np.argsort(self._X_line)
        return self._X_line[o], (num / (den / xlen))[o]

"""Frictional contact of a body's boundary with a counterpart (chapter §2, eqs. 1–9).

The slave surface Γ_c is a named boundary of a :class:`tribofx.body.Body`.  Its
nominal tractions are unknown P1 fields on the facet submesh of Γ_c (λ_N, and
λ_T with friction), coupled to the bulk through an entity map.  The residual is
the Alart–Curnier augmented Lagrangian of
:func:`tribofx.forms.contact.augmented_lagrangian_contact`,

    G_c = ∫_Γc (T_N δg_N + T_T·δx̄) dS − ∫_Γc (1/ρ_N)(λ_N − T_N) δλ_N dS
          − ∫_Γc (1/ρ_T)(λ_T − T_T)·δλ_T dS,

integrated with vertex quadrature (the classical nodal scheme).  Slip is the
increment of the projection point over a step (Lagrangian) or the Eulerian
relative velocity v = F V − V_master times a pseudo-time (steady sliding, eqs.
26–27).

The counterpart is an object with ``geometry(x)`` (a
:class:`tribofx.forms.contact.ContactGeometry` of the UFL position x),
``update(x_nodes)`` (kernel data at the slave nodes, before every assembly),
``motion_since_commit()``, ``commit()``, ``state_fields()`` and ``unknowns()``;
the rigid countersurfaces of :mod:`tribofx.obstacles` are such objects, created
from a factory ``counterpart(V_sub)``.  Nothing here assumes the counterpart is
rigid.  Units: mm, N, MPa.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..body import AXISYMMETRIC_MOTION
from ..forms import contact as cf
from ..forms import kinematics as kin
from ..forms import wear as wf
from ..laws import friction_law
from ..params import InputError
from ..problem import BlockTolerance
from ..protocols import ComponentBase
from .surface import Surface, node_to_dof

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping

    import numpy.typing as npt
    import ufl.core.expr
    from dolfinx import mesh as dmesh

    from ..body import Body
    from ..forms.contact import ContactGeometry
    from ..laws import Law
    from ..protocols import Counterpart

__all__ = ["Contact", "gather_nodal", "node_to_dof"]


class Contact(ComponentBase):
    """Contact of ``body`` on boundary ``boundary`` with ``counterpart``.

    Args:
        body: the slave :class:`tribofx.body.Body`.
        boundary: name of the potential contact surface Γ_c.
        counterpart: factory ``counterpart(V_sub)`` returning the counterpart
            (e.g. :func:`tribofx.obstacles.rigid_plane`).
        rho_n: normal augmentation parameter (MPa/mm).
        friction: Coulomb coefficient μ (0: frictionless, no tangential multiplier), or a
            friction :class:`tribofx.laws.Law` μ(p) of the contact pressure p = −T_N
            (its reference value μ₀ > 0 decides whether there is friction).
        rho_t: tangential augmentation (MPa per unit of slip measure; default rho_n).
        slip: "lagrangian" or "eulerian" (needs the body's ``velocity``).
        V_master: velocity of the counterpart's surface for eulerian slip (mm/s).
        dtau: pseudo-time turning a slip velocity into a slip (s).
        name: name of the interface (reports).
        rtol: relative size of the gap tolerance (see :meth:`tolerances`).
    """

    lam_t: fem.Function | None
    slip: ufl.core.expr.Expr | None
    _post: dict[str, Any] | None

    def __init__(self, body: Body, boundary: str,
                 counterpart: Callable[[fem.FunctionSpace], Counterpart], rho_n: float,
                 friction: float | Law = 0.0, rho_t: float | None = None,
                 slip: str = "lagrangian", V_master: npt.ArrayLike | None = None,
                 dtau: float = 1.0, name: str = "contact", rtol: float = 1e-10) -> None:
        if slip not in ("lagrangian", "eulerian"):
            raise ValueError(f"unknown slip {slip!r}")
        law = friction_law(friction)
        friction = law.reference_value
        if friction < 0:
            raise ValueError("friction coefficient must be >= 0")
        self.body, self.name, self.rtol = body, name, rtol
        msh, gdim = body.mesh, body.gdim
        self.surface = s = Surface(body, boundary)
        self.sub, self.emap, self.Vs, self.Q, self.dsc = s.sub, s.emap, s.Vs, s.Q, s.dsc
        self.sub_dofs, self.bulk_dofs, self.X_sub = s.sub_dofs, s.bulk_dofs, s.X_sub
        self.lam_n = fem.Function(self.Q, name="contact_pressure_nominal")
        self.u_sub = fem.Function(self.Vs, name="u_contact")
        self.xbar_n = fem.Function(self.Vs, name="projection_at_last_step")
        self.counterpart = counterpart(self.Vs)
        self.geometry: ContactGeometry = self.counterpart.geometry(body.position())
        self.friction, self.slip_kind, self.dtau = float(friction), slip, float(dtau)
        self.friction_law = law.bind(msh)       # μ(p), p = −T_N: Coulomb's μ by default
        # ρ_N, ρ_T as Constants: a case run at another ρ reuses the compiled kernels
        self._rho = (fem.Constant(body.mesh, float(rho_n)),
                     fem.Constant(body.mesh, float(rho_t if rho_t is not None else rho_n)))
        self.lam_t = self.slip = None
        if friction > 0:
            self.lam_t = fem.Function(self.Vs, name="friction_traction_nominal")
            if slip == "eulerian":
                if body.velocity is None:
                    raise ValueError("eulerian slip needs the body's background velocity")
                Vm = np.zeros(gdim) if V_master is None else np.asarray(V_master, float)
                if body.kind == "axisymmetric" and Vm[0] != 0:
                    raise InputError(AXISYMMETRIC_MOTION)
                self.V_master = fem.Constant(msh, Vm)
                self.slip = cf.eulerian_slip(body.u, self.geometry, body.velocity,
                                             self.V_master, dtau)
            else:
                xbar_old = self.xbar_n + self.counterpart.motion_since_commit()
                self.slip = cf.lagrangian_slip(self.geometry, xbar_old)
        x_sub = ufl.SpatialCoordinate(self.sub) + self.u_sub
        self._xbar_expr = fem.Expression(self.counterpart.geometry(x_sub).projection,
                                         self.Vs.element.interpolation_points)
        self._post = None
        self.commit()

    # -- laws ------------------------------------------------------------------
    @property
    def rho_n(self) -> float:
        """Normal augmentation parameter ρ_N (MPa/mm)."""
        return float(self._rho[0].value)

    @property
    def rho_t(self) -> float:
        """Tangential augmentation parameter ρ_T."""
        return float(self._rho[1].value)

    @property
    def law(self) -> dict[str, Any]:
        """Keyword arguments of :func:`tribofx.forms.contact.contact_tractions`."""
        return dict(rho_n=self._rho[0], lam_t=self.lam_t, rho_t=self._rho[1], slip=self.slip,
                    mu=self.friction_law)

    def tractions(self) -> tuple[ufl.core.expr.Expr, ufl.core.expr.Expr | None]:
        """Nominal (T_N, T_T) of the Alart–Curnier law at the current state (UFL)."""
        return cf.contact_tractions(self.geometry, self.lam_n, **self.law)

    def wear_load(self, slip: ufl.core.expr.Expr | None = None) -> wf.WearLoad:
        """Return what drives Archard wear here (:class:`tribofx.forms.wear.WearLoad`, UFL).

        Frictionless: the pressure form on λ_N (the sliding speed is the Wear's).
        With friction: the dissipation form, T_T, the slip velocity v_T = slip/Δτ
        (or the slip increment ``slip``) and μ(p); k(p) and μ(p) take p = −T_N.
        """
        t_n, t_t = self.tractions()
        if self.lam_t is None:
            return wf.WearLoad(normal=self.lam_n, pressure=-t_n)
        assert self.slip is not None        # set with λ_T (friction > 0)
        v_t = self.slip / self.dtau if slip is None else slip
        return wf.WearLoad(normal=self.lam_n, pressure=-t_n, shear=t_t, slip=v_t,
                           friction=self.friction_law(-t_n))

    # -- component protocol --------------------------------------------------------
    def unknowns(self) -> list[fem.Function]:
        """λ_N (and λ_T), plus the counterpart's unknowns."""
        return [self.lam_n] + ([self.lam_t] if self.lam_t is not None else []) \
            + list(self.counterpart.unknowns())

    def contributions(self) -> list[tuple[fem.Function, ufl.Form]]:
        """Contact virtual work on u's row, the constraint rows of λ_N and λ_T."""
        mu_t = ufl.TestFunction(self.Vs) if self.lam_t is not None else None
        R_u, R_n, R_t = cf.augmented_lagrangian_contact(
            self.body.u, self.body.v, self.geometry, self.lam_n, ufl.TestFunction(self.Q),
            self._rho[0], self.dsc, self.lam_t, mu_t, self._rho[1], self.slip, self.friction_law,
            weight=self.surface.weight)
        out: list[tuple[fem.Function, ufl.Form]] = [(self.body.u, R_u), (self.lam_n, R_n)]
        if R_t is not None:
            assert self.lam_t is not None   # R_t exists only with λ_T
            out.append((self.lam_t, R_t))
        return out

    def bcs(self) -> list[fem.DirichletBC]:
        """Zero friction multiplier where u is prescribed on contact nodes.

        A slave node whose displacement component is prescribed (e.g. on a
        symmetry plane) cannot also carry a stick constraint in that direction:
        the two would be redundant and the Jacobian singular.  Its friction
        traction in that direction is zero (symmetry), so it is prescribed.
        """
        if self.lam_t is None:
            return []
        fdim = self.body.mesh.topology.dim - 1
        gdim = self.body.gdim
        out = []
        for facets, component in self.body.prescribed():
            blocks = fem.locate_dofs_topological(self.body.V, fdim, facets)
            sub_blocks = self.sub_dofs[np.isin(self.bulk_dofs, blocks)]
            for c in range(gdim) if component is None else [component]:
                out.append(fem.dirichletbc(fem.Constant(self.sub, 0.0),
                                           (gdim * sub_blocks + c).astype(np.int32),
                                           self.Vs.sub(c)))
        return out

    def bcs_by_unknown(self) -> dict[fem.Function, list[fem.DirichletBC]]:
        """Dirichlet conditions sorted by unknown."""
        return {self.lam_t: self.bcs()} if self.lam_t is not None else {}

    def entity_maps(self) -> list[dmesh.EntityMap]:
        """Return the submesh ↔ bulk entity map."""
        return [self.emap]

    def refresh(self) -> None:
        """Copy u to the submesh and let the counterpart project the slave nodes."""
        gdim = self.body.gdim
        ub = self.body.u.x.array.reshape(-1, gdim)
        us = self.u_sub.x.array.reshape(-1, gdim)
        us[self.sub_dofs] = ub[self.bulk_dofs]
        self.counterpart.update(self.positions())

    def tolerances(self) -> dict[fem.Function, BlockTolerance]:
        """Constraint rows over their lumped measure: a gap (slip) ≤ rtol·G/ρ_N mm.

        A gap error g moves the augmented traction by ρ_N g, so this bounds the
        traction error by rtol·G (G the body's shear modulus); it is kept above
        the round-off of the positions, 100 ε L.
        """
        atol = max(self.rtol * self.body.stiffness / self.rho_n,
                   100 * np.finfo(float).eps * self.body.length)
        ones = ufl.as_vector([1.0] * self.body.gdim)
        out = {self.lam_n: BlockTolerance(atol, "mm", ufl.TestFunction(self.Q) * self.dsc)}
        if self.lam_t is not None:
            out[self.lam_t] = BlockTolerance(
                atol, "mm", ufl.dot(ufl.TestFunction(self.Vs), ones) * self.dsc)
        return out

    def state_fields(self) -> list[fem.Function | fem.Constant]:
        """Multipliers, the slip history and the counterpart's state."""
        return (self.unknowns() + [self.xbar_n] + list(self.counterpart.state_fields())
                + self.friction_law.state_fields())

    def commit(self) -> None:
        """Accept the converged step: the slip history moves to the current state."""
        self.refresh()
        self.xbar_n.interpolate(self._xbar_expr)
        self.counterpart.commit()

    # -- outputs ---------------------------------------------------------------------
    def positions(self) -> npt.NDArray[np.float64]:
        """Return slave-node positions x = X + u, shape (n_sub_dofs, gdim), dof order."""
        return self.X_sub + self.u_sub.x.array.reshape(-1, self.body.gdim)

    def force_functional(self, i: int) -> ufl.Form:
        """Component ``i`` of :meth:`force` as a UFL functional of the unknowns (N)."""
        tn, tt = self.tractions()
        n = self.geometry.normal
        force = -tn * n - (tt if tt is not None else 0 * n)
        return force[i] * self.surface.weight * self.dsc

    def _forms(self) -> dict[str, Any]:
        if self._post is None:
            tn, tt = self.tractions()
            em = [self.emap]
            q = ufl.TestFunction(self.Q)
            j = kin.area_ratio(kin.deformation_gradient(self.body.u, self.body.kind),
                               ufl.FacetNormal(self.body.mesh), self.body.kind)
            tmag = ufl.sqrt(ufl.dot(tt, tt)) if tt is not None else 0 * tn
            self._post = {
                "force": [fem.form(self.force_functional(i), entity_maps=em)
                          for i in range(self.body.gdim)],
                "magnitudes": [fem.form(-tn * self.surface.weight * self.dsc, entity_maps=em),
                               fem.form(tmag * self.surface.weight * self.dsc,
                                        entity_maps=em)],
                "lumped": fem.form(q * self.surface.weight * self.dsc, entity_maps=em),
                "lumped_j": fem.form(j * q * self.surface.weight * self.dsc, entity_maps=em),
                "active": fem.form(ufl.conditional(ufl.lt(tn, 0), 1.0, 0.0) * q * self.dsc,
                                   entity_maps=em),
            }
        return self._post

    def _sum(self, form: fem.Form) -> float:
        return self.body.mesh.comm.allreduce(fem.assemble_scalar(form), op=MPI.SUM)

    def nodal(self, form: fem.Form | ufl.Form) -> npt.NDArray[np.float64]:
        """Assembled (ghost-updated) vector of the linear ``form`` on the submesh dofs."""
        return self.surface.nodal(form)

    def force(self) -> npt.NDArray[np.float64]:
        """Total force exerted by the counterpart on the modelled body (N; N/mm in plane strain).

        The modelled part of a symmetry-reduced body (a quarter sphere: a quarter of
        the full force); for an axisymmetric body the revolved body's (2πR-weighted).
        """
        return np.array([self._sum(f) for f in self._forms()["force"]])

    def traction_magnitudes(self) -> tuple[float, ...]:
        """(∫ |T_N| dS, ∫ ‖T_T‖ dS): total normal and frictional traction magnitudes (N)."""
        return tuple(self._sum(f) for f in self._forms()["magnitudes"])

    def nodal_data(self) -> dict[str, npt.NDArray[Any]]:
        """Per owned submesh node: reference X, current x, Cauchy pressure p = −T_N/j, weight.

        The weight is the lumped current area (length in 2D, per radian·2π in
        axisymmetry) of the node; ``active`` flags nodes in contact.
        """
        f = self._forms()
        n_own = self.Q.dofmap.index_map.size_local
        w, wj, act = self.nodal(f["lumped"]), self.nodal(f["lumped_j"]), self.nodal(f["active"])
        j = np.divide(wj, w, out=np.ones_like(w), where=w > 0)
        p = -self.lam_n.x.array / j
        x = self.positions()
        return {"X": self.X_sub[:n_own], "x": x[:n_own], "p": p[:n_own],
                "weight": wj[:n_own], "active": act[:n_own] > 0}

    def measures(self) -> tuple[float, float]:
        """Global contact area (sum of active lumped current weights) and peak pressure."""
        d = self.nodal_data()
        comm = self.body.mesh.comm
        area = comm.allreduce(float(np.sum(d["weight"][d["active"]])), op=MPI.SUM)
        pmax = comm.allreduce(float(np.max(d["p"], initial=0.0)), op=MPI.MAX)
        return area, pmax

    def gather_profile(self) -> dict[str, npt.NDArray[Any]] | None:
        """All nodal contact data on rank 0 (None elsewhere), sorted by reference X[0]."""
        return gather_nodal(self.body.mesh.comm, self.nodal_data())


def gather_nodal(comm: MPI.Comm,
                 data: Mapping[str, npt.NDArray[Any]]) -> dict[str, npt.NDArray[Any]] | None:
    """Concatenate the ranks' nodal ``data`` (dict of arrays) on rank 0, sorted by X[:, 0]."""
    allp = comm.gather(data, root=0)
    if comm.rank != 0:
        return None
    assert allp is not None                 # the root's gather is the list
    out = {k: np.concatenate([a[k] for a in allp]) for k in data}
    order = np.argsort(out["X"][:, 0])
    return {k: v[order] for k, v in out.items()}

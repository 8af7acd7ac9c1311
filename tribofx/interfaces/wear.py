"""Finite wear on a contact interface: Archard law and the discrete shape evolution law (§3–§4).

A :class:`Wear` interface sits on a :class:`tribofx.interfaces.Contact` whose
slave body carries the ALE shape field (``Body(..., shape=True)``: w, its
history w_n and the auxiliary elasticity rows, eqs. 19–20).  Everything lives
on the initial mesh: x = X̂ + u, X = X̂ + w, the contact multipliers are
tractions per unit *initial* area.

Residual contributions (all built by :mod:`tribofx.forms`):

* the shape row of w: ∫_Γ̂c ζ δw·a(w) dŜ (:func:`tribofx.forms.ale.shape_multiplier_work`),
  the reaction of the nodal constraint below on the auxiliary elasticity, along the
  Nanson vector of the worn boundary at the step's end (:func:`tribofx.forms.ale.nanson_vector`):
  normal to the current worn boundary, so that the tangential positions of its nodes (the
  ALE's freedom) are a function of the worn shape alone, not of the step history (along
  the swept vector below they drift by O(Δt) from step to step, which makes BDF2's nodal
  error first order under cycles while its shape error stays second order);
* the row of the multiplier ζ (P1 on the contact submesh, vertex quadrature):
  the discrete shape evolution law (28),

      ∫_Γ̂c η [(w − w_n)·a + Δt Ẇ_{n+θ} j_w] dŜ = 0,

  (:func:`tribofx.forms.wear.shape_update_residual`) with a the step average of
  the Nanson vector cof(G) N̂ (:func:`tribofx.forms.ale.swept_nanson_vector`),
  which makes (w − w_n)·a dŜ the exact volume swept by a boundary facet, so the
  discrete worn volume equals the time integral of the wear rate.

Wear rate per unit initial area Ẇ j_w (:func:`tribofx.forms.wear.slave_wear_rate`,
eqs. 14–17): frictionless contact, the pressure form k V |λ_N| (V the sliding
speed ``speed``); with friction (the contact has λ_T), the dissipation form
(k/μ) T_T·v_T with the slip velocity v_T of the Eulerian steady slip (eqs.
26–27).  Options: the spatial law (15)–(16), divided by J = det F relative to
the worn configuration; a depth-graded coefficient k(d) = k max(1 + g d, 0),
d = −w·N̂ (:func:`tribofx.forms.wear.depth_graded_coefficient`); both at t_{n+θ}.

θ-scheme (eq. 28): ``scheme=IMPLICIT`` (θ = 1, :mod:`tribofx.scheme`) takes the rate
at the unknown state (u, λ, w)_{n+1}, so the wear rows couple to the contact rows in one monolithic
problem in (u, λ_N, [λ_T], w, ζ); ``scheme=EXPLICIT`` (θ = 0) takes it at the known
contact state and the known shape w_n, so the shape step (w, ζ) can be solved
alone before the contact problem.  ``averaged=True`` drives (28) by the nodal
field ``rate_bar`` instead (the cycle-averaged rate W̄̇ of eqs. 21–23, set by
the slow-time stepper from the fast-time cycles, :mod:`tribofx.stepper`); then
any θ in [0, 1] is allowed (the stepper iterates for θ > 0).

The interface follows the component protocol of :mod:`tribofx.problem`; the
slow-time stepper uses, in addition, ``dt`` (a Constant, s), ``scheme``,
``averaged``, :meth:`shape_unknowns`, :meth:`begin_step`, :meth:`end_step`,
:meth:`min_volume_factor`, :meth:`nodal_increment` and ``rate_bar``.

Two bodies (:class:`tribofx.interfaces.TwoBodyContact`): a Wear sits on
``contact.wear_surface("slave")`` or ``contact.wear_surface("master")`` (a
:class:`tribofx.interfaces.two_body_contact.WearSurface`), one per body, each
with its own coefficient K = k/μ and the body's own shape field.  The rate is
the frictional dissipation of the fast-time cycles (``averaged=True``): the
slave's nominal increment K⁽¹⁾ ΔD⁽¹⁾ (eq. 17), the master's K⁽²⁾ ΔD⁽¹⁾
transferred to the master nodes it was dissipated against, which is eq. (18)
with its area factors j⁽²⁾/j⁽¹⁾ (see :meth:`TwoBodyContact.master_transfer`).
Units: mm, N, s, MPa.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, cast

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..bdf2 import SweptHistory
from ..forms import ale
from ..forms import wear as wf
from ..laws import is_constant, wear_coefficient_law
from ..problem import BlockTolerance
from ..protocols import ComponentBase
from ..scheme import IMPLICIT, Scheme
from .contact import node_to_dof

if TYPE_CHECKING:
    from collections.abc import Callable

    import numpy.typing as npt
    import ufl.core.expr
    from dolfinx import mesh as dmesh

    from ..body import Body
    from ..laws import Law

    class ShapedBody(Body):
        """A :class:`tribofx.body.Body` with ``shape=True``: w and w_n are Functions."""

        w: fem.Function
        w_n: fem.Function

__all__ = ["LAWS", "Wear"]

LAWS = ("nominal", "spatial")


class Wear(ComponentBase):
    """Archard wear of the slave surface of ``contact`` with the shape evolution law (28).

    Args:
        contact: the :class:`tribofx.interfaces.Contact`; its body must carry a
            shape field (``Body(..., shape=True)``).
        k: Archard coefficient k (mm³/(N·mm)); with friction K = k/μ (μ the contact's
            friction law at the node).  Or a wear-coefficient :class:`tribofx.laws.Law`
            k(p) of the contact pressure p = −T_N (e.g.
            :func:`tribofx.forms.wear.pressure_dependent_coefficient`), times the
            depth grading of ``k_grad``.
        speed: sliding speed V (mm/s) of the frictionless pressure form (with
            friction the slip velocity of the contact is used).
        law: "nominal" (eq. 14) or "spatial" (eqs. 15–16).
        k_grad: relative depth gradient g (1/mm) of k(d) = k max(1 + g d, 0).
        scheme: the slow-time scheme (:class:`tribofx.scheme.Scheme` or its
            name): :data:`~tribofx.scheme.IMPLICIT` (θ = 1 of (28)),
            :data:`~tribofx.scheme.EXPLICIT` (θ = 0), any θ in [0, 1] with
            ``averaged``, or :data:`~tribofx.scheme.BDF2` (the variable-step
            BDF2 law in swept volumes, :func:`tribofx.forms.wear.shape_update_residual`;
            its first step, and the first after a start, is backward Euler; with
            ``averaged`` the law is driven by ``rate_bar`` of the new shape, the
            Stepper's Picard iteration of cycles).
        averaged: drive (28) by the nodal cycle-averaged rate ``rate_bar``.
        name: name of the interface (reports).
        rtol: relative size of the stopping tolerance of the ζ rows (× body size, mm);
            the rows carry the wear increment of a step, orders of magnitude below
            the body size, hence a default two decades below the contact gap's.
    """

    #: the driving interfaces, duck-typed (:class:`tribofx.protocols.WearDriver`: a
    #: Contact, a Film, a side of a two-body contact or the user's own; what each
    #: answers beyond the protocol is probed with hasattr/getattr)
    drivers: list[Any]
    contact: Any
    body: ShapedBody    # checked in __init__
    _post: dict[str, Any] | None

    def __init__(self, contact: Any, k: float | Law, speed: float = 0.0, law: str = "nominal",
                 k_grad: float = 0.0, scheme: Scheme | str = IMPLICIT, averaged: bool = False,
                 name: str = "wear", rtol: float = 1e-12) -> None:
        scheme = Scheme.of(scheme)
        drivers = list(contact) if isinstance(contact, (list, tuple)) else [contact]
        contact = drivers[0]
        body = contact.body
        if any(d.body is not body for d in drivers):
            raise ValueError("the interfaces of one Wear must act on the same body")
        self.drivers, self.surface = drivers, contact.surface
        tag = self.surface.dsc.subdomain_id()
        if any(d.surface.dsc.subdomain_id() != tag for d in drivers):
            raise ValueError("the interfaces of one Wear must lie on the same boundary")
        if body.w is None or not getattr(body, "shape_is_unknown", True):
            raise ValueError("wear needs a body with a shape field: Body(..., shape=True)")
        if law not in LAWS:
            raise ValueError(f"unknown wear law {law!r}; expected one of {LAWS}")
        if not averaged and scheme.theta not in (0, 1):
            raise ValueError(f"theta = {scheme.theta}: 0 or 1 (any value in [0, 1] with "
                             "averaged)")
        if averaged and len(drivers) > 1:
            raise ValueError("cycle-averaged wear is driven by one interface")
        if not averaged and not all(hasattr(d, "wear_load") for d in drivers):
            raise ValueError(f"{type(contact).__name__} supplies no wear load: averaged=True")
        if hasattr(contact, "wear_increment") and not averaged:
            raise ValueError("two-body wear is driven by the dissipation of the fast-time "
                             "cycles: averaged=True")
        if any(getattr(d, "lam_t", None) is not None and d.slip_kind != "eulerian"
               for d in drivers) and not averaged:
            raise ValueError("Lagrangian (fast-time) friction needs averaged=True and the "
                             "fast-time cycles of the slow-time stepper (tribofx.stepper)")
        self.contact, self.body, self.name, self.rtol = contact, body, name, rtol
        self.law, self.scheme, self.averaged = law, scheme, bool(averaged)
        msh = body.mesh
        Q = self.surface.Q
        self.zeta = fem.Function(Q, name=f"{name}_shape_multiplier")
        self.rate_bar = fem.Function(Q, name=f"{name}_cycle_averaged_rate")
        self.dt = fem.Constant(msh, 0.0)  # 0: a plain contact solve does not wear
        # BDF2: weights, the volumes swept in the last two steps (nodal, per unit
        # initial area) and their Δt (state: restored with a failed step)
        self.bdf = SweptHistory(Q, name)
        self.k_law = wear_coefficient_law(k).bind(msh)   # k(p), p = −T_N; a number: constant
        if hasattr(contact, "wear_increment") and not is_constant(self.k_law.law):
            raise ValueError("a two-body contact's wear takes a constant coefficient")
        self.k = next(iter(self.k_law.constants.values()))   # its reference parameter
        self.k_grad = fem.Constant(msh, float(k_grad))
        self.speed = fem.Constant(msh, float(speed))
        self.N_hat = ufl.FacetNormal(msh)
        w, w_n = body.w, body.w_n
        self.a = ale.swept_nanson_vector(w, w_n, self.N_hat)
        self.a_end = ale.nanson_vector(w, self.N_hat)    # the reaction's direction
        if averaged:
            self.rate_density: ufl.core.expr.Expr = self.rate_bar
        else:  # t_{n+θ}: implicit (u, λ, w)_{n+1}; explicit the known state and w_n
            self.rate_density = self.rate(w if scheme.implicit else w_n)
        # trace map of w: contact-submesh dof → dof of the shape space
        gmap_w = node_to_dof(body.Vw)
        node_of_bulk = np.full(len(gmap_w), -1, dtype=np.int64)
        node_of_bulk[node_to_dof(body.V)] = np.arange(len(gmap_w))
        self._bulk_dofs_w = gmap_w[node_of_bulk[self.surface.bulk_dofs]]
        self._post = None
        self._bdf_forms: dict[str, fem.Form] = {}

    # -- the wear law ------------------------------------------------------------
    def rate(self, w: fem.Function,
             slip: ufl.core.expr.Expr | None = None) -> ufl.core.expr.Expr:
        """Wear rate per unit initial area Ẇ j_w (mm/s) at shape ``w`` and the interfaces' state.

        The sum over the driving interfaces of Archard's law for each one's
        :class:`~tribofx.forms.wear.WearLoad` (:func:`tribofx.forms.wear.archard_rate`),
        each with k(p) of its own pressure and the depth grading.  ``slip``: a slip
        increment instead of the slip velocity (then the wear increment K T_T·Δs
        in mm, for the fast-time cycles).
        """
        J = None
        if self.law == "spatial":
            J = ufl.det(ale.deformation_gradient_worn(self.body.u, w, self.body.kind))
        depth = wf.wear_depth(w, self.N_hat)
        total = 0
        for d in self.drivers:
            load = d.wear_load(slip)
            # with friction K = k/μ(p) (the contact's own friction law), so that in
            # sliding Ẇ = (k/μ) T_T·v_T = k |T_N| ‖v_T‖ whatever the law
            k = wf.depth_graded_coefficient(self.k_law(load.law_pressure), self.k_grad, depth)
            total = total + wf.archard_rate(k, load, speed=self.speed, J=J)
        return cast("ufl.core.expr.Expr", total)     # a sum over at least one driver

    # -- component protocol --------------------------------------------------------
    def unknowns(self) -> list[fem.Function]:
        """Return the multiplier ζ of the shape constraint (w is the body's)."""
        return [self.zeta]

    def shape_unknowns(self) -> list[fem.Function]:
        """Unknowns of the shape step: w and ζ."""
        return [self.body.w, self.zeta]

    def contributions(self) -> list[tuple[fem.Function, ufl.Form]]:
        """ζ δw·a on the shape row, the discrete shape evolution law (28) on ζ's row."""
        c = self.surface
        dw = ufl.TestFunction(self.body.Vw)
        eta = ufl.TestFunction(c.Q)
        bdf2 = self.bdf.weights if self.scheme.bdf2 else None
        return [(self.body.w, ale.shape_multiplier_work(self.zeta, dw, self.a_end, c.dsc)),
                (self.zeta, wf.shape_update_residual(self.body.w, self.body.w_n, self.a,
                                                     self.rate_density, self.dt, eta,
                                                     c.dsc, bdf2=bdf2))]

    def bcs(self) -> list[fem.DirichletBC]:
        """No Dirichlet conditions of its own (the body holds those of w)."""
        return []

    def bcs_by_unknown(self) -> dict[fem.Function, list[fem.DirichletBC]]:
        """Dirichlet conditions sorted by unknown (none)."""
        return {}

    def entity_maps(self) -> list[dmesh.EntityMap]:
        """Return the submesh ↔ bulk entity maps of the surface and of the interfaces."""
        out = [self.surface.emap]
        for d in self.drivers:
            maps = d.entity_maps() if hasattr(d, "entity_maps") else []
            out += [m for m in maps if all(m is not o for o in out)]
        return out

    def refresh(self) -> None:
        """Nothing computed outside UFL (the contact refreshes its counterpart)."""

    def tolerances(self) -> dict[fem.Function, BlockTolerance]:
        """ζ rows over their lumped measure: a normal shape change ≤ rtol·L (mm)."""
        eta = ufl.TestFunction(self.surface.Q)
        return {self.zeta: BlockTolerance(self.rtol * self.body.length, "mm",
                                          eta * self.surface.dsc)}

    def state_fields(self) -> list[fem.Function | fem.Constant]:
        """ζ, the cycle-averaged rate, the BDF2 history and the wear law's parameters.

        (w, w_n: the body's.)
        """
        return [self.zeta, self.rate_bar] + self.bdf.state_fields() + self.k_law.state_fields()

    def commit(self) -> None:
        """Nothing: the shape history moves on in :meth:`begin_step` of the slow time."""

    # -- slow time -------------------------------------------------------------------
    def begin_step(self, dt: float) -> None:
        """Start a slow step of Δt (s): w_n ← w, Δt set.

        BDF2: the volume swept in the previous step, (w − w_n)·a per node, is kept
        before w_n moves on, and the weights follow ω = Δt/Δt_prev (backward Euler
        when there is no previous step).
        """
        if self.scheme.bdf2:
            self.bdf.begin_step(dt, self.swept_volume, self._nodal_rate)
        self.dt.value = float(dt)  # type: ignore[assignment]  # dolfinx types it NDArray
        self.body.w_n.x.array[:] = self.body.w.x.array

    def _nodal_value(self, key: str,
                     integrand: ufl.core.expr.Expr) -> npt.NDArray[np.float64]:
        """Return nodal values of ``integrand``, the vertex rule's lumping ∫η_i f/∫η_i.

        The form of ``key`` is compiled once.
        """
        if key not in self._bdf_forms:
            eta = ufl.TestFunction(self.surface.Q)
            self._bdf_forms[key] = fem.form(eta * integrand * self.surface.dsc,
                                            entity_maps=self.entity_maps())
        num = self.surface.nodal(self._bdf_forms[key])
        den = self.surface.nodal(self._forms()["lumped"])
        return np.divide(num, den, out=np.zeros_like(num), where=den > 0)

    def lumped_weight(self) -> npt.NDArray[np.float64]:
        """Nodal lumped area of the worn surface (mm², the rows of ζ; owned and ghosts)."""
        return self.surface.nodal(self._forms()["lumped"])

    def swept_volume(self) -> npt.NDArray[np.float64]:
        """Nodal (w − w_n)·a(w, w_n) per unit initial area."""
        return self._nodal_value("swept", ufl.dot(self.body.w - self.body.w_n, self.a))

    def step_error(
            self,
            filter: Callable[[npt.NDArray[np.float64]], npt.NDArray[np.float64]] | None = None,
    ) -> float | None:
        """Return the error estimate of the last BDF2 step (mm, all ranks), or None.

        :meth:`tribofx.bdf2.SweptHistory.error` of the nodal swept volumes per unit
        initial area (its order in :attr:`error_order`), ``filter``-ed if given.
        """
        if not self.scheme.bdf2:
            return None
        return self.bdf.error(self.swept_volume()[:self.surface.n_own], self.body.mesh.comm,
                              filter)

    @property
    def error_order(self) -> int:
        """Order in Δt of the last :meth:`step_error`."""
        return self.bdf.error_order

    def set_start_rate(self, rate: npt.NDArray[np.float64]) -> None:
        """Nodal rate Ẇ j_w (mm/s) at the start of a cycle-driven step (``rate_bar``'s layout).

        A BDF2 first step is checked against forward Euler from the rate at t_n;
        driven by cycles, that rate is the first cycle's (``rate_bar`` at
        :meth:`begin_step` is the last step's).  No effect otherwise.
        """
        if self.scheme.bdf2:
            self.bdf.set_start_rate(rate)

    def _nodal_rate(self) -> npt.NDArray[np.float64]:
        """Nodal Ẇ j_w (mm/s) of the current state."""
        return self._nodal_value("rate", self.rate_density)

    def end_step(self) -> None:
        """End a slow step: Δt = 0, so that a later contact solve does not wear."""
        self.dt.value = 0.0  # type: ignore[assignment]  # (a float works)

    # -- outputs ---------------------------------------------------------------------
    def _forms(self) -> dict[str, Any]:
        if self._post is None:
            c, b = self.surface, self.body
            em = self.entity_maps()
            G = ale.shape_gradient(b.w)
            q = ufl.TestFunction(c.Q)
            now = self.rate_bar if self.averaged else self.rate(b.w)
            DG0 = fem.functionspace(b.mesh, ("DG", 0))
            self._post = {
                "volume": fem.form((1 - ufl.det(G)) * b.dx),
                "rate": fem.form(now * c.dsc, entity_maps=em),
                "normal": fem.form(ufl.dot(ufl.TestFunction(c.Vs), self.N_hat) * c.dsc,
                                   entity_maps=em),
                "lumped": fem.form(q * c.dsc, entity_maps=em),
                "detG": fem.Function(DG0),
                "detG_expr": fem.Expression(ufl.det(G), DG0.element.interpolation_points),
            }
            d = self.contact
            if getattr(d, "lam_t", None) is not None and d.slip_kind == "lagrangian" and \
                    not hasattr(d, "wear_increment"):
                self._post["increment"] = fem.form(self.rate(b.w, slip=d.slip) * q * c.dsc,
                                                   entity_maps=em)
            n = c.nodal(self._post["normal"]).reshape(-1, b.gdim)
            self._N_nodal = n / np.linalg.norm(n, axis=1)[:, None]
        return self._post

    def _sum(self, form: fem.Form) -> float:
        return self.body.mesh.comm.allreduce(fem.assemble_scalar(form), op=MPI.SUM)

    def worn_volume(self) -> float:
        """Worn volume ∫_Ω̂ (1 − det G) dV̂ (mm³; per unit thickness, mm², in plane strain)."""
        return self._sum(self._forms()["volume"])

    def wear_rate_integral(self) -> float:
        """∫_Γc Ẇ dS = ∫_Γ̂c Ẇ j_w dŜ at the current state (mm³/s; mm²/s per mm in 2D).

        With ``averaged``: the integral of ``rate_bar`` (the rate of the last step).
        """
        return self._sum(self._forms()["rate"])

    def nodal_increment(self) -> npt.NDArray[np.float64]:
        """Wear increment K T_T·Δs (mm) per unit initial area of the last fast sub-step.

        Lagrangian friction only; call after the sub-step's solve and before the
        commit (Δs is measured from the last committed projection point).
        Returns the local array on the contact dofs (lumped nodal values).
        """
        f = self._forms()
        if hasattr(self.contact, "wear_increment"):   # a side of a two-body contact
            return self.contact.wear_increment(self.k.value / self.contact.friction)
        if "increment" not in f:
            raise ValueError("wear increments need Lagrangian friction on the contact")
        num, den = self.surface.nodal(f["increment"]), self.surface.nodal(f["lumped"])
        return np.divide(num, den, out=np.zeros_like(num), where=den > 0)

    def min_volume_factor(self) -> float:
        """Smallest det(I + Grad w) over all cells (≤ 0: the worn mesh is inverted)."""
        f = self._forms()
        f["detG"].interpolate(f["detG_expr"])
        n = f["detG"].function_space.dofmap.index_map.size_local
        local = float(np.min(f["detG"].x.array[:n], initial=np.inf))
        return self.body.mesh.comm.allreduce(local, op=MPI.MIN)

    def nodal_shape_data(self) -> dict[str, npt.NDArray[Any]]:
        """Per owned contact node: the contact's nodal data and X̂, X = X̂ + w, depth −w·N̂ (mm)."""
        self._forms()
        c, gdim = self.surface, self.body.gdim
        d = self.contact.nodal_data() if hasattr(self.contact, "nodal_data") else {}
        n_own = c.Q.dofmap.index_map.size_local
        wb = self.body.w.x.array.reshape(-1, gdim)
        ws = np.zeros_like(c.X_sub)
        ws[c.sub_dofs] = wb[self._bulk_dofs_w]
        d["X_hat"] = c.X_sub[:n_own]
        d["X_worn"] = c.X_sub[:n_own] + ws[:n_own]
        d["depth"] = -np.sum(ws[:n_own] * self._N_nodal[:n_own], axis=1)
        return d

    def max_depth(self) -> float:
        """Largest wear depth over the contact nodes (mm, on every rank)."""
        d = self.nodal_shape_data()
        return self.body.mesh.comm.allreduce(float(np.max(d["depth"], initial=0.0)),
                                             op=MPI.MAX)

    def gather_shape(self, root_only: bool = True) -> dict[str, npt.NDArray[Any]] | None:
        """:meth:`nodal_shape_data` of all ranks, sorted by X̂[0], on rank 0 (None elsewhere).

        ``root_only=False``: the same dict on every rank.
        """
        comm = self.body.mesh.comm
        d = self.nodal_shape_data()
        allp = comm.gather(d, root=0)
        out = None
        if comm.rank == 0:
            out = {k: np.concatenate([a[k] for a in allp]) for k in d}
            order = np.argsort(out["X_hat"][:, 0], kind="stable")
            out = {k: v[order] for k, v in out.items()}
        return out if root_only else comm.bcast(out, root=0)

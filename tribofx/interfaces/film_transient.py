"""Transient films: the squeeze term in time, the film as an evolving interface of the Stepper.

:class:`TransientFilm` is a base class of :class:`tribofx.interfaces.Film`.
:meth:`TransientFilm.transient` (called before the Problem is built) turns the
steady film of the chapter into the transient one of :mod:`tribofx.forms.squeeze`:

* the Reynolds (or JFO transport) rows get the rate of the fluid content
  c = ρ θ h J_S w at fixed reference point X and the mean velocity relative to
  the moving lubrication surface, v̄ − (I − ν⊗ν) ẏ;
* the layer velocity gets the displacement rate u̇ (rows and Couette traction);
* the rates are backward differences of histories kept by the film: c at the
  quadrature points of Γ_l, the trace u_s and the body's u at their nodes, the
  countersurface's rigid translation; ẏ follows by the chain rule
  (:func:`tribofx.forms.squeeze.surface_rate`).

The film then answers the slow-time protocol of :class:`tribofx.stepper.Stepper`
(an implicit :class:`tribofx.scheme.Scheme`, not averaged, no shape unknowns):
``begin_step(dt)`` moves the histories on (t_n ← the converged state) and sets
the weights, backward Euler (``scheme=IMPLICIT``, named ``"euler"``) or
variable-step BDF2 (``scheme=BDF2``, ``"bdf2"``, started by one backward-Euler
step).  Between steps (before the first) the rate weight 1/Δt is
0 and the film is the steady one, so a steady solve gives the initial state.
"""

import dataclasses

import basix.ufl
import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..forms import mixed
from ..forms import squeeze as sq
from ..forms import wear as wf
from ..scheme import BDF2, Scheme

__all__ = ["TransientFilm"]


class TransientFilm:
    """Time history and slow-time protocol of a transient :class:`tribofx.interfaces.Film`."""

    averaged = False
    scheme: Scheme | None = None     # None: the steady film of the chapter
    _content_form = None     # the compiled ∫ c dS of :meth:`content`
    _conductance = None      # the compiled w h³|p|/(12 μ h_e) of :meth:`row_round_off`

    def transient(self, scheme=BDF2, lumped=False):
        """Make the film transient, integrated by ``scheme``; returns self.

        ``scheme``: :data:`~tribofx.scheme.IMPLICIT` (backward Euler, ``"euler"``)
        or :data:`~tribofx.scheme.BDF2` (``"bdf2"``).

        Call before the :class:`tribofx.problem.Problem` is built (the rows are
        built with the rates).  Needs the Gauss quadrature of Γ_l (the history of
        the content c lives at its points).  ``lumped`` (JFO): the content's rate
        on the vertex rule, its history at the nodes of each cell (discontinuous
        P1), and weighted by the full-film fraction in SUPG; on a curve also the
        Constant ``vertex_couette`` ω (0 until set), the vertex rule's share of
        the cavitated Couette flux (:func:`tribofx.forms.jfo.jfo_on_surface`).
        """
        scheme = Scheme.of(scheme)
        if not scheme.implicit:
            raise ValueError(f"a transient film is implicit: euler or bdf2, not {scheme.name}")
        if self.scheme is not None:
            raise ValueError("the film is already transient")
        md = self.dx.metadata()
        if md.get("quadrature_rule") == "vertex":
            raise ValueError("a transient film needs quadrature='gauss'")
        if lumped and self.lam is None:
            raise ValueError("a lumped transient film is for cavitation='jfo'")
        self.scheme, self.lumped = scheme, bool(lumped)
        if lumped and self._jumps:   # ω of jfo_on_surface(vertex=): 0 until set (reforming films)
            self.vertex_couette = fem.Constant(self.sub, 0.0)
        sub, body, gdim = self.sub, self.body, self.body.gdim
        deg = md["quadrature_degree"]
        Cq = fem.functionspace(sub, ("DG", 1) if lumped else basix.ufl.quadrature_element(
            sub.basix_cell(), (), degree=deg))
        n = self.name
        self._hist = {
            "c": [fem.Function(Cq, name=f"{n}_content_{k}") for k in ("n", "nm1")],
            "u_s": [fem.Function(self.Vs, name=f"{n}_trace_{k}") for k in ("n", "nm1")],
            "u": [fem.Function(body.u.function_space, name=f"{n}_body_u_{k}")
                  for k in ("n", "nm1")],
        }
        # the countersurface's rigid translation (if any) at t_n, t_{n−1}
        self._offset = getattr(self.counterpart, "offset", None)
        self._offset_hist = [fem.Constant(sub, np.zeros(gdim)) for _ in range(2)]
        # weights 1/Δt, c₀, c₁ and the previous step: bulk constants, submesh mirrors
        self.time_weights = [fem.Constant(body.mesh, 0.0) for _ in range(3)]
        self.dt_prev = fem.Constant(body.mesh, 0.0)
        w_sub = [self._mirror(c) for c in self.time_weights]
        H = self._hist
        self.film_rate = sq.backward_difference(self._content(), *H["c"], *w_sub)
        u_rate = sq.backward_difference(self.u_s, *H["u_s"], *w_sub)
        # ẏ by the chain rule: y(x, c) moves with a common translation of x and c
        c_rate = None
        if self._offset is not None:
            c_rate = sq.backward_difference(self._offset, *self._offset_hist, *w_sub)
        y_rate = sq.surface_rate(self.kin.y, self.u_s, u_rate, c_rate)
        self.kin = sq.moving_surface(self.kin, layer_rate=u_rate)
        self.kin_reynolds = sq.moving_surface(self.kin, surface_rate=y_rate)
        self.kin_bulk = sq.moving_surface(self.kin_bulk,
                                          layer_rate=sq.backward_difference(
                                              body.u, *H["u"], *self.time_weights))
        self._tractions()
        self._expr = fem.Expression(self._content(), Cq.element.interpolation_points)
        cells = sub.topology.index_map(sub.topology.dim).size_global
        one = fem.form(fem.Constant(sub, 1.0) * self.dx)
        self._cell_size = (self._sum(one) / cells) ** (1 / sub.topology.dim)
        return self

    def history_fields(self):
        """Histories and time weights of a transient film (none when steady)."""
        if self.scheme is None:
            return []
        return ([f for fs in self._hist.values() for f in fs] + list(self.time_weights)
                + [self.dt_prev] + self._offset_hist)

    # -- slow-time protocol (tribofx.stepper.Stepper) ------------------------------------
    def shape_unknowns(self):
        """No shape unknowns: the film's unknowns are solved with the body's."""
        return []

    def min_volume_factor(self):
        """No shape change: +inf (the Stepper's mesh check passes)."""
        return np.inf

    def begin_step(self, dt):
        """Start a step of Δt (s): histories t_{n−1} ← t_n ← the converged state; weights.

        BDF2 with ω = Δt/Δt_prev (:func:`tribofx.forms.wear.bdf2_coefficients`);
        the first step, and every step of the implicit θ-scheme, is backward Euler.
        """
        if self.scheme is None:
            raise ValueError("begin_step of a steady film: call film.transient() first")
        self.refresh()
        live = {"u_s": self.u_s, "u": self.body.u}
        for key, (f_n, f_nm1) in self._hist.items():
            f_nm1.x.array[:] = f_n.x.array
            if key in live:
                f_n.x.array[:] = live[key].x.array
            else:
                f_n.interpolate(self._expr)
            f_n.x.scatter_forward()
        if self._offset is not None:
            self._offset_hist[1].value[:] = self._offset_hist[0].value
            self._offset_hist[0].value[:] = self._offset.value
        prev = float(self.dt_prev.value)
        c0, c1 = (1.0, 0.0) if not self.scheme.bdf2 or prev <= 0 \
            else wf.bdf2_coefficients(dt / prev)
        for c, v in zip(self.time_weights, (1.0 / dt, c0, c1)):
            c.value = v
        self.dt_prev.value = float(dt)
        self._rate_speed = self._cell_size / dt      # the Reynolds rows' tolerance
        self._round_off = self.row_round_off()
        self.set_scales()

    def row_round_off(self):
        """Round-off floor of the Reynolds rows at the current state (mm²/s; mm³/s revolved).

        A row sums Poiseuille fluxes K (p_i − p_j) with K = w h³/(12 μ h_e) of its
        elements: p known to an ulp or so (≈ eps |p|, whatever the iteration)
        leaves ≈ 2 eps K |p| to 4 eps K |p| per row.  Where the film is thick this
        exceeds rtol·U·h_ref: the seal's flank opens to h = 0.84 mm in the
        instroke (K ≈ 3.6e9 mm³/(MPa·s) at p_s = 1 MPa), whose rows stopped at
        6.5e-7 mm³/s against a tolerance of 6.5e-7 (measured).  Returns
        4 eps max K |p| over the nodes (every rank), added to the p tolerance of
        the step (:meth:`begin_step`).
        """
        if self._conductance is None:
            kin, mu = self._flux_kinematics()
            self._conductance = fem.Expression(
                self.w_film * kin.h**3 * abs(self.p) / (12 * mu * ufl.CellDiameter(self.sub)),
                self.Q.element.interpolation_points)
        Kp = fem.Function(self.Q)
        Kp.interpolate(self._conductance)
        local = float(np.max(np.abs(Kp.x.array), initial=0.0))
        return 4 * np.finfo(float).eps * self.sub.comm.allreduce(local, op=MPI.MAX)

    def end_step(self):
        """Nothing: the outputs of the step keep its rates (the next step resets them)."""

    def _content(self):
        """UFL content ρ θ h J_S w per unit reference measure (h, J_S: any ``kin`` of the film).

        A rough film with average flow stores the expected gap h_T(h) (Patir & Cheng:
        the squeeze term is ∂h_T/∂t), the gap its flux is written on.
        """
        kin, rough = self.kin, getattr(self, "_rough", None)
        if rough is not None and rough[0] is not None:
            kin = dataclasses.replace(kin, h=mixed.expected_gap(kin.h, self.roughness.sigma))
        return sq.film_content(kin, self.lam, self.rho_p, self.w_film)

    def content(self):
        """Fluid in the film's modelled part, ∫ ρ θ h ds_S (all ranks; form compiled once).

        mm² per unit length in the plane, mm³ in 3D and revolved.  A lumped film
        integrates it by the vertex rule of its rate: the content the discrete
        rows conserve (its change over a step is the net flux of
        :meth:`~tribofx.interfaces.reynolds_film.ReynoldsFilm.consistent_fluxes`).
        """
        if self._content_form is None:
            dx = self.nodal_dx if self.lumped else self.dx
            self._content_form = fem.form(self._content() * dx)
        return self._sum(self._content_form)

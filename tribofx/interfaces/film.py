"""Lubricating film: the soft-EHL interface on a body's boundary (chapter §6–7).

The lubricated boundary Γ_l is a named boundary of a :class:`tribofx.body.Body`;
the counterpart is an object with ``geometry(x)`` (closest-point geometry of the
UFL position x), ``update(x_nodes)`` (kernel data, refreshed before every
assembly), ``commit()``, ``state_fields()`` and ``unknowns()`` — the rigid
countersurfaces of :mod:`tribofx.obstacles` (plane, cylinder, sphere, surface
mesh) created from a factory ``counterpart(V_sub)``, as for
:class:`tribofx.interfaces.Contact`.  Nothing here assumes that the counterpart
is rigid; only :meth:`Film.place_countersurface` moves a rigid one.

Unknowns on the facet submesh of Γ_l (all on the initial mesh):

* u_s — trace of the body's displacement (same degree), tied to u by
  :func:`tribofx.forms.ehl.trace_constraint` (DOLFINx differentiates submesh
  fields only in submesh integrals, so the Reynolds equation is written in u_s);
* p — film pressure, P1;
* g — tangential pressure gradient Grad_Γ p, vector DG0 (with the shear
  tractions only; :func:`tribofx.forms.ehl.tangential_gradient_constraint`);
* λ — void fraction of the JFO model (``cavitation="jfo"``), P1.

Residual rows, all from :mod:`tribofx.forms.ehl` (pure UFL):

* u: the film term of the virtual work (62), −∫_Γl T·δu dS, with the nominal
  fluid traction (46) T = −p J F⁻ᵀN − j((μ/h)(v_layer − v_counter) + (h/2) grad_S p)
  (:func:`~tribofx.forms.ehl.fluid_traction`, ``shear=False``: pressure only);
* u_s: the trace constraint;
* p: the steady Reynolds equation (49) on the lubrication surface S = P(γ_l)
  (or S_α, Fig. 23) pulled back to Γ_l, SUPG (Remark 3.2), penalty cavitation
  (:func:`~tribofx.forms.ehl.reynolds_on_surface`), or the JFO transport (57)
  (:func:`~tribofx.forms.ehl.jfo_on_surface`);
* g: Grad_Γ p; λ: the nodal complementarity (52).

The lubrication surface follows the counterpart's projection, h = (x − y)·ν,
∂P/∂x by :func:`~tribofx.forms.ehl.countersurface_projection`; ``model="linear"``
is the classical (geometrically linear) EHL model (geometry of the undeformed
configuration, h linear in u; pair it with a "linear" body material).  The body
moves with its Eulerian velocity v = F V (``body.velocity``, eq. 26; None: at
rest); the countersurface with ``V_counter`` (mm/s, a Constant; None: at rest).

Kinds: "plane_strain" (Γ_l a curve, T = (N_y, −N_x)), "3d" (Γ_l a surface) and
"axisymmetric" (meridian plane (r, z), weights 2πr: the Reynolds equation on the
surface of revolution S carries ds = 2π r_S dl with r_S the radius of the
projection point, the traction the body's 2πR times the hoop stretch r/R).

Stopping test (:class:`tribofx.problem.BlockTolerance`, lumped reference
measures of Γ_l): Reynolds rows as a nodal volume flux imbalance (mm²/s per
unit length on a curve, mm³/s on a surface) ≤ rtol·U·h_ref·b, b the width of
the film (1, the diameter ℓ_l of Γ_l, or 2πr), i.e. rtol of the Couette flux
through the film; trace rows as a displacement (mm) ≤ rtol·h_ref, g rows (MPa/mm)
≤ rtol·p_c/ℓ_l, complementarity rows (dimensionless) ≤ rtol; U, h_ref and p_c are
the speed, film and pressure scales of :meth:`Film.set_scales`.

Row scaling (``row_scaling=True``, the default).  The Newton line search of
:class:`tribofx.problem.Problem` compares 2-norms of the whole residual; the
film rows are therefore multiplied by physical factors that give every row the
unit of a force per area of the momentum rows: μ/h_ref for the flux rows
(Reynolds, complementarity: a flux imbalance δq costs the pressure μδq/h_ref²
over h_ref), G/h_ref for the trace rows, h_ref for the g rows (fixed at
construction).  They do not change the solution, and the stopping test divides
them out again (the weights carry them).  Measured without them (the Reynolds
rows in mm²/s then dominate the line-search norm by orders of magnitude): the
penalty cases converge in about the same Newton iterations, the geometrically
linear ball needs up to twice as many, and the JFO cylinder fails (the LU
factorisation breaks down after a poor line-search step).

Units: mm, N, s, MPa (viscosity MPa·s).
"""

import numpy as np
import ufl
from dolfinx import fem, la
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..forms import ehl as ef
from ..problem import BlockTolerance
from ..submesh import facet_submesh

__all__ = ["Film", "PrescribedPressure", "RigidFilm"]


def _outward_cell_normals(body, sub, emap, G):
    """DG0 field on the submesh: outward unit normal of each (flat) cell of Γ_l."""
    msh = body.mesh
    tdim = msh.topology.dim
    imap = sub.topology.index_map(tdim - 1)
    nc = imap.size_local + imap.num_ghosts
    facets = emap.sub_topology_to_topology(np.arange(nc, dtype=np.int32), False)
    f2c = msh.topology.connectivity(tdim - 1, tdim)
    xg, dm = msh.geometry.x, msh.geometry.dofmaps[0]
    cells = np.array([f2c.links(f)[0] for f in facets], dtype=np.int64)
    xc = xg[dm[cells]].mean(axis=1)
    xs = sub.geometry.x[sub.geometry.dofmaps[0][:nc]]
    if tdim == 2:
        t = xs[:, 1] - xs[:, 0]
        n = np.c_[t[:, 1], -t[:, 0], np.zeros(nc)]
    else:
        n = np.cross(xs[:, 1] - xs[:, 0], xs[:, 2] - xs[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    flip = np.sum(n * (xs.mean(axis=1) - xc), axis=1) < 0
    n[flip] *= -1
    N = fem.Function(G, name="reference_normal")
    gdim = body.gdim
    dofs = np.array([G.dofmap.cell_dofs(c)[0] for c in range(nc)], dtype=np.int64)
    arr = N.x.array.reshape(-1, gdim)
    arr[dofs] = n[:, :gdim]
    return N


class _ReynoldsFilm:
    """Pressure rows, boundary conditions, scales and JFO tools shared by the films.

    A subclass sets ``sub`` (the mesh of the film), ``Q``/``Ql`` and ``p``/``lam``,
    the kinematics ``kin`` (:class:`tribofx.forms.ehl.LubricationKinematics`),
    ``grad_gamma``, ``T`` (curve tangent), the measures ``dx``/``nodal_dx``, the
    constants ``mu_c``, ``p_c``, ``eps``, ``_c_p``, ``_q_ref``, and ``w_film``,
    ``_supg``, ``_jumps``, ``rtol``, ``h_ref``, ``U_ref``, ``length``, then calls
    :meth:`_init_rows`.
    """

    def _init_rows(self):
        self._bcs, self._inlet, self._tol, self._h_expr = [], None, {}, None
        self._bfacets = None
        self.set_scales()

    # -- boundary conditions of the film ---------------------------------------------
    def boundary_facets(self):
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

    def _boundary_dofs(self, V, where):
        if where is not None:
            return fem.locate_dofs_geometrical(V, where)
        return fem.locate_dofs_topological(V, self.sub.topology.dim - 1, self.boundary_facets())

    def add_pressure_bc(self, where=None, value=0.0):
        """Prescribe p = ``value`` (MPa) where the film opens to a reservoir; returns the Constant.

        ``where``: callable of the reference coordinates (3, n) → bool, as for
        ``fem.locate_dofs_geometrical``; None: the whole boundary ∂Γ_l (the ends
        of a rigid 1D film).  The rest
        of ∂Γ_l has zero flux (natural), e.g. a symmetry line.
        """
        c = fem.Constant(self.sub, float(value))
        self._bcs.append(fem.dirichletbc(c, self._boundary_dofs(self.Q, where), self.Q))
        return c

    def add_inlet(self, where, void=0.0):
        """JFO inlet: λ = ``void`` and, flooded (``void`` = 0), p = 0 at ``where``.

        The rest of ∂Γ_l is a natural outlet (no Poiseuille flux; p = 0 there by
        complementarity in the cavitated zone).
        """
        if self.lam is None:
            raise ValueError("an inlet needs cavitation='jfo'")
        self._inlet, self._void_in = where, float(void)
        self._bcs.append(fem.dirichletbc(fem.Constant(self.sub, float(void)),
                                         self._boundary_dofs(self.Ql, where), self.Ql))
        if void == 0:
            self.add_pressure_bc(where)

    def set_scales(self, p_c=None, eps=None, film_scale=None, speed_scale=None):
        """Change the SUPG/complementarity pressure scale, the penalty and the tolerance scales.

        ``p_c`` (MPa) and ``eps`` (MPa·s/mm) change the discrete problem (SUPG
        Péclet number, penalty); ``film_scale`` h_ref (mm) and ``speed_scale`` U
        (mm/s) only the stopping tolerances (the row scales stay those of the
        construction).
        """
        if p_c is not None:
            self.p_c.value = float(p_c)
        if eps is not None and self.eps is not None:
            self.eps.value = float(eps)
        if film_scale is not None:
            self.h_ref = float(film_scale)
        if speed_scale is not None:
            self.U_ref = float(speed_scale)
        atol = {"p": self.rtol * self.U_ref * self.h_ref * self._flux_width(),
                "u_s": self.rtol * self.h_ref,
                "g": self.rtol * float(self.p_c.value) / self.length, "lam": self.rtol}
        for key, a in atol.items():
            if key in self._tol:
                self._tol[key].atol = a

    def _reynolds(self, dp):
        """Reynolds (or JFO transport) residual tested by ``dp``, and the JFO constraint."""
        dx = ef.WeightedMeasure(self.w_film, self.dx) if self.w_film != 1 else self.dx
        nodal = (ef.WeightedMeasure(self.w_film, self.nodal_dx) if self.w_film != 1
                 else self.nodal_dx)
        h_e = ufl.CellDiameter(self.sub)
        if self.lam is None:
            return ef.reynolds_on_surface(self.p, dp, self.kin, self.mu_c, dx, eps=self.eps,
                                          supg=self._supg, p_c=self.p_c, h_e=h_e,
                                          nodal_dx=nodal, grad_gamma=self.grad_gamma), None
        return ef.jfo_on_surface(self.p, self.lam, dp, ufl.TestFunction(self.Ql), self.kin,
                                 self.mu_c, dx, self.p_c, self._q_ref, h_e, nodal,
                                 supg=self._supg, grad_gamma=self.grad_gamma, T=self.T,
                                 ds_ends=self._ds_ends() if self._jumps else None)

    def bcs(self):
        """Pressure (and inlet void fraction) Dirichlet conditions."""
        return list(self._bcs)

    def _flux_width(self):
        """Width (mm) across which the flux scale U·h_ref passes.

        1 on a curve (fluxes per unit length), the diameter of a surface Γ_l,
        2π r_max for an axisymmetric film.
        """
        if getattr(self, "body", None) is not None and self.body.kind == "axisymmetric":
            r = self.sub.geometry.x[:, 0].max(initial=0.0)
            return 2 * np.pi * self.sub.comm.allreduce(float(r), op=MPI.MAX)
        return 1.0 if self.sub.topology.dim == 1 else self.length

    def _pressure_tolerances(self):
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

    def _film_thickness(self):
        """Nodal film thickness h (mm) at the P1 pressure nodes (local, with ghosts)."""
        if self._h_expr is None:
            self._h_expr = fem.Expression(self.kin.h, self.Q.element.interpolation_points)
        h = fem.Function(self.Q)
        h.interpolate(self._h_expr)
        return h.x.array

    # -- JFO -----------------------------------------------------------------------------
    def _ds_ends(self):
        """Measure of the end points of Γ_l (the submesh's true boundary, tagged explicitly).

        In parallel the untagged ``ds`` of the facet submesh also contains the
        vertices on the partition boundary.
        """
        sub = self.sub
        ends = self.boundary_facets()
        tags = dmesh.meshtags(sub, 0, ends, np.full(len(ends), 1, dtype=np.int32))
        return ufl.Measure("ds", sub, subdomain_data=tags, subdomain_id=1,
                           metadata=self.dx.metadata())

    def _at_dofs(self, values, dofs):
        """Value of a nodal array at the first of ``dofs`` owned by some rank (all ranks)."""
        own = dofs[dofs < self.Q.dofmap.index_map.size_local]
        val = float(values[own[0]]) if len(own) else None
        return next(v for v in self.sub.comm.allgather(val) if v is not None)

    def jfo_initial_guess(self, downstream=(1.0, 0.0)):
        """Void fraction of a film that keeps its flux across the cavitated zones.

        Downstream (along ``downstream``) of the minimum film h_m the film ruptures,
        λ = max(0, 1 − h_m/h); upstream the film supplied at the inlet, (1 − λ_in)
        h_in, is advected, λ = max(0, 1 − (1 − λ_in) h_in/h) (0 for a flooded inlet
        of a converging gap); from the current film h, p left as it is.  The
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
        # λ and p share the P1 layout of the same mesh
        self.lam.x.array[:] = np.maximum(np.where(X > X_m, 1 - h_m / h, 1 - supplied / h), 0.0)
        self.lam.x.scatter_forward()

    def consistent_fluxes(self, inlet=None):
        """Volume fluxes (mm²/s) into and out of the film from the discrete residual.

        φ are the hat functions of the end nodes (``inlet``: where the flow enters,
        default the JFO inlet), R(φ) the Reynolds rows tested by them.  JFO (57),
        Couette part in divergence form, w = θ h v̄·t_S the Couette flux along S
        (:func:`tribofx.forms.ehl.couette_flux`): q_in = w(inlet) + R(φ_in),
        q_out = w(outlet) − R(φ_out); the weak form (49) carries the whole flux in
        its rows: q_in = R(φ_in), q_out = −R(φ_out).  The hat functions sum to one,
        so q_out − q_in is the sum of the interior rows: zero to solver tolerance
        for a conservative model (the penalty is not).
        """
        inlet = self._inlet if inlet is None else inlet
        if inlet is None:
            raise ValueError("consistent fluxes need the inlet (add_inlet or inlet=)")
        self.refresh()
        ends, dofs_in = self._boundary_dofs(self.Q, None), self._boundary_dofs(self.Q, inlet)
        w = np.zeros(len(self.p.x.array))
        if self.lam is not None:
            wf = fem.Function(self.Q)
            wf.interpolate(fem.Expression(ef.couette_flux(
                self.kin, ufl.min_value(self.lam, 1.0), self.T),
                self.Q.element.interpolation_points))
            w = wf.x.array
        out = []
        for dofs in (dofs_in, np.setdiff1d(ends, dofs_in)):
            phi = fem.Function(self.Q)
            phi.x.array[dofs] = 1.0
            R = self._sum(fem.form(self._reynolds(phi)[0],
                                   entity_maps=self.entity_maps() or None))
            out.append((self._at_dofs(w, dofs), R))
        return out[0][0] + out[0][1], out[1][0] - out[1][1]

    def _gather(self, data, key, everywhere):
        """Concatenate the ranks' nodal ``data`` on rank 0 (or everywhere), sorted by ``key``."""
        comm = self.sub.comm
        allp = comm.gather({k: np.asarray(v).copy() for k, v in data.items()}, root=0)
        out = None
        if comm.rank == 0:
            out = {k: np.concatenate([a[k] for a in allp]) for k in data}
            x = out[key] if out[key].ndim == 1 else out[key][:, 0]
            order = np.argsort(x, kind="stable")
            out = {k: v[order] for k, v in out.items()}
        return comm.bcast(out, root=0) if everywhere else out

    def _sum(self, form):
        return self.sub.comm.allreduce(fem.assemble_scalar(form), op=MPI.SUM)


class Film(_ReynoldsFilm):
    """Soft-EHL film on ``boundary`` of ``body`` against ``counterpart``.

    Args:
        body: the lubricated :class:`tribofx.body.Body` (affine mesh).
        boundary: name of the lubricated boundary Γ_l.
        counterpart: factory ``counterpart(V_sub)`` (e.g. :func:`tribofx.obstacles.rigid_plane`),
            called with the P1 vector space of the submesh of Γ_l.
        mu: viscosity (MPa·s).
        V_counter: velocity of the countersurface (mm/s): a vector, a ``fem.Constant``
            (e.g. driven by a continuation) or None (at rest).
        model: "finite" or "linear" (geometrically linear EHL).
        shear: Couette and Poiseuille shear tractions on the body (and the unknown g).
        supg: SUPG stabilisation of the Reynolds equation.
        cavitation: "penalty" (ε⁻¹ min(p, 0)) or "jfo" (void fraction λ, plane strain).
        eps: penalty parameter ε (MPa·s/mm); None: no cavitation term.
        p_c: pressure scale of SUPG and of the JFO complementarity (MPa).
        alpha: None (S = P(γ_l)) or α ∈ [0, 1] of the intermediate surface S_α (plane strain).
        film_scale: film thickness scale h_ref (mm) of the tolerances and row scales.
        speed_scale: speed scale U (mm/s) of the Reynolds tolerance and of the JFO flux scale.
        quadrature_degree: quadrature degree of the integrals over Γ_l.
        row_scaling: physical row scales of the film rows (see the module docstring).
        name: name of the interface (unknown names, reports).
        rtol: relative size of the stopping tolerances (see the module docstring).
    """

    CAVITATION = ("penalty", "jfo")

    def __init__(self, body, boundary, counterpart, mu, V_counter=None, model="finite",
                 shear=True, supg=True, cavitation="penalty", eps=None, p_c=1.0, alpha=None,
                 film_scale=1e-2, speed_scale=1.0, quadrature_degree=4, row_scaling=True,
                 name="film", rtol=1e-10):
        if model not in ef.MODELS:
            raise ValueError(f"unknown model {model!r}; expected one of {ef.MODELS}")
        if cavitation not in self.CAVITATION:
            raise ValueError(f"unknown cavitation model {cavitation!r}")
        gdim = body.gdim
        if (cavitation == "jfo" or alpha is not None) and gdim != 2:
            raise ValueError("cavitation='jfo' and alpha are implemented for a curve Γ_l "
                             "(gdim = 2)")
        self.body, self.name, self.rtol = body, name, float(rtol)
        self.model, self.shear, self.cavitation, self._supg = model, shear, cavitation, supg
        self.mu = float(mu)
        msh = body.mesh
        self.sub, self.emap, _ = facet_submesh(msh, body.facet_tags, body.tag(boundary),
                                               f"{body.name} {boundary}")
        sub = self.sub
        degree = body.V.ufl_element().embedded_superdegree
        self.Vs = fem.functionspace(sub, ("Lagrange", degree, (gdim,)))
        self.V1 = fem.functionspace(sub, ("Lagrange", 1, (gdim,)))
        self.Q = fem.functionspace(sub, ("Lagrange", 1))
        self.G = fem.functionspace(sub, ("DG", 0, (gdim,)))
        self.u_s = fem.Function(self.Vs, name=f"{name}_displacement_trace")
        self.p = fem.Function(self.Q, name=f"{name}_pressure")
        self.g = fem.Function(self.G, name=f"{name}_pressure_gradient") if shear else None
        self.lam = None
        if cavitation == "jfo":
            self.Ql = fem.functionspace(sub, ("Lagrange", 1))
            self.lam = fem.Function(self.Ql, name=f"{name}_void_fraction")
        self._u1 = fem.Function(self.V1)
        self._X1 = self.V1.tabulate_dof_coordinates()[:, :gdim]
        self.counterpart = counterpart(self.V1)

        # scales and physical constants
        self.h_ref, self.U_ref = float(film_scale), float(speed_scale)
        self.mu_c = fem.Constant(sub, self.mu)
        self.p_c = fem.Constant(sub, float(p_c))
        self.eps = None if eps is None else fem.Constant(sub, float(eps))
        self.alpha = None if alpha is None else fem.Constant(sub, float(alpha))
        scales = ((self.mu / self.h_ref, body.stiffness / self.h_ref, self.h_ref)
                  if row_scaling else (1.0, 1.0, 1.0))
        self._c_p, self._c_u, self._c_g = (fem.Constant(sub, c) for c in scales)
        self._q_ref = fem.Constant(sub, 0.5 * self.U_ref * self.h_ref)

        # measures and reference geometry
        qd = {"quadrature_degree": quadrature_degree}
        self.ds = ufl.Measure("ds", msh, subdomain_data=body.facet_tags,
                              subdomain_id=body.tag(boundary), metadata=qd)
        self.dx = ufl.Measure("dx", sub, metadata=qd)
        self.nodal_dx = ufl.Measure("dx", sub, metadata={"quadrature_rule": "vertex",
                                                         "quadrature_degree": 1})
        self.N = _outward_cell_normals(body, sub, self.emap, self.G)
        self.grad_gamma = ef.tangential_gradient(self.N)
        N_b = ufl.FacetNormal(msh)
        self.T = self.T_b = None
        if gdim == 2:
            self.T = ufl.as_vector([self.N[1], -self.N[0]])
            self.T_b = ufl.as_vector([N_b[1], -N_b[0]])
        X, Xs = ufl.SpatialCoordinate(msh), ufl.SpatialCoordinate(sub)
        lo = self.sub.geometry.x[:, :gdim].min(axis=0, initial=np.inf)
        hi = self.sub.geometry.x[:, :gdim].max(axis=0, initial=-np.inf)
        msh.comm.Allreduce(MPI.IN_PLACE, lo, op=MPI.MIN)
        msh.comm.Allreduce(MPI.IN_PLACE, hi, op=MPI.MAX)
        self.length = float(np.linalg.norm(hi - lo))   # diameter of Γ_l (mm)

        # kinematics of S on the bulk side (tractions) and on the submesh (Reynolds).
        # FFCx compiles a submesh form only with Constants of the submesh: the film
        # keeps submesh copies of the velocities, synchronised before every assembly
        self._mirrors = []
        V_body = self._mirror(body.velocity) if body.velocity is not None else ufl.zero(gdim)
        if V_counter is not None and not isinstance(V_counter, fem.Constant):
            V_counter = fem.Constant(sub, np.asarray(V_counter, dtype=float))
        self.V_counter = V_counter
        if V_counter is not None:
            V_counter = self._mirror(V_counter)

        def surface(x):
            return ef.countersurface_projection(self.counterpart.geometry, x)

        self.kin_bulk = ef.lubrication_kinematics(X, body.u, ufl.grad(body.u), N_b, None,
                                                  None, V_body, model, surface, self.alpha,
                                                  V_counter)
        self.kin = ef.lubrication_kinematics(Xs, self.u_s, self.grad_gamma(self.u_s), self.N,
                                             None, None, V_body, model, surface, self.alpha,
                                             V_counter)
        F = ufl.Identity(gdim) + ufl.grad(body.u)
        grad_p = self.g if shear else ufl.zero(gdim)
        self.traction = ef.fluid_traction(self.p, grad_p, self.kin_bulk, F, N_b, self.T_b,
                                          self.mu_c, shear=shear, model=model)
        self._couette = ef.fluid_traction(0.0, ufl.zero(gdim), self.kin_bulk, F, N_b,
                                          self.T_b, self.mu_c, shear=True, model=model)
        # reference measure factors: the body's (2πR) and, axisymmetric, the hoop stretch
        self.w_solid, self.w_film = body.weight, 1
        if body.kind == "axisymmetric":
            if model == "finite":
                self.w_solid = body.weight * (1 + body.u[0] / X[0])
            self.w_film = 2 * ufl.pi * self.kin.y[0]
        self._jumps = cavitation == "jfo"
        self._post = None
        self._dry = None
        self._init_rows()

    def _mirror(self, constant):
        copy = fem.Constant(self.sub, np.array(constant.value, dtype=float))
        self._mirrors.append((constant, copy))
        return copy

    def _sync(self):
        for src, dst in self._mirrors:
            dst.value = src.value

    # -- component protocol --------------------------------------------------------------
    def unknowns(self):
        """Return u_s, p (g, λ) and the counterpart's unknowns."""
        out = [self.u_s, self.p] + ([self.g] if self.g is not None else []) \
            + ([self.lam] if self.lam is not None else [])
        return out + list(self.counterpart.unknowns())

    def contributions(self):
        """Film virtual work on u; trace, Reynolds, gradient and complementarity rows."""
        body = self.body
        out = [(body.u, ef.film_virtual_work(self.traction, body.v, self.ds, self.w_solid)),
               (self.u_s, self._c_u * ef.trace_constraint(self.u_s, body.u,
                                                          ufl.TestFunction(self.Vs), self.ds))]
        R_p, C = self._reynolds(ufl.TestFunction(self.Q))
        out.append((self.p, self._c_p * R_p))
        if self.g is not None:
            out.append((self.g, self._c_g * ef.tangential_gradient_constraint(
                self.g, self.p, ufl.TestFunction(self.G), None, self.dx, self.grad_gamma)))
        if C is not None:
            out.append((self.lam, self._c_p * C))
        return out

    def entity_maps(self):
        """Return the submesh ↔ bulk entity map."""
        return [self.emap]

    def positions(self):
        """Nodal positions of Γ_l at which the counterpart is projected (P1 dof order, mm).

        Current x = X + u_s, or the reference X for ``model="linear"``.
        """
        if self.model == "linear":
            return self._X1.copy()
        self._u1.interpolate(self.u_s)
        return self._X1 + self._u1.x.array.reshape(-1, self.body.gdim)

    def refresh(self):
        """Copy the velocities; let the counterpart project the nodes of Γ_l (kernel data)."""
        self._sync()
        self.counterpart.update(self.positions())

    def tolerances(self):
        """Per-block tolerances in physical units over lumped reference measures of Γ_l."""
        if self._tol:
            return self._tol_out
        ones = ufl.as_vector([1.0] * self.body.gdim)
        self._tol["u_s"] = BlockTolerance(0.0, "mm", self._c_u * ufl.dot(
            ufl.TestFunction(self.Vs), ones) * self.dx)
        out = {self.u_s: self._tol["u_s"], **self._pressure_tolerances()}
        if self.g is not None:
            self._tol["g"] = BlockTolerance(0.0, "MPa/mm", self._c_g * ufl.dot(
                ufl.TestFunction(self.G), ones) * self.dx)
            out[self.g] = self._tol["g"]
        self._tol_out = out
        self.set_scales()
        return out

    def state_fields(self):
        """Unknowns and the counterpart's state.

        The scales p_c and ε are not part of the state: they follow the
        continuation parameters (speed, load) through :meth:`set_scales`.
        """
        return self.unknowns() + list(self.counterpart.state_fields())

    def commit(self):
        """Accept the converged step (the counterpart's history moves on)."""
        self.counterpart.commit()

    # -- outputs -------------------------------------------------------------------------
    def _forms(self):
        if self._post is None:
            em = [self.emap]
            gdim = self.body.gdim
            self._post = {
                "force": [fem.form(self.traction[i] * self.w_solid * self.ds, entity_maps=em)
                          for i in range(gdim)],
                "couette": [fem.form(self._couette[i] * self.w_solid * self.ds, entity_maps=em)
                            for i in range(gdim)],
                "y": fem.Expression(self.kin.y, self.V1.element.interpolation_points),
            }
        return self._post

    def _nodal(self, key):
        f = fem.Function(self.V1)
        f.interpolate(self._forms()[key])
        return f.x.array

    def force(self):
        """Force (N; N/mm in plane strain) of the film on the modelled part of the body."""
        self.refresh()
        return np.array([self._sum(f) for f in self._forms()["force"]])

    def couette_force(self):
        """Couette drag alone (N; N/mm): ∫ −j(μ/h)(v_layer − v_counter) dS (any ``shear``)."""
        self.refresh()
        return np.array([self._sum(f) for f in self._forms()["couette"]])

    def min_film(self):
        """Smallest nodal film thickness on Γ_l (mm, all ranks)."""
        self.refresh()
        n = self.Q.dofmap.index_map.size_local
        return self.sub.comm.allreduce(float(self._film_thickness()[:n].min(initial=np.inf)),
                                       op=MPI.MIN)

    def profile(self, everywhere=False):
        """Nodal X, x (current), y (projection), h, p (and λ) of Γ_l, sorted by X₀.

        On rank 0 (None elsewhere), or on every rank (``everywhere``).  x and y
        are P1 nodal values (the trace interpolated at the vertices).
        """
        self.refresh()
        gdim = self.body.gdim
        n = self.Q.dofmap.index_map.size_local
        # Q, V1 (and Ql) share the P1 layout of the same submesh
        self._u1.interpolate(self.u_s)
        x = self._X1 + self._u1.x.array.reshape(-1, gdim)
        d = {"X": self._X1[:n], "x": x[:n], "y": self._nodal("y").reshape(-1, gdim)[:n],
             "h": self._film_thickness()[:n].copy(), "p": self.p.x.array[:n].copy()}
        if self.lam is not None:
            d["lam"] = self.lam.x.array[:n].copy()
        return self._gather(d, "X", everywhere)

    # -- starting states -----------------------------------------------------------------
    def place_countersurface(self, h0, at):
        """Translate a rigid countersurface along its normal so that h = ``h0`` (mm) at ``at``.

        ``at`` is a reference point; the node of Γ_l nearest to it is used.  The
        counterpart must have a rigid translation ``offset`` (mm).
        """
        if not hasattr(self.counterpart, "offset"):
            raise ValueError("place_countersurface needs a rigid countersurface (offset)")
        self.refresh()
        gdim = self.body.gdim
        n = self.Q.dofmap.index_map.size_local
        h = self._film_thickness()
        nu = fem.Function(self.V1)
        # × N·N (= 1): an Expression needs a coefficient of the submesh (ν of a plane is constant)
        nu.interpolate(fem.Expression(self.kin.nu * ufl.dot(self.N, self.N),
                                      self.V1.element.interpolation_points))
        d2 = np.sum((self._X1[:n] - np.asarray(at, float)[:gdim]) ** 2, axis=1)
        i = int(np.argmin(d2)) if n else 0
        loc = (float(d2[i]) if n else np.inf,
               (float(h[i]), nu.x.array.reshape(-1, gdim)[i].copy()) if n else None)
        _, (h_c, nu_c) = min(self.body.mesh.comm.allgather(loc), key=lambda t: t[0])
        self.counterpart.offset.value[:] += (h_c - h0) * nu_c
        self.refresh()

    def start_from_pressure(self, pressure, h0, at, verbose=False):
        """Set an initial state: the body under a prescribed film pressure, film ``h0`` at ``at``.

        ``pressure`` is a callable of the reference coordinates (3, n) → p (MPa),
        e.g. the Hertz pressure; the body is solved under it as a follower load
        (:class:`PrescribedPressure`, no shear), p is set to it (g to 0) as the
        first pressure iterate and a rigid countersurface is placed so that the
        film is ``h0`` (mm) at the node nearest to ``at``.  Returns the Newton report.
        """
        from ..problem import Problem

        if self._dry is None:
            dry = PrescribedPressure(self)
            self._dry = (dry, Problem([self.body, dry], name=f"{self.name}_dry"))
        dry, problem = self._dry
        dry.p.interpolate(pressure)
        report = problem.solve(verbose=verbose)
        self.p.x.array[:] = dry.p.x.array
        if self.g is not None:
            self.g.x.array[:] = 0.0
        self.place_countersurface(h0, at)
        return report


class PrescribedPressure:
    """The lubricated boundary of a :class:`Film` under a prescribed pressure (no film).

    Component of a dry problem ``Problem([body, PrescribedPressure(film)])``: the
    pressure ``p`` (P1 on Γ_l, MPa) loads the body through the pressure part of
    the fluid traction (46) (a follower load for ``model="finite"``), and the
    film's trace u_s follows u (trace rows), so the film starts from the
    deformed state.
    """

    def __init__(self, film):
        self.film = film
        self.p = fem.Function(film.Q, name=f"{film.name}_prescribed_pressure")
        f, body = film, film.body
        gdim = body.gdim
        F = ufl.Identity(gdim) + ufl.grad(body.u)
        self.traction = ef.fluid_traction(self.p, ufl.zero(gdim), f.kin_bulk, F,
                                          ufl.FacetNormal(body.mesh), f.T_b, f.mu_c,
                                          shear=False, model=f.model)

    def unknowns(self):
        """Return the film's trace u_s."""
        return [self.film.u_s]

    def contributions(self):
        """Prescribed-pressure work on u, trace rows on u_s."""
        f, body = self.film, self.film.body
        return [(body.u, ef.film_virtual_work(self.traction, body.v, f.ds, f.w_solid)),
                (f.u_s, f._c_u * ef.trace_constraint(f.u_s, body.u, ufl.TestFunction(f.Vs),
                                                     f.ds))]

    def bcs(self):
        """Return no conditions."""
        return []

    def entity_maps(self):
        """Return the film's entity map."""
        return [self.film.emap]

    def refresh(self):
        """Nothing to refresh (the pressure part of the traction needs no countersurface)."""

    def tolerances(self):
        """Return the film's trace tolerance."""
        return {self.film.u_s: self.film.tolerances()[self.film.u_s]}

    def state_fields(self):
        """Return the prescribed pressure and the trace."""
        return [self.p, self.film.u_s]

    def commit(self):
        """Nothing to accept."""


class RigidFilm(_ReynoldsFilm):
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
        mu: viscosity (MPa·s).
        degree: Lagrange degree of p (JFO and the nodal penalty: 1).
        cavitation: "none", "penalty" or "jfo".
        supg, eps, p_c: as for :class:`Film`.
        film_scale, speed_scale: h_ref (mm), U (mm/s) of the tolerances; their
            product is the flux scale of the JFO complementarity rows.
        quadrature_degree: default 4·degree + 6 (h is not polynomial in general).
        rtol: relative size of the stopping tolerances.
    """

    CAVITATION = ("none", "penalty", "jfo")

    def __init__(self, mesh, gap, vbar, mu, degree=1, cavitation="none", supg=False, eps=None,
                 p_c=1.0, film_scale=1e-2, speed_scale=1.0, quadrature_degree=None,
                 name="film", rtol=1e-10):
        if cavitation not in self.CAVITATION:
            raise ValueError(f"unknown cavitation model {cavitation!r}")
        if cavitation == "jfo" and degree != 1:
            raise ValueError("cavitation='jfo' needs P1 pressure (nodal complementarity)")
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
        self.mu_c, self.p_c = fem.Constant(mesh, float(mu)), fem.Constant(mesh, float(p_c))
        self.eps = None
        if cavitation == "penalty":
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
    def unknowns(self):
        """Return p (and λ)."""
        return [self.p] + ([self.lam] if self.lam is not None else [])

    def contributions(self):
        """Reynolds (or JFO transport) rows on p, complementarity rows on λ."""
        R_p, C = self._reynolds(ufl.TestFunction(self.Q))
        return [(self.p, R_p)] + ([(self.lam, C)] if C is not None else [])

    def entity_maps(self):
        """Return no entity maps: the film lives on its own mesh."""
        return []

    def refresh(self):
        """Nothing computed outside UFL."""

    def tolerances(self):
        """Reynolds rows (mm/s) and complementarity rows (-) over lumped measures."""
        if not self._tol:
            self._tol_out = self._pressure_tolerances()
            self.set_scales()
        return self._tol_out

    def state_fields(self):
        """Return p (and λ)."""
        return self.unknowns()

    def commit(self):
        """Nothing to accept."""

    # -- outputs -------------------------------------------------------------------------
    def integral(self, expr, dx=None):
        """Global integral of the UFL expression ``expr`` over the film (default ``dx``)."""
        return self._sum(fem.form(expr * (dx or self.dx)))

    def profile(self, everywhere=False):
        """Nodal x, p, h (and λ) sorted by x on rank 0 (None elsewhere) or ``everywhere``."""
        n = self.Q.dofmap.index_map.size_local
        d = {"x": self.Q.tabulate_dof_coordinates()[:n, 0], "p": self.p.x.array[:n],
             "h": self.h_fun.x.array[:n]}
        if self.lam is not None:
            d["lam"] = self.lam.x.array[:n]
        return self._gather(d, "x", everywhere)

    def set_from_profile(self, prof):
        """Set p (and λ) by interpolation of a (coarser) nodal profile (dict, all ranks)."""
        for fun, key in ((self.p, "p"), (self.lam, "lam")):
            if fun is not None:
                xs = fun.function_space.tabulate_dof_coordinates()[:, 0]
                fun.x.array[:] = np.interp(xs, prof["x"], prof[key])

"""Reciprocating O-ring seal: axisymmetric soft EHL with housing contact (chapter §8.1).

The O-ring cross-section (Mooney–Rivlin, axisymmetric about the rod axis z; air
side z > 0, sealed side z < 0) is squeezed between the rigid housing and the
rigid rod r = r_rod:

* housing: groove bottom r = r_g and air-side wall z = z_w, rigid planes with
  frictionless augmented-Lagrangian contact (:mod:`forms.contact`), nodal
  multipliers λ_b, λ_w on the facet submesh of the non-lubricated boundary
  (SEALED ∪ HOUSING arcs of :mod:`meshes.oring`); the sealed-side wall is left
  open, p_s pushes the ring against the air-side wall;
* sealed pressure p_s: follower pressure on the SEALED arc (the quarter of the
  boundary facing the sealed side, 225° ≤ φ ≤ 315°) and the Dirichlet value of
  the film pressure at the sealed-side end of Γ_l (so that the fluid at p_s
  also loads the sealed-side flank of Γ_l through the film traction);
* rod (``dry=False``): soft-EHL film on the lubricated arc Γ_l
  (:mod:`forms.ehl_axisym`), unknowns as in
  :class:`tribofx.ehl_problem.EHLProblem`: trace u_s, P1 pressure p, DG0
  tangential pressure derivative g; p = p_s at the sealed-side end, p = 0 at the
  air-side end, penalty cavitation, SUPG;
* rod (``dry=True``): frictionless contact with the rod instead of the film,
  multipliers λ_r at the nodes of u on Γ_l, p_s on the sealed half of Γ_l where
  it is open (a dry reference; its nodal pressure is too rough on P1 meshes for
  Blok's inverse theory, :func:`tribofx.references.inverse_film`, so no test
  relies on it).

Mounting (:meth:`ORingProblem.mount`): the ring starts clear of the rod by
``gap0`` and touching the groove bottom and the air-side wall; the groove bottom
is moved to r_g in steps (squeeze), with the film (or the dry contact) active,
at a small sealed pressure; then p_s is raised (:meth:`ORingProblem.ramp`).
Continuation steps are cut on Newton failure and the last converged state is
kept.  Units: mm, N, s, MPa.
"""

import math

import numpy as np
import ufl
from dolfinx import fem, la
from dolfinx import mesh as dmesh
from dolfinx.la.petsc import _ghost_update
from mpi4py import MPI
from petsc4py import PETSc

from .forms import contact as cf
from .forms import ehl as ef
from .forms import ehl_axisym as ax
from .forms import hyperelastic as hf
from .forms import kinematics as km
from .meshes.oring import HOUSING, LUBRICATED, SEALED
from .newton import BlockNewton, NewtonDivergence
from .submesh import facet_submesh

__all__ = ["ORingProblem", "oscillation_indicator"]

_CONTACT = 99


class ORingProblem:
    """O-ring cross-section ``msh`` between a rigid rod and a rigid housing groove.

    Args:
        msh, cell_tags, facet_tags: mesh of :func:`meshes.oring.oring_section`.
        center, a: centre (r_c, z_c) and radius of the cross-section (mm).
        r_rod: rod radius (mm).  r_g: groove bottom radius after mounting (mm).
        z_w: air-side groove wall (mm).
        mat: Mooney–Rivlin parameters {"mu1", "mu2", "kappa"} (MPa).
        mu: viscosity (MPa·s).  U: rod speed (mm/s, > 0 outstroke).
        p_s: sealed pressure (MPa).
        h_ref: film scale (mm) of the row scaling and of the penalty.
        eps_rel: cavitation penalty ε = eps_rel · 12μℓ²/h_ref³, ℓ = a/4 (MPa·s/mm).
        supg: SUPG in the Reynolds equation.  degree: Lagrange degree of u (1, 2).
        rho_n: augmentation of the contacts (MPa/mm), default E/a.
        dry: dry frictionless rod contact instead of the film.
        r_g0: initial groove bottom (mm), default the touching position.
    """

    def __init__(self, msh, cell_tags, facet_tags, center, a, r_rod, r_g, z_w, mat, mu, U,
                 p_s, h_ref, eps_rel=1e-4, supg=True, degree=2, rho_n=None, dry=False,
                 r_g0=None):
        if degree not in (1, 2):
            raise ValueError("degree must be 1 or 2")
        self.mesh, self.a, self.center = msh, float(a), tuple(map(float, center))
        self.r_rod, self.mu, self.degree, self.dry = float(r_rod), float(mu), degree, dry
        self.r_g_target = float(r_g)
        E = 3 * (mat["mu1"] + mat["mu2"])
        rho_n = rho_n if rho_n is not None else E / a
        self.sub, self.emap, _ = facet_submesh(msh, facet_tags, LUBRICATED, "lubricated arc")
        cf_idx = np.sort(np.concatenate([facet_tags.find(SEALED), facet_tags.find(HOUSING)]))
        ctags = dmesh.meshtags(msh, 1, cf_idx.astype(np.int32),
                               np.full(len(cf_idx), _CONTACT, dtype=np.int32))
        self.csub, self.cmap, _ = facet_submesh(msh, ctags, _CONTACT, "housing arc")
        sub = self.sub
        self.V = fem.functionspace(msh, ("Lagrange", degree, (2,)))
        self.Vs = fem.functionspace(sub, ("Lagrange", degree, (2,)))
        self.Q = fem.functionspace(sub, ("Lagrange", 1))
        self.G = fem.functionspace(sub, ("DG", 0))
        self.Qc = fem.functionspace(self.csub, ("Lagrange", 1))
        self.Qr = fem.functionspace(sub, ("Lagrange", degree))
        self.u = fem.Function(self.V, name="displacement")
        self.u_s = fem.Function(self.Vs, name="displacement_trace")
        self.p = fem.Function(self.Q, name="film_pressure")
        self.g = fem.Function(self.G, name="pressure_tangential_derivative")
        self.lam_b = fem.Function(self.Qc, name="groove_bottom_traction")
        self.lam_w = fem.Function(self.Qc, name="air_wall_traction")
        self.lam_r = fem.Function(self.Qr, name="dry_rod_traction")

        r_g0 = float(center[0] + a) - 1e-3 * a if r_g0 is None else float(r_g0)
        self.r_g = fem.Constant(msh, r_g0)
        self.z_w = fem.Constant(msh, float(z_w))
        self.p_s = fem.Constant(msh, float(p_s))
        self.p_s_sub = fem.Constant(sub, float(p_s))
        self.U = float(U)
        self.U_c = fem.Constant(msh, self.U)
        self.U_s = fem.Constant(sub, self.U)
        mu_b, mu_s = fem.Constant(msh, self.mu), fem.Constant(sub, self.mu)
        self.h_ref = float(h_ref)
        ell_p = 0.25 * self.a
        self.eps = fem.Constant(sub, eps_rel * 12 * self.mu * ell_p**2 / self.h_ref**3)
        self.p_c = fem.Constant(sub, max(float(p_s), 1.0))

        qd = {"quadrature_degree": 2 * degree}
        dx = ufl.Measure("dx", msh, metadata=qd)
        ds = ufl.Measure("ds", msh, subdomain_data=facet_tags, metadata={"quadrature_degree": 4})
        self.ds_l, self.ds_sealed = ds(LUBRICATED), ds(SEALED)
        vertex = {"quadrature_rule": "vertex", "quadrature_degree": 1}
        # nodal contact on the housing; on Γ_l collocated at all nodes of u (P2: Simpson)
        dsc = ufl.Measure("ds", msh, subdomain_data=facet_tags, subdomain_id=(SEALED, HOUSING),
                          metadata=vertex)
        nodes_u = vertex if degree == 1 else {"quadrature_rule": "GLL", "quadrature_degree": 3}
        dsr = ufl.Measure("ds", msh, subdomain_data=facet_tags, subdomain_id=LUBRICATED,
                          metadata=nodes_u)
        self.dx_s = ufl.Measure("dx", sub, metadata={"quadrature_degree": 4})
        nodal = ufl.Measure("dx", sub, metadata=vertex)
        X = ufl.SpatialCoordinate(msh)
        Xs = ufl.SpatialCoordinate(sub)
        w = 2 * ufl.pi * X[0]
        self._w = w
        v = ufl.TestFunction(self.V)
        x = X + self.u
        c0 = ufl.as_vector(self.center)
        Nb = ufl.FacetNormal(msh)

        # solid: internal work (7), p_s on the SEALED arc, housing contact (8)
        R_u = hf.internal_virtual_work(self.u, v, "axisymmetric", "mooney-rivlin", mat, dx)
        self.t_sealed = ax.follower_pressure_traction(self.p_s, self.u, Nb)
        R_u -= hf.external_virtual_work(self.t_sealed, v, "axisymmetric", self.ds_sealed)
        mb, mw = ufl.TestFunction(self.Qc), ufl.TestFunction(self.Qc)
        self.geo_b = cf.plane_countersurface(x, ufl.as_vector([self.r_g, 0.0]),
                                             ufl.as_vector([-1.0, 0.0]))
        self.geo_w = cf.plane_countersurface(x, ufl.as_vector([0.0, self.z_w]),
                                             ufl.as_vector([0.0, -1.0]))
        Rb_u, Rb, _ = cf.augmented_lagrangian_contact(self.u, v, self.geo_b, self.lam_b, mb,
                                                      rho_n, dsc, weight=w)
        Rw_u, Rw, _ = cf.augmented_lagrangian_contact(self.u, v, self.geo_w, self.lam_w, mw,
                                                      rho_n, dsc, weight=w)
        R_u += Rb_u + Rw_u
        self.rho_n = rho_n

        # film: kinematics on the bulk (tractions) and on the submesh (Reynolds)
        Ns = ax.manifold_normal(sub, (Xs - c0) / self.a)
        Ts = ufl.as_vector([Ns[1], -Ns[0]])
        Tb = ufl.as_vector([Nb[1], -Nb[0]])       # same orientation as Ts (both outward N)
        PN = ufl.Identity(2) - ufl.outer(Ns, Ns)

        def grad_gamma(f):
            """Tangential gradient on Γ_l (projected: grad X = I on the manifold)."""
            gr = ufl.grad(f)
            return PN * gr if len(gr.ufl_shape) == 1 else gr * PN

        self.kin_bulk = ax.rod_kinematics(X, self.u, ufl.grad(self.u), Nb, self.r_rod, self.U_c)
        self.kin_sub = ax.rod_kinematics(Xs, self.u_s, ufl.grad(self.u_s), Ns, self.r_rod,
                                         self.U_s)
        self.traction = ax.axisymmetric_fluid_traction(self.p, self.g, self.kin_bulk, self.u, Nb,
                                                       Tb, mu_b)
        dus = ufl.TestFunction(self.Vs)
        self._trace_form = ef.trace_constraint(self.u_s, self.u, dus, self.ds_l)
        if dry:
            mr = ufl.TestFunction(self.Qr)
            self.geo_r = cf.plane_countersurface(x, ufl.as_vector([self.r_rod, 0.0]),
                                                 ufl.as_vector([1.0, 0.0]))
            Rr_u, Rr, _ = cf.augmented_lagrangian_contact(self.u, v, self.geo_r, self.lam_r, mr,
                                                          rho_n, dsr, weight=w)
            # p_s on the sealed half of Γ_l where the gap is open (ramp over 0.02a)
            open_frac = ufl.max_value(ufl.min_value(self.geo_r.gap / (0.02 * self.a), 1.0), 0.0)
            sealed_half = ufl.conditional(ufl.lt(X[1], self.center[1]), 1.0, 0.0)
            t_l = ax.follower_pressure_traction(self.p_s * open_frac * sealed_half, self.u, Nb)
            R_u += Rr_u - hf.external_virtual_work(t_l, v, "axisymmetric", self.ds_l)
            self.unknowns = [self.u, self.lam_b, self.lam_w, self.lam_r]
            self.residuals = [R_u, Rb, Rw, Rr]
            self.bcs = []
            self.solver = BlockNewton(self.residuals, self.unknowns,
                                      entity_maps=[self.emap, self.cmap], rtol=1e-10,
                                      atol=1e-8, max_it=30, max_backtracks=0)
            jr = km.area_ratio(km.deformation_gradient(self.u, "axisymmetric"), Nb,
                               "axisymmetric")
            mq = ufl.TestFunction(self.Qr)
            self._lumped_j = fem.form(jr * mq * dsr, entity_maps=[self.emap])
            self._lumped = fem.form(mq * dsr, entity_maps=[self.emap])
        else:
            R_u -= hf.external_virtual_work(self.traction, v, "axisymmetric", self.ds_l)
            # row scales (N): Δp over ℓ changes the flux by h³Δp/(12μℓ) and the load
            # by Δp ℓ, hence c_p = 12μℓ²/h_ref³; trace rows E·2πR_c; g rows 2πR_c·h_ref
            Rc = 2 * math.pi * self.center[0]
            self._c_p = fem.Constant(sub, 12 * self.mu * ell_p**2 / self.h_ref**3 * Rc
                                     / (2 * math.pi * self.r_rod))
            c_u = fem.Constant(msh, Rc * E)
            c_g = fem.Constant(sub, Rc * self.h_ref)
            dp, dg = ufl.TestFunction(self.Q), ufl.TestFunction(self.G)
            R_us = c_u * self._trace_form
            R_p = self._c_p * ax.reynolds_on_rod(
                self.p, dp, self.kin_sub, mu_s, self.dx_s, self.r_rod, eps=self.eps, supg=supg,
                p_c=self.p_c, h_e=ufl.CellDiameter(sub), nodal_dx=nodal, grad_gamma=grad_gamma)
            R_g = c_g * ef.tangential_gradient_constraint(self.g, self.p, dg, Ts, self.dx_s)
            self.unknowns = [self.u, self.u_s, self.p, self.g, self.lam_b, self.lam_w]
            self.residuals = [R_u, R_us, R_p, R_g, Rb, Rw]
            # p = p_s at the sealed-side end of Γ_l, p = 0 at the air-side end
            zs = sub.geometry.x[:, 1]
            z_lo = msh.comm.allreduce(float(zs.min(initial=np.inf)), op=MPI.MIN)
            z_hi = msh.comm.allreduce(float(zs.max(initial=-np.inf)), op=MPI.MAX)
            tol = 1e-8 * self.a
            lo = fem.locate_dofs_geometrical(self.Q, lambda y: np.isclose(y[1], z_lo, atol=tol))
            hi = fem.locate_dofs_geometrical(self.Q, lambda y: np.isclose(y[1], z_hi, atol=tol))
            self.bcs = [fem.dirichletbc(self.p_s_sub, lo, self.Q),
                        fem.dirichletbc(fem.Constant(sub, 0.0), hi, self.Q)]
            Xq = self.Q.tabulate_dof_coordinates()
            self.p.x.array[:] = np.where(Xq[:, 1] < self.center[1], float(p_s), 0.0)
            # atol 1e-8 of the force scale E·2πR_c·a² (≈ 2e-5 N, 1e-7 of the housing
            # reaction): the Reynolds rows of the thick-film flanks reach their
            # round-off floor at 1e-7…1e-5 N depending on the mesh
            self.atol = 1e-8 * E * Rc * self.a**2
            self.solver = _FilmNewton(self, self.residuals, self.unknowns, bcs=self.bcs,
                                      entity_maps=[self.emap, self.cmap], rtol=1e-10,
                                      atol=self.atol, max_it=40, max_backtracks=10)
        self._trace_solver = None
        self.iterations = []

        # post-processing
        self._flux_expr = fem.Expression(ax.film_flux(self.kin_sub, self.p, mu_s, grad_gamma),
                                         self.G.element.interpolation_points)
        self._h_expr = fem.Expression(self.kin_sub.h, self.Q.element.interpolation_points)
        self._zq_expr = fem.Expression((Xs + self.u_s)[1], self.Q.element.interpolation_points)
        self._zc_expr = fem.Expression((Xs + self.u_s)[1], self.G.element.interpolation_points)
        er, ez = ufl.as_vector([1.0, 0.0]), ufl.as_vector([0.0, 1.0])
        tn_b, _ = cf.contact_tractions(self.geo_b, self.lam_b, rho_n)
        tn_w, _ = cf.contact_tractions(self.geo_w, self.lam_w, rho_n)
        self._forms = {
            "film": [fem.form(ufl.dot(self.traction, e) * w * self.ds_l, entity_maps=[self.emap])
                     for e in (er, ez)],
            "sealed": [fem.form(ufl.dot(self.t_sealed, e) * w * self.ds_sealed) for e in (er, ez)],
            "bottom": [fem.form(-tn_b * ufl.dot(self.geo_b.normal, e) * w * dsc,
                                entity_maps=[self.cmap]) for e in (er, ez)],
            "wall": [fem.form(-tn_w * ufl.dot(self.geo_w.normal, e) * w * dsc,
                              entity_maps=[self.cmap]) for e in (er, ez)],
        }

    # -- solving ---------------------------------------------------------------
    @property
    def num_dofs(self):
        """Global number of unknowns."""
        return self.solver.num_dofs

    def solve(self, verbose=False):
        """Newton solve at the current parameters; returns the NewtonReport."""
        rep = self.solver.solve(verbose=verbose)
        self.iterations.append(rep.iterations)
        return rep

    def state(self):
        """Copy of all fields and of the continuation parameters (step cutting)."""
        fields = [self.u, self.u_s, self.p, self.g, self.lam_b, self.lam_w, self.lam_r]
        return ([f.x.array.copy() for f in fields]
                + [float(c.value) for c in (self.r_g, self.p_s, self.U_c)])

    def restore(self, st):
        """Restore a :meth:`state`."""
        fields = [self.u, self.u_s, self.p, self.g, self.lam_b, self.lam_w, self.lam_r]
        for f, a in zip(fields, st):
            f.x.array[:] = a
        r_g, p_s, U = st[len(fields):]
        self.r_g.value = r_g
        self.set_pressure(p_s)
        self.set_speed(U)

    def set_pressure(self, p_s):
        """Sealed pressure p_s (MPa) on the SEALED arc and at the sealed end of the film."""
        self.p_s.value = float(p_s)
        self.p_s_sub.value = float(p_s)

    def set_speed(self, U):
        """Rod speed U (mm/s), signed (> 0 outstroke)."""
        self.U = float(U)
        self.U_c.value = self.U
        self.U_s.value = self.U

    def continuation(self, setter, start, end, steps, on_step=None, max_cuts=10, verbose=False,
                     geometric=False):
        """Move a parameter from ``start`` to ``end`` in ``steps`` increments with step cutting.

        ``setter(value)`` applies the parameter (``geometric``: steps in log scale,
        same sign).  A failed increment restores the last converged state and
        halves the increment, a converged one doubles it again (at most 1/steps);
        after ``max_cuts`` net cuts the :class:`NewtonDivergence` is re-raised with
        the problem at its last converged state.  Returns the Newton iterations.
        """
        if geometric:
            f0, f1 = math.log(abs(start)), math.log(abs(end))
            sgn = math.copysign(1.0, end)

            def val(t):
                return end if t >= 1 else sgn * math.exp(f0 + t * (f1 - f0))
        else:
            def val(t):
                return end if t >= 1 else start + t * (end - start)
        its = []
        t, dt, cuts = 0.0, 1.0 / steps, 0
        while t < 1 - 1e-12:
            tn = min(1.0, t + dt)
            saved = self.state()
            setter(val(tn))
            try:
                rep = self.solve(verbose=verbose)
            except NewtonDivergence as err:
                self.restore(saved)
                setter(val(t))
                cuts += 1
                if cuts > max_cuts:
                    err.problem = self
                    raise
                dt *= 0.5
                continue
            its.append(rep.iterations)
            t = tn
            cuts = max(0, cuts - 1)
            dt = min(1.0 / steps, 2 * dt)
            if on_step is not None:
                on_step(val(t), rep)
        return its

    def mount(self, steps=10, verbose=False, on_step=None):
        """Squeeze: move the groove bottom from its initial position to r_g (Newton its).

        With the film, the Reynolds equation is first solved alone on the
        initial geometry (the coupled Newton then starts from a film pressure
        consistent with the gap).
        """
        its = []
        if not self.dry:
            self._trace()
            frozen = BlockNewton([self.residuals[2]], [self.p], bcs=self.bcs,
                                 entity_maps=[self.emap], rtol=1e-10, atol=self.atol,
                                 max_it=30)
            its.append(frozen.solve(verbose=verbose).iterations)
        its.append(self.solve(verbose=verbose).iterations)

        def set_r(r):
            self.r_g.value = r
        return its + self.continuation(set_r, float(self.r_g.value), self.r_g_target, steps,
                                       verbose=verbose, on_step=on_step)

    def ramp(self, p_s, steps=4, verbose=False, on_step=None):
        """Raise (or lower) the sealed pressure to ``p_s`` (MPa) in steps (Newton its)."""
        return self.continuation(self.set_pressure, float(self.p_s.value), p_s, steps,
                                 verbose=verbose, on_step=on_step)

    def speed(self, U, steps=4, verbose=False, on_step=None):
        """Move the rod speed geometrically to ``U`` (same sign) in steps (Newton its)."""
        return self.continuation(self.set_speed, self.U, U, steps, verbose=verbose,
                                 on_step=on_step, geometric=True)

    # -- results -----------------------------------------------------------------
    def _trace(self):
        """Set u_s to the trace of u on Γ_l (one Newton step of the linear L2 projection)."""
        if self._trace_solver is None:
            self._trace_solver = BlockNewton([self._trace_form], [self.u_s],
                                             entity_maps=[self.emap], rtol=1e-12, atol=1e-14,
                                             max_it=3, max_backtracks=0)
        self._trace_solver.solve()

    def _nodal(self, form):
        vec = fem.assemble_vector(form)
        vec.scatter_reverse(la.InsertMode.add)
        vec.scatter_forward()
        return vec.array.copy()

    def _gather(self, d, key):
        allp = self.mesh.comm.gather(d, root=0)
        if self.mesh.comm.rank != 0:
            return None
        out = {k: np.concatenate([a[k] for a in allp]) for k in d}
        order = np.argsort(out[key])
        return {k: v[order] for k, v in out.items()}

    def dry_profile(self):
        """Dry mode: current z and Cauchy rod-contact pressure −λ_r/j at the nodes (rank 0)."""
        if not self.dry:
            raise ValueError("dry_profile needs dry=True")
        wl = self._nodal(self._lumped)
        wj = self._nodal(self._lumped_j)
        j = np.divide(wj, wl, out=np.ones_like(wl), where=wl > 0)
        self._trace()
        n = self.Qr.dofmap.index_map.size_local
        Z = self.Qr.tabulate_dof_coordinates()[:n, 1]
        z = Z + self.u_s.x.array[1::2][:n]          # Vs and Qr share the dof layout
        return self._gather({"z": z, "p": (-self.lam_r.x.array / j)[:n]}, "z")

    def dry_inlet_gradient(self, U):
        """Dry mode: max |dp/dz| (MPa/mm) on the inlet side of the peak for the speed U.

        Inlet: the sealed side (below the peak) for U > 0, the air side for U < 0.
        """
        d = self.dry_profile()
        out = None
        if d is not None:
            z, p = d["z"], d["p"]
            gp = np.diff(p) / np.diff(z)
            zm = 0.5 * (z[1:] + z[:-1])
            zk = z[int(np.argmax(p))]
            side = zm < zk if U > 0 else zm > zk
            out = float(np.max(np.abs(gp[side])))
        return self.mesh.comm.bcast(out, root=0)

    def profile(self):
        """Film data on rank 0 (None elsewhere), sorted by the current axial position.

        Nodal: z (current axial position = position on the rod, mm), h (mm), p (MPa);
        cellwise: z_cell, q (flux per unit circumference, mm²/s).
        """
        if self.dry:
            raise ValueError("profile needs the film (dry=False)")
        h = fem.Function(self.Q)
        h.interpolate(self._h_expr)
        z = fem.Function(self.Q)
        z.interpolate(self._zq_expr)
        n = self.Q.dofmap.index_map.size_local
        nodal = self._gather({"z": z.x.array[:n], "h": h.x.array[:n], "p": self.p.x.array[:n]},
                             "z")
        q = fem.Function(self.G)
        q.interpolate(self._flux_expr)
        zc = fem.Function(self.G)
        zc.interpolate(self._zc_expr)
        nc = self.G.dofmap.index_map.size_local
        cell = self._gather({"z_cell": zc.x.array[:nc], "q": q.x.array[:nc]}, "z_cell")
        if nodal is not None:
            nodal.update(cell)
        return nodal

    def forces(self):
        """Return the r, z forces (N, whole circumference) on the ring: film, p_s, bottom, wall."""
        comm = self.mesh.comm
        return {k: np.array([comm.allreduce(fem.assemble_scalar(f), op=MPI.SUM) for f in fs])
                for k, fs in self._forms.items()}

    def sealed_arc_radii(self):
        """Return the current radii r (mm) of the two end points of the SEALED arc.

        End points φ = −135° (first) and φ = −45° (second) of the cross-section.
        """
        out = []
        n = self.V.dofmap.index_map.size_local
        X = self.V.tabulate_dof_coordinates()
        for t in (math.radians(-135), math.radians(-45)):
            pt = np.array(self.center) + self.a * np.array([math.cos(t), math.sin(t)])
            k = np.nonzero(np.linalg.norm(X[:n, :2] - pt, axis=1) < 1e-6 * self.a)[0]
            val = float(X[k[0], 0] + self.u.x.array[2 * k[0]]) if len(k) else None
            out.append(next(v for v in self.mesh.comm.allgather(val) if v is not None))
        return out

    def measures(self):
        """Film measures on all ranks (see the keys)."""
        prof = self.profile()
        res = None
        if self.mesh.comm.rank == 0:
            z, h, p = prof["z"], prof["h"], prof["p"]
            k, i = int(np.argmax(p)), int(np.argmin(h))
            ps = float(self.p_s.value)
            thr = ps + 0.5 * (p[k] - ps)      # loaded zone: half the rise above p_s
            zone = flux_zone(prof, thr)
            qz = prof["q"][zone]
            res = {"p_max": float(p[k]), "z_p_max": float(z[k]), "h_at_p_max": float(h[k]),
                   "h_min": float(h[i]), "z_h_min": float(z[i]),
                   "h_mean": float(np.mean(h[p > thr])),
                   "flux": float(np.median(qz)),
                   "flux_spread": float((qz.max() - qz.min()) / abs(np.median(qz))),
                   "oscillation": oscillation_indicator(h, p, thr)}
        res = self.mesh.comm.bcast(res, root=0)
        f = self.forces()
        res["load_per_circumference"] = float(f["film"][0]) / (2 * math.pi * self.r_rod)
        res["friction_force_per_circumference"] = float(f["film"][1]) / (2 * math.pi
                                                                         * self.r_rod)
        res["leakage"] = 2 * math.pi * self.r_rod * res["flux"]
        return res


def flux_zone(prof, threshold):
    """Cells strictly inside the nodes with p > threshold (the loaded, uncavitated film)."""
    z, p = prof["z"], prof["p"]
    hot = z[p > threshold]
    zc = prof["z_cell"]
    return (zc > hot.min()) & (zc < hot.max())


class _FilmNewton(BlockNewton):
    """BlockNewton whose line search only keeps the film open (h > 0 at every node of u_s).

    ‖R‖ is a poor merit function here: the Reynolds rows of the thick-film flanks
    of Γ_l (h up to 10³ times the film in the contact) carry fluxes far above
    those of the contact zone and react to every motion of the seal, so an Armijo
    test on ‖R‖ stalls at tiny steps.  The full Newton step is taken unless it
    closes the film (h ≤ 0 at a node, where h³ of the Reynolds equation changes
    sign) or gives a non-finite residual; then it is halved.
    """

    def __init__(self, prob, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._prob = prob
        self._r0 = prob.Vs.tabulate_dof_coordinates()[:, 0]

    def _residual(self):
        r = super()._residual()
        prob = self._prob
        h = self._r0 + prob.u_s.x.array[0::2] - prob.r_rod
        hmin = prob.mesh.comm.allreduce(float(h.min(initial=np.inf)), op=MPI.MIN)
        return r if hmin > 0 else np.inf

    def _line_search(self, r):
        x0 = self.x.copy()
        alpha = 1.0
        for _ in range(self.max_backtracks + 1):
            self.x.waxpy(-alpha, self.dx, x0)
            _ghost_update(self.x, PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
            if np.isfinite(self._residual()):
                break
            alpha *= 0.5
        x0.destroy()


def oscillation_indicator(h, p, threshold):
    """Spurious-oscillation (zigzag) amplitude of the film in the loaded zone p > threshold.

    mean |h_{i+1} − 2h_i + h_{i−1}| / (4 mean h) over the nodes of the zone (sorted
    by z): a nodal zigzag ±δ gives δ/h̄, a smooth film O((Δz)² h''/h̄) → 0 with
    refinement.
    """
    hz = h[p > threshold]
    if len(hz) < 3:
        return 0.0
    return float(np.mean(np.abs(np.diff(hz, 2))) / (4 * np.mean(hz)))

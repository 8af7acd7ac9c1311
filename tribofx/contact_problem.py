"""A hyperelastic body in frictional contact with a rigid countersurface.

Assembles the residual from ``forms`` (internal work, prescribed tractions,
Alart–Curnier contact with multipliers on the contact facet submesh), solves it
with :class:`tribofx.newton.BlockNewton`, and post-processes nodal contact
pressures, contact forces and contact sizes.  Units: mm, N, MPa.
"""

from dataclasses import dataclass

import numpy as np
import ufl
from dolfinx import fem, la
from dolfinx.cpp import mesh as _cpp_mesh
from mpi4py import MPI

from .forms import contact as cf
from .forms import hyperelastic as hf
from .forms import kinematics as kin
from .newton import BlockNewton
from .submesh import facet_submesh

__all__ = ["ContactProblem", "ContactSettings"]


@dataclass
class ContactSettings:
    """Numerical and physical settings of the contact treatment.

    Attributes:
        rho_n: normal augmentation parameter (MPa/mm).
        friction: Coulomb coefficient μ (0: frictionless, no tangential multiplier).
        rho_t: tangential augmentation parameter (MPa per unit of slip measure).
        slip: "lagrangian" (slip increment of the projection point per step) or
            "eulerian" (steady sliding, v = F V, eq. 26).
        V: background velocity of the body for eulerian slip (mm/s).
        V_master: velocity of the countersurface (mm/s).
        dtau: pseudo-time scale turning slip velocity into slip (s).
    """

    rho_n: float
    friction: float = 0.0
    rho_t: float | None = None
    slip: str = "lagrangian"
    V: tuple | None = None
    V_master: tuple | None = None
    dtau: float = 1.0


def _node_to_dof(V):
    """Map geometry-node index → block dof of a Lagrange space on a P1-geometry mesh."""
    msh = V.mesh
    xdm = msh.geometry.dofmaps[0]
    nv = _cpp_mesh.cell_num_vertices(msh.topology.cell_type)
    if xdm.shape[1] != nv:
        raise ValueError("contact requires an affine (P1) geometry of the contact body")
    out = np.full(msh.geometry.x.shape[0], -1, dtype=np.int64)
    out[xdm.ravel()] = V.dofmap.list[:, :nv].ravel()
    return out


class ContactProblem:
    """Body ``msh`` with contact boundary ``facet_tags == contact_tag`` against ``obstacle``.

    Args:
        msh, facet_tags: bulk mesh (affine geometry) and its facet tags.
        contact_tag: tag of the potential contact surface Γ_c (slave).
        kind: "3d", "plane_strain" or "axisymmetric".
        material, mat_params: strain energy (see :mod:`tribofx.forms.hyperelastic`).
        obstacle_factory: callable(mesh, V_sub) → obstacle (analytic or meshed).
        settings: :class:`ContactSettings`.
        degree: Lagrange degree of the displacement.
        quadrature_degree: volume quadrature degree.
    """

    def __init__(self, msh, facet_tags, contact_tag, kind, material, mat_params,
                 obstacle_factory, settings, degree=1, quadrature_degree=None):
        self.mesh, self.facet_tags, self.kind = msh, facet_tags, kind
        self.settings = settings
        gdim = msh.geometry.dim
        self.sub, self.emap, gmap = facet_submesh(msh, facet_tags, contact_tag,
                                                  "contact surface")
        self.V = fem.functionspace(msh, ("Lagrange", degree, (gdim,)))
        self.Vs = fem.functionspace(self.sub, ("Lagrange", 1, (gdim,)))
        self.Q = fem.functionspace(self.sub, ("Lagrange", 1))
        self.u = fem.Function(self.V, name="displacement")
        self.lam_n = fem.Function(self.Q, name="contact_pressure_nominal")
        self.u_sub = fem.Function(self.Vs, name="u_contact")
        self.xbar_n = fem.Function(self.Vs, name="projection_at_last_step")
        # trace map: submesh P1 dof -> bulk dof (vertex values of u)
        bulk = _node_to_dof(self.V)
        subm = _node_to_dof(self.Vs)
        nsub = self.sub.geometry.x.shape[0]
        self._sub_dofs = subm[np.arange(nsub)]
        self._bulk_dofs = bulk[gmap[np.arange(nsub)]]
        self._X_sub = np.zeros((len(self.u_sub.x.array) // gdim, gdim))
        self._X_sub[self._sub_dofs] = self.sub.geometry.x[:, :gdim]
        self.obstacle = obstacle_factory(msh, self.Vs)

        qd = {} if quadrature_degree is None else {"quadrature_degree": quadrature_degree}
        self.dx = ufl.Measure("dx", msh, metadata=qd)
        self.ds = ufl.Measure("ds", msh, subdomain_data=facet_tags)
        # nodal (vertex-quadrature) contact: multipliers collocated at slave nodes
        self.dsc = ufl.Measure("ds", msh, subdomain_data=facet_tags, subdomain_id=contact_tag,
                               metadata={"quadrature_rule": "vertex", "quadrature_degree": 1})
        self.weight = kin.reference_volume_factor(msh, kind)
        v = ufl.TestFunction(self.V)
        mu_n = ufl.TestFunction(self.Q)
        self.x = kin.spatial_position(self.u)
        self.geometry = self.obstacle.geometry(self.x)
        self.unknowns = [self.u, self.lam_n]
        self.lam_t, slip, mu_t = None, None, None
        if settings.friction > 0:
            self.lam_t = fem.Function(self.Vs, name="friction_traction_nominal")
            mu_t = ufl.TestFunction(self.Vs)
            self.unknowns.append(self.lam_t)
            if settings.slip == "eulerian":
                slip = cf.eulerian_slip(self.u, self.geometry, ufl.as_vector(settings.V),
                                        ufl.as_vector(settings.V_master), settings.dtau)
            else:
                # material point of the rigid master hit at the last converged step,
                # carried along by the rigid translation of the obstacle since then
                self.offset_n = fem.Constant(self.sub, self.obstacle.offset.value.copy())
                xbar_old = self.xbar_n + self.obstacle.offset - self.offset_n
                slip = cf.lagrangian_slip(self.geometry, xbar_old)
        self.slip = slip
        rho_t = settings.rho_t if settings.rho_t is not None else settings.rho_n
        self._contact_args = dict(rho_n=settings.rho_n, lam_t=self.lam_t, rho_t=rho_t,
                                  slip=slip, mu=settings.friction)
        R_u, R_n, R_t = cf.augmented_lagrangian_contact(
            self.u, v, self.geometry, self.lam_n, mu_n, settings.rho_n, self.dsc,
            self.lam_t, mu_t, rho_t, slip, settings.friction, weight=self.weight)
        self.R_u = hf.internal_virtual_work(self.u, v, kind, material, mat_params, self.dx) + R_u
        self._v = v
        self.residuals = [self.R_u, R_n] + ([R_t] if R_t is not None else [])
        self.bcs = []
        self.solver = None
        x_sub = ufl.SpatialCoordinate(self.sub) + self.u_sub
        self._xbar_expr = fem.Expression(self.obstacle.geometry(x_sub).projection,
                                         self.Vs.element.interpolation_points)
        self.commit()

    # -- set-up -------------------------------------------------------------
    def add_traction(self, tag, traction):
        """Add a prescribed nominal traction (UFL vector, MPa) on facets ``tag``."""
        self.R_u = self.R_u - hf.external_virtual_work(traction, self._v, self.kind, self.ds(tag))
        self.residuals[0] = self.R_u

    def add_dirichlet(self, tag, value, component=None):
        """Prescribe u (or one ``component`` of it) on facets ``tag``; returns the value holder."""
        fdim = self.mesh.topology.dim - 1
        facets = self.facet_tags.find(tag)
        if component is None:
            c = fem.Constant(self.mesh, np.asarray(value, dtype=float))
            dofs = fem.locate_dofs_topological(self.V, fdim, facets)
            self.bcs.append(fem.dirichletbc(c, dofs, self.V))
        else:
            Vc = self.V.sub(component)
            c = fem.Constant(self.mesh, float(value))
            dofs = fem.locate_dofs_topological(Vc, fdim, facets)
            self.bcs.append(fem.dirichletbc(c, dofs, Vc))
        if self.lam_t is not None:
            self._fix_friction_multiplier(facets, component)
        return c

    def _fix_friction_multiplier(self, facets, component):
        """Zero the friction multiplier where u is prescribed on contact nodes.

        A slave node whose displacement component is prescribed (e.g. on a
        symmetry plane) cannot also carry a stick constraint in that direction:
        the two would be redundant and the Jacobian singular.  Its friction
        traction in that direction is zero (symmetry), so it is prescribed.
        """
        fdim = self.mesh.topology.dim - 1
        gdim = self.mesh.geometry.dim
        blocks = fem.locate_dofs_topological(self.V, fdim, facets)
        sub_blocks = self._sub_dofs[np.isin(self._bulk_dofs, blocks)]
        comps = range(gdim) if component is None else [component]
        for c in comps:
            self.bcs.append(fem.dirichletbc(fem.Constant(self.sub, 0.0),
                                            (gdim * sub_blocks + c).astype(np.int32),
                                            self.Vs.sub(c)))

    def finalize(self, **newton_kw):
        """Compile forms and create the Newton solver."""
        self.solver = BlockNewton(self.residuals, self.unknowns, bcs=self.bcs,
                                  entity_maps=[self.emap], pre_evaluate=self._pre_evaluate,
                                  **newton_kw)
        tn, tt = cf.contact_tractions(self.geometry, self.lam_n, **self._contact_args)
        gdim = self.mesh.geometry.dim
        force = -tn * self.geometry.normal - (tt if tt is not None else 0 * self.geometry.normal)
        self._force_forms = [fem.form(force[i] * self.weight * self.dsc, entity_maps=[self.emap])
                             for i in range(gdim)]
        self._magnitude_forms = [
            fem.form(-tn * self.weight * self.dsc, entity_maps=[self.emap]),
            fem.form((ufl.sqrt(ufl.dot(tt, tt)) if tt is not None else 0 * tn) * self.weight
                     * self.dsc, entity_maps=[self.emap]),
        ]
        q = ufl.TestFunction(self.Q)
        j = kin.area_ratio(kin.deformation_gradient(self.u, self.kind),
                           ufl.FacetNormal(self.mesh), self.kind)
        self._lumped = fem.form(q * self.weight * self.dsc, entity_maps=[self.emap])
        self._lumped_j = fem.form(j * q * self.weight * self.dsc, entity_maps=[self.emap])
        self._active = fem.form(
            ufl.conditional(ufl.lt(tn, 0), 1.0, 0.0) * q * self.dsc, entity_maps=[self.emap])

    # -- evaluation ---------------------------------------------------------
    def update_trace(self):
        """Copy the vertex values of u onto the contact submesh."""
        gdim = self.mesh.geometry.dim
        ub = self.u.x.array.reshape(-1, gdim)
        us = self.u_sub.x.array.reshape(-1, gdim)
        us[self._sub_dofs] = ub[self._bulk_dofs]

    def positions(self):
        """Return current slave-node positions x = X + u, shape (n_sub_dofs, gdim), dof order."""
        gdim = self.mesh.geometry.dim
        return self._X_sub + self.u_sub.x.array.reshape(-1, gdim)

    def _pre_evaluate(self):
        self.update_trace()
        self.obstacle.update(self.positions())

    def solve(self, verbose=False):
        """Newton solve of the current step; returns the :class:`NewtonReport`."""
        if self.solver is None:
            self.finalize()
        return self.solver.solve(verbose=verbose)

    def commit(self):
        """Accept the converged step: the slip history moves to the current state."""
        self._pre_evaluate()
        self.xbar_n.interpolate(self._xbar_expr)
        if self.slip is not None and self.settings.slip == "lagrangian":
            self.offset_n.value[:] = self.obstacle.offset.value

    def _state_constants(self):
        return [self.obstacle.offset] + ([self.offset_n] if hasattr(self, "offset_n") else [])

    def state(self):
        """Copy of all unknowns, the slip history and the obstacle position (step cutting)."""
        return ([f.x.array.copy() for f in self.unknowns + [self.xbar_n]]
                + [c.value.copy() for c in self._state_constants()])

    def restore(self, state):
        """Restore a state obtained from :meth:`state`."""
        fields = self.unknowns + [self.xbar_n]
        for f, a in zip(fields, state):
            f.x.array[:] = a
        for c, a in zip(self._state_constants(), state[len(fields):]):
            c.value[:] = a
        self._pre_evaluate()

    # -- post-processing ----------------------------------------------------
    def contact_force(self):
        """Total force exerted by the countersurface on the (modelled part of the) body (N)."""
        comm = self.mesh.comm
        return np.array([comm.allreduce(fem.assemble_scalar(f), op=MPI.SUM)
                         for f in self._force_forms])

    def traction_magnitudes(self):
        """(∫ |T_N| dS, ∫ ‖T_T‖ dS): total normal and frictional traction magnitudes (N)."""
        comm = self.mesh.comm
        return tuple(comm.allreduce(fem.assemble_scalar(f), op=MPI.SUM)
                     for f in self._magnitude_forms)

    def _nodal(self, form):
        vec = fem.assemble_vector(form)
        vec.scatter_reverse(la.InsertMode.add)
        vec.scatter_forward()
        return vec.array.copy()

    def nodal_contact_data(self):
        """Per owned submesh node: reference X, current x, Cauchy pressure p = −T_N/j, weight.

        The weight is the lumped current area (length in 2D, per radian·2π in
        axisymmetry) of the node; ``active`` flags nodes in contact.
        """
        n_own = self.Q.dofmap.index_map.size_local
        w = self._nodal(self._lumped)
        wj = self._nodal(self._lumped_j)
        act = self._nodal(self._active)
        j = np.divide(wj, w, out=np.ones_like(w), where=w > 0)
        p = -self.lam_n.x.array / j
        x = self.positions()
        return {"X": self._X_sub[:n_own], "x": x[:n_own], "p": p[:n_own],
                "weight": wj[:n_own], "active": act[:n_own] > 0}

    def contact_measures(self):
        """Global contact area (sum of active lumped current weights) and peak pressure."""
        d = self.nodal_contact_data()
        comm = self.mesh.comm
        area = comm.allreduce(float(np.sum(d["weight"][d["active"]])), op=MPI.SUM)
        pmax = comm.allreduce(float(np.max(d["p"], initial=0.0)), op=MPI.MAX)
        return area, pmax

    def gather_profile(self):
        """All nodal contact data on rank 0 (None elsewhere), sorted by reference X[0]."""
        d = self.nodal_contact_data()
        allp = self.mesh.comm.gather(d, root=0)
        if self.mesh.comm.rank != 0:
            return None
        out = {k: np.concatenate([a[k] for a in allp]) for k in d}
        order = np.argsort(out["X"][:, 0])
        return {k: v[order] for k, v in out.items()}

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
  (:func:`~tribofx.forms.film_traction.fluid_traction`, ``shear=False``: pressure only);
* u_s: the trace constraint;
* p: the steady Reynolds equation (49) on the lubrication surface S = P(γ_l)
  (or S_α, Fig. 23) pulled back to Γ_l, SUPG (Remark 3.2), penalty cavitation
  (:func:`~tribofx.forms.ehl.reynolds_on_surface`), or the JFO transport (57)
  (:func:`~tribofx.forms.jfo.jfo_on_surface`);
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

Stopping test: :mod:`tribofx.interfaces.reynolds_film`.

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
from dolfinx import fem
from mpi4py import MPI

from ..forms import ehl as ef
from ..forms import film_traction as ft
from ..forms import mixed
from ..laws import viscosity_law
from ..problem import BlockTolerance
from .film_outputs import FilmOutputs
from .film_start import FilmStart
from .film_transient import TransientFilm
from .reynolds_film import ReynoldsFilm
from .surface import Surface

__all__ = ["Film"]


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


def _is_motion(spec):
    """Whether a velocity ``spec`` is (shape, U): a motion of :mod:`tribofx.motions` and a speed."""
    return isinstance(spec, tuple) and len(spec) == 2 and callable(spec[0])


class Film(FilmOutputs, FilmStart, TransientFilm, ReynoldsFilm):
    """Soft-EHL film on ``boundary`` of ``body`` against ``counterpart``.

    Args:
        body: the lubricated :class:`tribofx.body.Body` (affine mesh).
        boundary: name of the lubricated boundary Γ_l.
        counterpart: factory ``counterpart(V_sub)`` (e.g. :func:`tribofx.obstacles.rigid_plane`),
            called with the P1 vector space of the submesh of Γ_l.
        mu: viscosity (MPa·s), or a viscosity :class:`tribofx.laws.Law` μ(p)
            (:mod:`tribofx.forms.fluid`): the same expression in the Reynolds rows,
            the fluid traction and the friction post-processing.
        density: None (incompressible) or a density :class:`tribofx.laws.Law`
            ρ(p)/ρ₀ (the compressible Reynolds equation; penalty cavitation).
        V_counter: velocity of the countersurface (mm/s): a vector, a ``fem.Constant``
            (e.g. driven by a continuation), (shape, U) (U·shape(y) at the projection
            y, a shape of :mod:`tribofx.motions` and U a Constant: a rolling cylinder)
            or None (at rest).
        model: "finite" or "linear" (geometrically linear EHL).
        shear: Couette and Poiseuille shear tractions on the body (and the unknown g).
        supg: SUPG stabilisation of the Reynolds equation.
        cavitation: "penalty" (ε⁻¹ min(p, 0)) or "jfo" (void fraction λ, plane strain).
        eps: penalty parameter ε (MPa·s/mm); None: no cavitation term.
        p_c: pressure scale of SUPG and of the JFO complementarity (MPa).
        alpha: None (S = P(γ_l)) or α ∈ [0, 1] of the intermediate surface S_α (plane strain).
        film_scale: film thickness scale h_ref (mm) of the tolerances and row scales.
        speed_scale: speed scale U (mm/s) of the Reynolds tolerance and of the JFO flux scale.
        quadrature_degree: quadrature degree of the (Gauss) integrals over Γ_l.
        quadrature: "gauss" (degree ``quadrature_degree``) or "vertex" (the vertex
            rule, second order for P1 displacements).  A meshed countersurface's
            data are exact at the nodes of Γ_l, P1 between them: the Gauss rule's
            tangent is off by O(h κ) on curved facets, the vertex rule's exact.  Not
            the default: a node projecting onto a kinked countersurface vertex gets
            ∂P/∂x = 0 (a degenerate S, NaN rows), which aligned meshes hit (docs/contact.md).
        row_scaling: physical row scales of the film rows (see the module docstring).
        name: name of the interface (unknown names, reports).
        rtol: relative size of the stopping tolerances (see the module docstring).
        require_open: line-search trials must keep the film open, h > 0 at every
            node of Γ_l (:meth:`admissible`; with ``Problem(line_search="admissible")``
            the only test of a trial step).
        motion: None (the layer moves with ``body.velocity``) or (shape, U): the
            layer's reference velocity U·shape(X) (:mod:`tribofx.motions`, U a Constant,
            mm/s), e.g. a rolling cylinder.
        roughness: None (smooth surfaces) or a :class:`tribofx.roughness.Roughness`:
            mixed lubrication, the average-flow Reynolds rows and the asperity
            pressure and boundary friction in the traction (plane strain and 3D).
    """

    CAVITATION = ("penalty", "jfo")

    def __init__(self, body, boundary, counterpart, mu, V_counter=None, model="finite",
                 shear=True, supg=True, cavitation="penalty", eps=None, p_c=1.0, alpha=None,
                 film_scale=1e-2, speed_scale=1.0, quadrature_degree=4, row_scaling=True,
                 name="film", rtol=1e-10, require_open=False, density=None, quadrature="gauss",
                 motion=None, roughness=None):
        if model not in ef.MODELS:
            raise ValueError(f"unknown model {model!r}; expected one of {ef.MODELS}")
        if cavitation not in self.CAVITATION:
            raise ValueError(f"unknown cavitation model {cavitation!r}")
        gdim = body.gdim
        if (cavitation == "jfo" or alpha is not None) and gdim != 2:
            raise ValueError("cavitation='jfo' and alpha are implemented for a curve Γ_l "
                             "(gdim = 2)")
        self.body, self.name, self.rtol = body, name, float(rtol)
        self.boundary = boundary
        self.require_open = bool(require_open)
        self.model, self.shear, self.cavitation, self._supg = model, shear, cavitation, supg
        self._viscosity_law = viscosity_law(mu)
        self.mu = self._viscosity_law.reference_value     # μ₀: the tolerances' scale
        msh = body.mesh
        self._surface = Surface(body, boundary)      # the submesh of Γ_l, shared with wear
        self.sub, self.emap = self._surface.sub, self._surface.emap
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
        self.viscosity = self._viscosity_law.bind(sub)
        self.mu_p = self.viscosity(self.p)      # μ(p): the one viscosity of every form
        self._bind_density(density, sub)
        self.roughness = roughness
        self._rough = roughness.bind(sub) if roughness is not None else None
        self.p_c = fem.Constant(sub, float(p_c))
        self.eps = None if eps is None else fem.Constant(sub, float(eps))
        self.alpha = None if alpha is None else fem.Constant(sub, float(alpha))
        scales = ((self.mu / self.h_ref, body.stiffness / self.h_ref, self.h_ref)
                  if row_scaling else (1.0, 1.0, 1.0))
        self._c_p, self.trace_scale, self._c_g = (fem.Constant(sub, c) for c in scales)
        self._q_ref = fem.Constant(sub, 0.5 * self.U_ref * self.h_ref)

        # measures and reference geometry
        if quadrature not in ("gauss", "vertex"):
            raise ValueError(f"quadrature {quadrature!r}: gauss or vertex")
        qd = ({"quadrature_rule": "vertex", "quadrature_degree": 1} if quadrature == "vertex"
              else {"quadrature_degree": quadrature_degree})
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
        V_body = self._velocity(motion, body.velocity)
        if V_counter is not None and not (isinstance(V_counter, fem.Constant)
                                          or _is_motion(V_counter)):
            V_counter = fem.Constant(sub, np.asarray(V_counter, dtype=float))
        self.V_counter = V_counter
        V_counter = self._velocity(V_counter)

        self.kin_bulk = self._kinematics(X, body.u, ufl.grad(body.u), N_b, V_body, V_counter)
        self.kin = self._kinematics(Xs, self.u_s, self.grad_gamma(self.u_s), self.N, V_body,
                                    V_counter)
        self._F, self._N_b = ufl.Identity(gdim) + ufl.grad(body.u), N_b
        self._tractions()
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

    def _velocity(self, spec, constant=None):
        """Return a velocity field (callable of a UFL position) from ``spec``, or None.

        ``spec``: None, a Constant (uniform) or (shape, U): U·shape(X) with a shape
        of :mod:`tribofx.motions` and U a Constant (mm/s).  The Constants are
        mirrored on the submesh (the Reynolds forms need them there).
        """
        if _is_motion(spec):
            shape, U = spec[0], self._mirror(spec[1])
            return lambda X: U * shape(X)
        c = spec if spec is not None else constant
        if c is None:
            return None
        c = self._mirror(c)
        return lambda X: c

    def _kinematics(self, X, disp, grad_disp, N, V_body, V_counter):
        """Lubrication surface S = P(γ_l) (or S_α) at X: on the bulk side or on the submesh.

        ``V_body`` (the layer's reference velocity) and ``V_counter`` (the
        countersurface's, at the projection y) are callables of a position, or None.
        """
        def surface(x):
            return ef.countersurface_projection(self.counterpart.geometry, x)

        V = V_body(X) if V_body is not None else ufl.zero(self.body.gdim)
        return ef.lubrication_kinematics(X, disp, grad_disp, N, None, None, V, self.model,
                                         surface, self.alpha, V_counter)

    def _tractions(self):
        """Fluid traction (46) on the body from ``kin_bulk``, and its Couette part alone."""
        args = (self.kin_bulk, self._F, self._N_b, self.T_b, self.mu_p)
        grad_p = self.g if self.shear else ufl.zero(self.body.gdim)
        factors = self.shear_factors(self.kin_bulk.h)
        self.traction = ft.fluid_traction(self.p, grad_p, *args, shear=self.shear,
                                          model=self.model, factors=factors)
        self._couette = ft.fluid_traction(0.0, ufl.zero(self.body.gdim), *args, shear=True,
                                          model=self.model, factors=factors)
        self.asperity = None
        if self._rough is not None and self._rough[2] is not None:
            r = self.roughness
            self.asperity = mixed.asperity_traction(self._rough[2](self.kin_bulk.h),
                                                    self.kin_bulk, self._F, self._N_b,
                                                    r.mu_b, r.delta_v)
            self.traction = self.traction + self.asperity

    def shear_factors(self, h):
        """Return the rough film's (c, d) in place of μ/h and h/2 (both walls), or None."""
        if self._rough is None or self._rough[3] is None:
            return None
        r = self.roughness
        return mixed.rough_shear_factors(h, self.mu_p, r.sigma, *self._rough[3], r.share)

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
        out = [(body.u, ft.film_virtual_work(self.traction, body.v, self.ds, self.w_solid)),
               (self.u_s, self.trace_scale * ef.trace_constraint(self.u_s, body.u,
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

    # -- wear driver (tribofx.protocols.WearDriver) ----------------------------------------
    @property
    def surface(self):
        """Γ_l as a :class:`~tribofx.interfaces.surface.Surface` (a Wear's home)."""
        return self._surface

    def wear_load(self, slip=None):
        """Return the film's pressure p⁺ j and sliding speed as the load of Archard wear.

        :func:`tribofx.forms.film_traction.film_wear_load`; with a rough surface's
        asperity contact, the asperity pressure p_a j instead (the film does not wear,
        :func:`tribofx.forms.mixed.asperity_wear_load`).  ``slip`` (a slip increment
        of fast-time cycles) has no meaning for a film.
        """
        if slip is not None:
            raise ValueError("a film has no slip increments: wear under a film is steady "
                             "(averaged=False)")
        if self.body.kind == "axisymmetric":
            raise ValueError("wear under a film of an axisymmetric body is not built (its "
                             "load needs the hoop stretch r/R)")
        if self._rough is not None and self._rough[2] is not None:
            return mixed.asperity_wear_load(self._rough[2](self.kin_bulk.h), self.kin_bulk,
                                            self._F, self._N_b)
        return ft.film_wear_load(self.p, self.kin_bulk, self._F, self._N_b, self.model)

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
        self._tol["u_s"] = BlockTolerance(0.0, "mm", self.trace_scale * ufl.dot(
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
        return (self.unknowns() + list(self.counterpart.state_fields())
                + self.viscosity.state_fields() + self.density.state_fields()
                + self.history_fields())

    def commit(self):
        """Accept the converged step (the counterpart's history moves on)."""
        self.counterpart.commit()

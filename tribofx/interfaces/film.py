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
* λ — void fraction of the JFO model (``cavitation=JFO()``), P1.

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

The parts of a film.  :class:`Film` derives :class:`~tribofx.interfaces.reynolds_film.ReynoldsFilm`,
the pressure rows it shares with :class:`~tribofx.interfaces.RigidFilm` (the
Reynolds/JFO rows, the pressure and inlet conditions on ∂Γ_l, the scales and
tolerances, the JFO starting guess and end fluxes); it owns its
:class:`~tribofx.interfaces.surface.Surface` (the submesh of Γ_l, shared with a
wear of the same boundary), its counterpart, its fluid laws (bound to the
submesh) and, once transient (:meth:`Film.transient`), a
:class:`~tribofx.interfaces.film_history.FilmHistory`.  Below the component
protocol come its starting states (:meth:`Film.start_from_pressure`) and its
outputs (forces on both walls, minimum film, profile).

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
from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any, Literal, Self, TypeAlias, cast, overload

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..forms import ehl as ef
from ..forms import film_traction as ft
from ..forms import mixed
from ..forms import squeeze as sq
from ..laws import viscosity_law
from ..problem import BlockTolerance, Problem
from ..scheme import BDF2, Scheme
from .film_history import FilmHistory, content_space
from .film_options import JFO, Cavitation, FilmScales, Fluid, Penalty, Quadrature
from .prescribed_pressure import PrescribedPressure
from .reynolds_film import ReynoldsFilm, global_extent
from .surface import Surface

if TYPE_CHECKING:
    from collections.abc import Callable

    import numpy.typing as npt
    import ufl.core.expr
    from dolfinx import mesh as dmesh
    from typing_extensions import TypeIs

    from ..body import Body
    from ..forms.ehl import LubricationKinematics
    from ..forms.wear import WearLoad
    from ..protocols import Counterpart
    from ..reports import NewtonReport
    from ..roughness import Roughness
    from .reynolds_film import Profile

    #: a velocity field: a callable of a UFL position (a shape of :mod:`tribofx.motions`)
    Shape: TypeAlias = Callable[[ufl.core.expr.Expr], ufl.core.expr.Expr]
    #: (shape, U): the velocity U·shape(X), U a Constant (mm/s)
    ShapeAndSpeed: TypeAlias = tuple[Shape, fem.Constant]

__all__ = ["Film"]


def _outward_cell_normals(body: Body, sub: dmesh.Mesh, emap: dmesh.EntityMap,
                          G: fem.FunctionSpace) -> fem.Function:
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


def _is_motion(spec: object) -> TypeIs[ShapeAndSpeed]:
    """Whether a velocity ``spec`` is (shape, U): a motion of :mod:`tribofx.motions` and a speed."""
    return isinstance(spec, tuple) and len(spec) == 2 and callable(spec[0])


class Film(ReynoldsFilm):
    """Soft-EHL film on ``boundary`` of ``body`` against ``counterpart``.

    Args:
        body: the lubricated :class:`tribofx.body.Body` (affine mesh).
        boundary: name of the lubricated boundary Γ_l.
        counterpart: factory ``counterpart(V_sub)`` (e.g. :func:`tribofx.obstacles.rigid_plane`),
            called with the P1 vector space of the submesh of Γ_l.
        fluid: the lubricant, a :class:`~tribofx.interfaces.film_options.Fluid`: its
            viscosity μ(p) is the same expression in the Reynolds rows, the fluid
            traction and the friction post-processing; a variable density ρ(p)/ρ₀ gives
            the compressible Reynolds equation (penalty or no cavitation).
        scales: the pressure, film and speed scales
            (:class:`~tribofx.interfaces.film_options.FilmScales`) of the stopping
            test, the row scales, SUPG and the JFO complementarity; None derives them
            from the problem (:meth:`FilmScales.soft_ehl` of the fluid's viscosity, the
            surfaces' speed, the size of Γ_l and the body's modulus).
        cavitation: None (no cavitation model), a
            :class:`~tribofx.interfaces.film_options.Penalty` (ε⁻¹ min(p, 0)) or
            :class:`~tribofx.interfaces.film_options.JFO` (void fraction λ; a curve Γ_l).
        quadrature: the :class:`~tribofx.interfaces.film_options.Quadrature` of the
            integrals over Γ_l.  A meshed countersurface's data are exact at the
            nodes of Γ_l, P1 between them: on curved facets the Gauss rule's tangent
            misses their interpolation error (it vanishes with the mesh), the vertex
            rule's is exact.
        roughness: None (smooth surfaces) or a :class:`tribofx.roughness.Roughness`:
            mixed lubrication, the average-flow Reynolds rows and the asperity
            pressure and boundary friction in the traction (plane strain and 3D).
        V_counter: velocity of the countersurface (mm/s): a vector, a ``fem.Constant``
            (e.g. driven by a continuation), (shape, U) (U·shape(y) at the projection
            y, a shape of :mod:`tribofx.motions` and U a Constant: a rolling cylinder)
            or None (at rest).
        motion: None (the layer moves with ``body.velocity``) or (shape, U): the
            layer's reference velocity U·shape(X) (:mod:`tribofx.motions`, U a Constant,
            mm/s), e.g. a rolling cylinder.
        model: "finite" or "linear" (geometrically linear EHL).
        alpha: None (S = P(γ_l)) or α ∈ [0, 1] of the intermediate surface S_α (plane strain).
        shear: Couette and Poiseuille shear tractions on the body (and the unknown g).
        supg: SUPG stabilisation of the Reynolds equation.
        row_scaling: physical row scales of the film rows (see the module docstring).
        name: name of the interface (unknown names, reports).
        rtol: relative size of the stopping tolerances (see the module docstring).
        require_open: line-search trials must keep the film open, h > 0 at every
            node of Γ_l (:meth:`admissible`; with ``Problem(line_search="admissible")``
            the only test of a trial step).
    """

    averaged = False      # the slow-time protocol: a transient film is not cycle-averaged

    body: Body
    counterpart: Counterpart
    g: fem.Function | None
    T_b: ufl.core.expr.Expr | None
    alpha: fem.Constant | None
    V_counter: fem.Constant | ShapeAndSpeed | None
    traction: ufl.core.expr.Expr
    asperity: ufl.core.expr.Expr | None
    w_solid: ufl.core.expr.Expr | float
    history: FilmHistory | None
    _mirrors: list[tuple[fem.Constant, fem.Constant]]   # (source, submesh copy)
    _post: dict[str, Any] | None
    _pa_nodal: tuple[fem.Function, fem.Function, fem.Expression] | None
    _content_form: fem.Form | None
    _conductance: fem.Expression | None
    _dry: tuple[PrescribedPressure, Problem] | None

    def __init__(self, body: Body, boundary: str,
                 counterpart: Callable[[fem.FunctionSpace], Counterpart], fluid: Fluid, *,
                 scales: FilmScales | None = None, cavitation: Cavitation | None = None,
                 quadrature: Quadrature = Quadrature(), roughness: Roughness | None = None,
                 V_counter: npt.ArrayLike | fem.Constant | ShapeAndSpeed | None = None,
                 motion: ShapeAndSpeed | None = None, model: str = "finite",
                 alpha: float | None = None, shear: bool = True, supg: bool = True,
                 row_scaling: bool = True, name: str = "film", rtol: float = 1e-10,
                 require_open: bool = False) -> None:
        if model not in ef.MODELS:
            raise ValueError(f"unknown model {model!r}; expected one of {ef.MODELS}")
        if not isinstance(fluid, Fluid):
            raise TypeError(f"fluid: a Fluid(viscosity, density), not {fluid!r}")
        if cavitation is not None and not isinstance(cavitation, (Penalty, JFO)):
            raise TypeError(f"cavitation: None, Penalty(eps) or JFO(), not {cavitation!r}")
        gdim = body.gdim
        if alpha is not None and gdim != 2:
            raise ValueError("alpha (the intermediate surface S_α) is implemented for a curve "
                             "Γ_l (gdim = 2)")
        mu, density = fluid.viscosity, fluid.density
        eps = cavitation.eps if isinstance(cavitation, Penalty) else None
        cavitation_name = "none" if cavitation is None else cavitation.name
        self.body, self.name, self.rtol = body, name, float(rtol)
        self.boundary = boundary
        self.require_open = bool(require_open)
        self.model, self.shear, self._supg = model, shear, supg
        self.cavitation = cavitation_name
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
        if cavitation_name == "jfo":
            self.Ql = fem.functionspace(sub, ("Lagrange", 1))
            self.lam = fem.Function(self.Ql, name=f"{name}_void_fraction")
        self._u1 = fem.Function(self.V1)
        self._X1 = self.V1.tabulate_dof_coordinates()[:, :gdim]
        self.counterpart = counterpart(self.V1)

        # physical constants
        self.viscosity = self._viscosity_law.bind(sub)
        self.mu_p = self.viscosity(self.p)      # μ(p): the one viscosity of every form
        self._bind_density(density, sub)
        self.roughness = roughness
        self._rough = roughness.bind(sub) if roughness is not None else None
        self.eps = None if eps is None else fem.Constant(sub, float(eps))
        self.alpha = None if alpha is None else fem.Constant(sub, float(alpha))

        # measures and reference geometry
        qd = quadrature.metadata()
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
        lo, hi = global_extent(self.sub.geometry.x[:, :gdim], msh.comm)
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
        counter_velocity = self._velocity(V_counter)

        self.kin_bulk = self._kinematics(X, body.u, ufl.grad(body.u), N_b, V_body,
                                         counter_velocity)
        self.kin = self._kinematics(Xs, self.u_s, self.grad_gamma(self.u_s), self.N, V_body,
                                    counter_velocity)

        # scales: the stopping test's, the rows', SUPG's and the complementarity's
        if scales is None:
            scales = self._derived_scales(V_body, counter_velocity)
        self.h_ref, self.U_ref = float(scales.film), float(scales.speed)
        self.p_c = fem.Constant(sub, float(scales.pressure))
        rows = ((self.mu / self.h_ref, body.stiffness / self.h_ref, self.h_ref)
                if row_scaling else (1.0, 1.0, 1.0))
        self._c_p, self.trace_scale, self._c_g = (fem.Constant(sub, c) for c in rows)
        self._q_ref = fem.Constant(sub, 0.5 * self.U_ref * self.h_ref)
        self._F, self._N_b = ufl.Identity(gdim) + ufl.grad(body.u), N_b
        self._tractions()
        # reference measure factors: the body's (2πR) and, axisymmetric, the hoop stretch
        self.w_solid, self.w_film = body.weight, 1
        if body.kind == "axisymmetric":
            if model == "finite":
                self.w_solid = body.weight * (1 + body.u[0] / X[0])
            self.w_film = 2 * ufl.pi * self.kin.y[0]
        self._jumps = cavitation_name == "jfo"
        self._post = None          # the compiled forms of the outputs
        self._pa_nodal = None      # the nodal asperity pressure's Expression (rough films)
        self.history = None        # a transient film's FilmHistory (transient())
        self._content_form = self._conductance = None
        self._dry = None
        self._init_rows()

    def _derived_scales(self, V_body: Shape | None, V_counter: Shape | None) -> FilmScales:
        """Return the scales of a film given none: :meth:`FilmScales.soft_ehl` of its problem.

        U: the largest mean speed |v_layer + v_counter|/2 of the surfaces over Γ_l at
        the start (the motions' velocities at the film's nodes); ℓ: the radius of
        Γ_l; E' = 4G, the plane-strain modulus of a nearly incompressible solid of
        the body's shear modulus G (``Body.stiffness``); μ₀ the fluid's viscosity at
        p = 0.
        """
        gdim = self.body.gdim
        Xs = ufl.SpatialCoordinate(self.sub)
        zero = ufl.zero(gdim)
        v = (V_body(Xs) if V_body is not None else zero) \
            + (V_counter(Xs) if V_counter is not None else zero)
        speed = fem.Function(self.Q)
        speed.interpolate(fem.Expression(0.5 * ufl.sqrt(ufl.dot(v, v)),
                                         self.Q.element.interpolation_points))
        U = self.sub.comm.allreduce(float(np.max(speed.x.array, initial=0.0)), op=MPI.MAX)
        return FilmScales.soft_ehl(self.mu, U, 0.5 * self.length, 4 * self.body.stiffness)

    def _velocity(self, spec: fem.Constant | ShapeAndSpeed | None,
                  constant: fem.Constant | None = None) -> Shape | None:
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

    def _kinematics(self, X: ufl.core.expr.Expr, disp: ufl.core.expr.Expr,
                    grad_disp: ufl.core.expr.Expr, N: ufl.core.expr.Expr, V_body: Shape | None,
                    V_counter: Shape | None) -> LubricationKinematics:
        """Lubrication surface S = P(γ_l) (or S_α) at X: on the bulk side or on the submesh.

        ``V_body`` (the layer's reference velocity) and ``V_counter`` (the
        countersurface's, at the projection y) are callables of a position, or None.
        """
        def surface(x: ufl.core.expr.Expr) -> tuple[ufl.core.expr.Expr, ufl.core.expr.Expr,
                                                     ufl.core.expr.Expr, ufl.core.expr.Expr]:
            return ef.countersurface_projection(self.counterpart.geometry, x)

        V = V_body(X) if V_body is not None else ufl.zero(self.body.gdim)
        return ef.lubrication_kinematics(X, disp, grad_disp, N, None, None, V, self.model,
                                         surface, self.alpha, V_counter)

    def _tractions(self) -> None:
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
            assert r is not None                    # bound together with _rough
            self.asperity = mixed.asperity_traction(self._rough[2](self.kin_bulk.h),
                                                    self.kin_bulk, self._F, self._N_b,
                                                    r.mu_b, r.delta_v)
            self.traction = self.traction + self.asperity

    def shear_factors(self, h: ufl.core.expr.Expr
                      ) -> tuple[ufl.core.expr.Expr, ufl.core.expr.Expr] | None:
        """Return the rough film's (c, d) in place of μ/h and h/2 (both walls), or None."""
        if self._rough is None or self._rough[3] is None:
            return None
        r = self.roughness
        assert r is not None                        # bound together with _rough
        return mixed.rough_shear_factors(h, self.mu_p, r.sigma, *self._rough[3], r.share)

    def _mirror(self, constant: fem.Constant) -> fem.Constant:
        copy = fem.Constant(self.sub, np.array(constant.value, dtype=float))
        self._mirrors.append((constant, copy))
        return copy

    def _sync(self) -> None:
        for src, dst in self._mirrors:
            dst.value = src.value

    # -- component protocol --------------------------------------------------------------
    def unknowns(self) -> list[fem.Function]:
        """Return u_s, p (g, λ) and the counterpart's unknowns."""
        out = [self.u_s, self.p] + ([self.g] if self.g is not None else []) \
            + ([self.lam] if self.lam is not None else [])
        return out + list(self.counterpart.unknowns())

    def contributions(self) -> list[tuple[fem.Function, ufl.Form]]:
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
        if C is not None:     # the JFO complementarity: λ exists
            out.append((cast("fem.Function", self.lam), self._c_p * C))
        return out

    def entity_maps(self) -> list[dmesh.EntityMap]:
        """Return the submesh ↔ bulk entity map."""
        return [self.emap]

    # -- wear driver (tribofx.protocols.WearDriver) ----------------------------------------
    @property
    def surface(self) -> Surface:
        """Γ_l as a :class:`~tribofx.interfaces.surface.Surface` (a Wear's home)."""
        return self._surface

    def wear_load(self, slip: ufl.core.expr.Expr | None = None) -> WearLoad:
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

    def positions(self) -> npt.NDArray[np.float64]:
        """Nodal positions of Γ_l at which the counterpart is projected (P1 dof order, mm).

        Current x = X + u_s, or the reference X for ``model="linear"``.
        """
        if self.model == "linear":
            return self._X1.copy()
        self._u1.interpolate(self.u_s)
        return self._X1 + self._u1.x.array.reshape(-1, self.body.gdim)

    def refresh(self) -> None:
        """Copy the velocities; let the counterpart project the nodes of Γ_l (kernel data)."""
        self._sync()
        self.counterpart.update(self.positions())

    def tolerances(self) -> dict[fem.Function, BlockTolerance]:
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

    def state_fields(self) -> list[fem.Function | fem.Constant]:
        """Unknowns and the counterpart's state.

        The scales p_c and ε are not part of the state: they follow the
        continuation parameters (speed, load) through :meth:`set_scales`.
        """
        return (self.unknowns() + list(self.counterpart.state_fields())
                + self.viscosity.state_fields() + self.density.state_fields()
                + self.history_fields())

    def commit(self) -> None:
        """Accept the converged step (the counterpart's history moves on)."""
        self.counterpart.commit()

    # -- time: a transient film (tribofx.forms.squeeze) ---------------------------------------
    @property
    def scheme(self) -> Scheme | None:
        """The implicit scheme of a transient film's rates, None for the steady film."""
        return None if self.history is None else self.history.scheme

    def transient(self, scheme: Scheme | str = BDF2, lumped: bool = False) -> Self:
        """Make the film transient, integrated by ``scheme``; returns self.

        ``scheme``: :data:`~tribofx.scheme.IMPLICIT` (backward Euler, ``"euler"``)
        or :data:`~tribofx.scheme.BDF2` (``"bdf2"``).  The film gets a
        :class:`~tribofx.interfaces.film_history.FilmHistory` (``self.history``),
        and its rows the rates of :mod:`tribofx.forms.squeeze`:

        * the Reynolds (or JFO transport) rows the rate of the fluid content
          c = ρ θ h J_S w at fixed reference point X, and the mean velocity relative
          to the moving lubrication surface, v̄ − (I − ν⊗ν) ẏ;
        * the layer velocity the displacement rate u̇ (rows and Couette traction);
        * ẏ follows by the chain rule (:func:`tribofx.forms.squeeze.surface_rate`)
          from the rates of u_s and of the countersurface's rigid translation.

        The film then answers the slow-time protocol of
        :class:`tribofx.stepper.Stepper` (:meth:`begin_step`, :meth:`end_step`).
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
        if self.history is not None:
            raise ValueError("the film is already transient")
        md = self.dx.metadata()
        if md.get("quadrature_rule") == "vertex":
            raise ValueError("a transient film needs quadrature='gauss'")
        if lumped and self.lam is None:
            raise ValueError("a lumped transient film is for cavitation='jfo'")
        self.lumped = bool(lumped)
        if lumped and self._jumps and self.T is not None:
            # ω of jfo_on_surface(vertex=) on a curve: 0 until set (reforming films)
            self.vertex_couette = fem.Constant(self.sub, 0.0)
        sub, body = self.sub, self.body
        Cq = content_space(sub, md["quadrature_degree"], lumped)
        H = self.history = FilmHistory(scheme, Cq, self.Vs, body.u.function_space,
                                       getattr(self.counterpart, "offset", None), body.mesh,
                                       sub, self.name)
        w_sub = [self._mirror(c) for c in H.weights]   # the weights on the submesh
        self.film_rate = sq.backward_difference(self._content(), *H.content, *w_sub)
        u_rate = sq.backward_difference(self.u_s, *H.trace, *w_sub)
        # ẏ by the chain rule: y(x, c) moves with a common translation of x and c
        c_rate = None
        if H.offset is not None:
            c_rate = sq.backward_difference(H.offset, *H.offset_history, *w_sub)
        y_rate = sq.surface_rate(self.kin.y, self.u_s, u_rate, c_rate)
        self.kin = sq.moving_surface(self.kin, layer_rate=u_rate)
        self.kin_reynolds = sq.moving_surface(self.kin, surface_rate=y_rate)
        self.kin_bulk = sq.moving_surface(self.kin_bulk,
                                          layer_rate=sq.backward_difference(
                                              body.u, *H.displacement, *H.weights))
        self._tractions()
        self._content_expr = fem.Expression(self._content(), Cq.element.interpolation_points)
        cells = sub.topology.index_map(sub.topology.dim).size_global
        one = fem.form(fem.Constant(sub, 1.0) * self.dx)
        self._cell_size = (self._sum(one) / cells) ** (1 / sub.topology.dim)
        return self

    def history_fields(self) -> list[fem.Function | fem.Constant]:
        """Return the history's fields of a transient film (none when steady)."""
        return [] if self.history is None else self.history.fields()

    # -- slow-time protocol (tribofx.stepper.Stepper) ------------------------------------
    def shape_unknowns(self) -> list[fem.Function]:
        """No shape unknowns: the film's unknowns are solved with the body's."""
        return []

    def min_volume_factor(self) -> float:
        """No shape change: +inf (the Stepper's mesh check passes)."""
        return np.inf

    def begin_step(self, dt: float) -> None:
        """Start a step of Δt (s): the history moves on (:meth:`FilmHistory.advance`).

        The stopping tolerance of the Reynolds rows follows the step: the speed
        ℓ_e/Δt of the mean element ℓ_e joins U (a content error of rtol·h_ref at a
        node is a flux imbalance of that size) and the rows' round-off floor
        (:meth:`row_round_off`) is added.
        """
        if self.history is None:
            raise ValueError("begin_step of a steady film: call film.transient() first")
        self.refresh()
        self.history.advance(dt, self.u_s, self.body.u, self._content_expr)
        self._rate_speed = self._cell_size / dt      # the Reynolds rows' tolerance
        self._round_off = self.row_round_off()
        self.set_scales()

    def row_round_off(self) -> float:
        """Round-off floor of the Reynolds rows at the current state (mm²/s; mm³/s revolved).

        A row sums Poiseuille fluxes K (p_i − p_j) with K = w h³/(12 μ h_e) of its
        elements: p known to an ulp or so (≈ eps |p|, whatever the iteration)
        leaves ≈ 2 eps K |p| to 4 eps K |p| per row.  Where the film is thick this
        exceeds rtol·U·h_ref: the seal's flank opens to h = 0.84 mm in the
        instroke (K ≈ 3.6e9 mm³/(MPa·s) at p_s = 1 MPa), whose rows stall at
        6.5e-7 mm³/s against a tolerance of 6.5e-7 (measured).  Returns
        4 eps max K |p| over the nodes (every rank), added to the p tolerance of
        the step (:meth:`begin_step`).
        """
        if self._conductance is None:
            kin, mu = self._flux_kinematics()
            self._conductance = fem.Expression(
                self.w_film * kin.h**3 * abs(self.p) / (12 * mu * ufl.CellDiameter(self.sub)),  # type: ignore[arg-type]  # ufl: Expr.__abs__ set at run time
                self.Q.element.interpolation_points)
        Kp = fem.Function(self.Q)
        Kp.interpolate(self._conductance)
        local = float(np.max(np.abs(Kp.x.array), initial=0.0))
        return 4 * np.finfo(float).eps * self.sub.comm.allreduce(local, op=MPI.MAX)

    def end_step(self) -> None:
        """Nothing: the outputs of the step keep its rates (the next step resets them)."""

    def _content(self) -> ufl.core.expr.Expr:
        """UFL content ρ θ h J_S w per unit reference measure (h, J_S: any ``kin`` of the film).

        A rough film with average flow stores the expected gap h_T(h) (Patir & Cheng:
        the squeeze term is ∂h_T/∂t), the gap its flux is written on.
        """
        kin, rough = self.kin, self._rough
        if rough is not None and rough[0] is not None:
            assert self.roughness is not None       # bound together with _rough
            kin = dataclasses.replace(kin, h=mixed.expected_gap(kin.h, self.roughness.sigma))
        return sq.film_content(kin, self.lam, self.rho_p, self.w_film)

    def content(self) -> float:
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

    # -- starting states ---------------------------------------------------------------

    def place_countersurface(self, h0: float, at: npt.ArrayLike) -> None:
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

    def start_from_pressure(self,
                            pressure: Callable[[npt.NDArray[np.float64]], npt.NDArray[np.float64]],
                            h0: float, at: npt.ArrayLike, verbose: bool = False) -> NewtonReport:
        """Set an initial state: the body under a prescribed film pressure, film ``h0`` at ``at``.

        ``pressure`` is a callable of the reference coordinates (3, n) → p (MPa),
        e.g. the Hertz pressure; the body is solved under it as a follower load
        (:class:`PrescribedPressure`, no shear), p is set to it (g to 0) as the
        first pressure iterate and a rigid countersurface is placed so that the
        film is ``h0`` (mm) at the node nearest to ``at``.  Returns the Newton report.
        """
        report = self._dry_start(pressure, verbose)
        self.place_countersurface(h0, at)
        return report

    def _dry_start(self, pressure: Callable[[npt.NDArray[np.float64]], npt.NDArray[np.float64]],
                   verbose: bool = False) -> NewtonReport:
        """Solve the body under ``pressure`` on Γ_l (no film); p set to it, g to 0."""
        if self._dry is None:
            dry = PrescribedPressure(self)
            self._dry = (dry, Problem([self.body, dry], name=f"{self.name}_dry"))
        dry, problem = self._dry
        dry.p.interpolate(pressure)
        report = problem.solve(verbose=verbose)
        self.p.x.array[:] = dry.p.x.array
        if self.g is not None:
            self.g.x.array[:] = 0.0
        return report

    # -- outputs -------------------------------------------------------------------------


    def _post_forms(self) -> dict[str, Any]:
        if self._post is None:
            em = [self.emap]
            gdim = self.body.gdim
            counter = ft.countersurface_traction(
                self.p, self.grad_gamma(self.p), self.kin, self.mu_p,
                factors=self.shear_factors(self.kin.h))
            self._post = {
                "force": [fem.form(self.traction[i] * self.w_solid * self.ds, entity_maps=em)
                          for i in range(gdim)],
                "couette": [fem.form(self._couette[i] * self.w_solid * self.ds, entity_maps=em)
                            for i in range(gdim)],
                "counter": [fem.form(counter[i] * self.kin.stretch * self.w_film * self.dx)
                            for i in range(gdim)],
                "asperity": None if self.asperity is None else [
                    fem.form(self.asperity[i] * self.w_solid * self.ds, entity_maps=em)
                    for i in range(gdim)],
                "y": fem.Expression(self.kin.y, self.V1.element.interpolation_points),
            }
        return self._post

    def _nodal(self, key: str) -> npt.NDArray[np.float64]:
        f: fem.Function = fem.Function(self.V1)
        f.interpolate(self._post_forms()[key])
        return f.x.array

    def _vector_integral(self, key: str) -> npt.NDArray[np.float64]:
        """Refresh the kernel data; the components of the post-processing form ``key``."""
        self.refresh()
        return np.array([self._sum(f) for f in self._post_forms()[key]])

    def force(self) -> npt.NDArray[np.float64]:
        """Force of the film on the modelled part of the body.

        N/mm per unit thickness in plane strain; N in 3D (a quarter model: a
        quarter of the full body's); axisymmetric: the revolved body's, N (2πR-weighted).
        """
        return self._vector_integral("force")

    def counter_force(self) -> npt.NDArray[np.float64]:
        """Force of the film on the countersurface (units and parts as :meth:`force`).

        ∫_S [−p ν + (μ/h) v_rel − (h/2) grad_S p] ds_S over the modelled part
        (:func:`forms.film_traction.countersurface_traction`): what a friction rig measures
        on the rigid counterpart.  The film's momentum balance makes this
        −:meth:`force` up to the shear where the layer's area differs from S's,
        ∫ shear (j − ds_S/dS) dS (steep flanks of a thick film); the
        geometrically linear model's traction −pN also leaves out the pressure on
        the displacement's slope, ∫ p grad_S(ν·u) ds_S (tests/test_ehl_ball.py).
        """
        return self._vector_integral("counter")

    def asperity_force(self) -> npt.NDArray[np.float64]:
        """Force of the asperity contact on the body (N; N/mm): pressure and boundary friction."""
        if self.asperity is None:
            return np.zeros(self.body.gdim)
        return self._vector_integral("asperity")

    def couette_force(self) -> npt.NDArray[np.float64]:
        """Couette drag alone (N; N/mm): ∫ −j(μ/h)(v_layer − v_counter) dS (any ``shear``)."""
        return self._vector_integral("couette")

    def min_film(self) -> float:
        """Smallest nodal film thickness on Γ_l (mm, all ranks)."""
        self.refresh()
        n = self.Q.dofmap.index_map.size_local
        return self.sub.comm.allreduce(float(self._film_thickness()[:n].min(initial=np.inf)),
                                       op=MPI.MIN)

    def admissible(self) -> bool:
        """Line-search test: True, or with ``require_open`` an open film and fluid at every node.

        Open: h > 0, or on rough surfaces h > −4σ (the nominal surfaces may
        overlap where the asperities carry; the Greenwood–Tripp fit ends at 4σ).
        """
        floor = 0.0 if self.roughness is None else -4 * self.roughness.sigma
        return not self.require_open or (self.has_fluid() and self.min_film() > floor)

    @overload
    def profile(self, everywhere: Literal[True]) -> Profile: ...

    @overload
    def profile(self, everywhere: bool = False) -> Profile | None: ...

    def profile(self, everywhere: bool = False) -> Profile | None:
        """Nodal X, x (current), y (projection), h, p (λ, p_a) of Γ_l, sorted by X₀.

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
        if self.asperity is not None:
            d["p_a"] = self._asperity_pressure(d["h"], n)
        return self._gather(d, "X", everywhere)

    def _asperity_pressure(self, h: npt.NDArray[np.float64], n: int) -> npt.NDArray[np.float64]:
        """Nodal asperity pressure p_a(h) (MPa) of the roughness's law at the nodal gaps."""
        hf: fem.Function
        out: fem.Function
        if self._pa_nodal is None:
            # called with an asperity contact only (profile): the law p_a is bound
            assert self._rough is not None and self._rough[2] is not None
            hf, out = fem.Function(self.Q), fem.Function(self.Q)
            expr = fem.Expression(self._rough[2](hf), self.Q.element.interpolation_points)
            self._pa_nodal = (hf, out, expr)
        hf, out, expr = self._pa_nodal
        hf.x.array[:n] = h
        out.interpolate(expr)
        return out.x.array[:n].copy()

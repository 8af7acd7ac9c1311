"""Reciprocating O-ring seal: axisymmetric soft EHL (chapter §8.1, Figs. 15–19).

An elastomeric O-ring of cross-section diameter d sits in a housing groove and
seals the pressure p_s against a rod of radius r_rod sliding axially with speed
U (U > 0 outstroke: the rod moves towards the air side, +z; U < 0 instroke).
Axisymmetric about the rod axis, mesh coordinates (r, z):

* seal: nearly incompressible Mooney–Rivlin, ψ = μ₁/2 (Ī₁ − 3) + μ₂/2 (Ī₂ − 3)
  + κ/2 (J − 1)², 3×3 F with hoop stretch r/R, weight 2πR (forms/hyperelastic);
* housing: groove bottom r = r_g = r_rod + d(1 − squeeze) and air-side wall,
  rigid planes, frictionless augmented-Lagrangian contact; sealed side open;
* sealed pressure: follower pressure p_s on the quarter of the ring boundary
  facing the sealed side (225° ≤ φ ≤ 315°) and p = p_s at the sealed-side end
  of the film (simple robust choice: the fluid at p_s reaches the film through
  the sealed-side flank of Γ_l; the arc between the flank and the groove bottom
  is loaded by p_s whether or not it touches the bottom);
* rod: soft-EHL film on the inner quarter arc Γ_l (135° ≤ φ ≤ 225°): S = P(γ_l)
  on the rod cylinder, h = r − r_rod, v̄ = ½U e_z, steady Reynolds equation (49)
  on the surface of revolution (weight 2π r_rod times the meridian stretch),
  SUPG; cavitation (``cavitation``): JFO (57, mass-conserving, the default with
  the mixed solid: void fraction λ, p ≥ 0, λ ≥ 0, pλ = 0 at the nodes; flooded
  inlet p = p_s or 0, λ = 0 at the upstream end, a natural outlet downstream in
  outstroke, p = p_s at the sealed end in instroke) or the penalty ε⁻¹ min(p, 0)
  with p = p_s / 0 at the sealed / air end (the chapter's; the default with the
  displacement solid);
  fluid traction (46): pressure (axisymmetric Nanson), Couette (μ/h)U e_z and
  Poiseuille −(h/2) grad_S p shear (forms/ehl_axisym.py).

Solution path: the ring starts ``gap0`` clear of the rod with the film on; the
groove bottom is moved in ``mount_steps`` steps to r_g (squeeze) at the mounting
pressure 0.1 MPa and the mounting speed U_m = sign(U) max(|U|, 1000 mm/s) (a
thicker film is easier); p_s is raised to the first target, the speed lowered
geometrically to U, then the other p_s targets follow.  Each continuation
step is cut on Newton failure (the last converged state is kept and written).

Core configuration: a :class:`~tribofx.body.Body` (axisymmetric Mooney–Rivlin,
follower pressure p_s on the sealed arc), two
:class:`~tribofx.interfaces.Contact` on the housing arc (sealed ∪ housing facets)
against :func:`~tribofx.obstacles.rigid_plane` (groove bottom, moved by its
offset; air-side wall), a :class:`~tribofx.interfaces.Film` on Γ_l against the
rod line r = r_rod moving with ``V_counter`` = U e_z, one
:class:`~tribofx.problem.Problem` with the admissible line search (a trial step
is accepted when it keeps the film open, h > 0, and R finite: ‖R‖ is a poor
merit function with the thick-film flanks of Γ_l) and
:class:`~tribofx.continuation.Continuation` in the groove offset, p_s and U.

``stroke=cycle``: the transient film over a reciprocating stroke,
U(t) = U cos(2πt/``period``), from the steady outstroke at the first p_s, with
an open air end supplied by the layer the rod carried out and an optional rough
rod (``sigma``); :mod:`tribofx.cases.ehl_oring`.

Default data (mm, N, s, MPa), after Stupkiewicz (2009) and Stupkiewicz &
Marciniszyn (Tribol. Int. 42, 2009) where the chapter fixes them:

* μ₁ + μ₂ = 3.66 MPa (chapter §8.1); split μ₁ = 2.93, μ₂ = 0.73 (μ₂/μ₁ = 0.25,
  a common ratio for NBR, our choice); κ = 1000 (μ₁ + μ₂) = 3660 MPa;
* d = 3.5 mm, r_rod = 10 mm, squeeze 10 % (typical dynamic O-ring gland);
* oil viscosity μ = 5e-8 MPa·s (0.05 Pa·s), U = 400 mm/s (Fig. 18: outstroke,
  p_s = 1 MPa, U = 400 mm/s);
* mesh density n: element size 0.1/n mm on Γ_l (0.1/(n·2^k) with
  ``arc_refine`` k: the film's inlet, where its thickness is set, is a few
  elements long at 100 mm/s), 0.4/n mm in the bulk; P1
  displacement with a P1 volumetric stress (``formulation=mixed``, default:
  locking-free; the chapter's zigzag film oscillations are the volumetric
  locking of the P1 displacement solid, ``formulation=displacement``), P1 film
  pressure.

``study=mesh`` repeats the outstroke at the first p_s on the densities
``mesh_levels`` (Figs. 18–19) and reports an oscillation indicator per density
(mean |Δ²h| / 4h̄ in the loaded zone p − p_s > (p_max − p_s)/2: the relative
zigzag amplitude)
and the change of the mean film h̄ of that zone from level to level.

Your own cross-section (``mesh_file``): a 2D gmsh ``.msh`` in the meridian plane
(r, z) with the physical groups ``lubricated`` (Γ_l, one open curve facing the
rod), ``sealed`` (loaded by p_s) and ``housing`` (the rest of the boundary that
may touch the groove bottom or the air-side wall; both housing contacts act on
sealed ∪ housing, as on the built section), read and checked by
:func:`tribofx.meshes.user.read_user_mesh`.  It replaces ``d`` (the radial
extent of the mesh, also the groove depth of ``squeeze``) and ``mesh`` (the
elements are the user's; ``study=mesh`` is rejected).  The section is moved so
that its innermost node is at r = r_rod + gap0 and its z extent centred at
z = 0; with a the radial half extent, the groove bottom starts 10⁻³ a inside
its outermost node and the air-side wall 0.005 mm below its top, as for the
built circle.  a also sets the penalty scale ℓ = a/4 and the augmentation
ρ_N = E/a of the housing contacts: a geometric scale for the built section
too (no element size is taken from either mesh; SUPG takes the cell size of
Γ_l).  Γ_l must end at its two z extremes, each the only node of Γ_l at that
height (checked): p = p_s at the lower (sealed-side) end, p = 0 at the upper
one.  All other parameters apply as for the built section.

Results per stroke and p_s (prefix ``out_``/``in_`` and ``ps<value>_``): p_max,
h_min and its position, h at the pressure peak, mean film h_mean of the loaded
zone, flux q = h v̄ − h³/(12μ) ∂p/∂z per circumference (median over the loaded
zone), leakage 2π r_rod q, radial load and friction force per circumference,
oscillation indicator, axial equilibrium error (sum of axial forces / axial
force of p_s).  Plots ``profiles.png`` (Fig. 17, out vs in), ``mesh_study.png``
(Figs. 18–19).  VTX of u and p at the end and as time series per stroke
(``outstroke_displacement_series.bp``, ``outstroke_pressure_series.bp``, ``in…``:
one time index per sealed pressure, its p_s in ``series_points``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms import ehl_axisym as ax
from ..forms.wear import bdf2_coefficients
from ..interfaces import Contact, Film, FilmScales, Fluid
from ..interfaces.film_options import named_cavitation
from ..meshes.oring import HOUSING, LUBRICATED, SEALED, oring_section
from ..meshes.user import read_user_mesh
from ..obstacles import rigid_plane
from ..params import InputError, number_list, param
from ..plots import plot_oring, plot_oring_cycle
from ..positions import oscillation_indicator, parabolic_vertex
from ..problem import Problem, options_name
from ..references import inverse_film
from ..restart import SweepJournal
from ..roughness import rough_pair
from ..scheme import Scheme
from ..step_control import FixedStep
from ..stepper import Stepper, nominal_steps
from ..sweep import SweepVariant, journalled_points
from .film_setup import (
    FluidParams,
    density,
    film_boundary,
    formulation_param,
    viscosity,
)
from .slow_time import SlowTimeRecords

if TYPE_CHECKING:
    import os
    from collections.abc import Callable, Mapping, Sequence
    from pathlib import Path

    import numpy.typing as npt
    from dolfinx import mesh as dmesh
    from tqdm import tqdm

    from ..continuation import Iterations
    from ..obstacles import AnalyticObstacle
    from ..output import RunRecord
    from ..roughness import Roughness

    class CycleStepper(Stepper):
        """The :class:`~tribofx.stepper.Stepper` of :func:`cycle_stepper`: its seal and layer."""

        seal: ORingSeal
        layer: AirLayer

__all__ = ["NAMES", "UNITS", "USER_GROUPS", "AirLayer", "ORingSeal", "Params", "air_end",
           "axial_balance", "build", "cycle_stepper", "doc", "geometry", "integral", "mesh_study",
           "name", "plot", "progress_total", "reforming", "resumable", "rod_speed", "run",
           "run_cycle", "solve_to", "transient_seal", "validate", "vtx_fields"]


P_MOUNT = 0.1        # MPa, sealed pressure during the squeeze


W_REF = 20.0         # MPa/mm, nominal inlet gradient of the film scale h_ref


NAMES = {"lubricated": LUBRICATED, "sealed": SEALED, "housing": (SEALED, HOUSING)}


USER_GROUPS = ("lubricated", "sealed", "housing")   # the groups of a user's section


def cavitation_model(v: Params) -> str:
    """Return the film's cavitation model of the values ``v``.

    ``v.cavitation``, or for ``auto`` JFO with the mixed solid and the penalty
    with the displacement one (measured on the O-ring: on the zig-zag surface of
    the locked P1 solid the semismooth JFO iteration cycles, density 2 at 1000 mm/s).
    """
    if v.cavitation != "auto":
        return v.cavitation
    return "jfo" if v.formulation == "mixed" else "penalty"


def arc_halvings(v: Params) -> int:
    """Return the halvings k of the seal's film-arc elements (0.1/(n·2^k) mm) of the values ``v``.

    ``v.arc_refine``, or by default 1 for the transient cycle (``stroke=cycle``
    on the built section) and 0 otherwise: at 25 µm (density 4, k = 0) the
    instroke's air-side reformation front sits on one node where p = λ = 0
    (degenerate complementarity), and the semismooth Newton iteration of the first
    instroke can cycle there (measured: the rough seal stops at t ≈ 42 ms); at
    12.5 µm both schemes run whole cycles (BDF2: tests/test_oring_cycle.py; backward
    Euler: demos/demo_oring_cycle.py without ``--quick``).
    """
    if v.arc_refine is not None:
        return v.arc_refine
    return 1 if v.stroke == "cycle" and not v.mesh_file else 0


def geometry(v: Params, extent: tuple[float, float] | None = None
             ) -> tuple[tuple[float, float], float, float, float, float]:
    """Centre, radius, rod radius, final groove bottom and air-side wall (mm).

    ``extent``: the half extents (r, z) of a user's section (None: the built
    circle, radius d/2); the centre is that of its bounding box, the radius a
    the radial half extent, d = 2a.
    """
    a, b = extent if extent is not None else (0.5 * v.d,) * 2
    r_rod = v.r_rod
    center = (r_rod + a + v.gap0, 0.0)
    return center, a, r_rod, r_rod + 2 * a * (1 - v.squeeze), b - 0.005


def _user_section(v: Params, comm: MPI.Comm
                  ) -> tuple[dmesh.Mesh, dmesh.MeshTags, dict[str, int | tuple[int, int]],
                             tuple[float, float]]:
    """Read a user's section, move it into place (see the module docstring).

    Returns ``(mesh, facet_tags, names, (a, b))``, a and b the half extents in r
    and z (mm).
    """
    msh, ft, tags = read_user_mesh(v.mesh_file, comm, 2, USER_GROUPS)
    x = msh.geometry.x
    lo = np.array([comm.allreduce(float(np.min(x[:, k], initial=np.inf)), op=MPI.MIN)
                   for k in range(2)])
    hi = np.array([comm.allreduce(float(np.max(x[:, k], initial=-np.inf)), op=MPI.MAX)
                   for k in range(2)])
    a, b = 0.5 * (hi - lo)
    if v.gap0 >= a:
        raise InputError(f"gap0 = {v.gap0} mm must be below half the radial extent of "
                         f"the section ({a:.4g} mm)")
    x[:, 0] += v.r_rod + v.gap0 - lo[0]
    x[:, 1] -= 0.5 * (lo[1] + hi[1])
    names = {"lubricated": tags["lubricated"], "sealed": tags["sealed"],
             "housing": (tags["sealed"], tags["housing"])}
    return msh, ft, names, (a, b)


class ORingSeal:
    """The configured seal: ``body``, ``film``, ``bottom``/``wall`` contacts, ``problem``.

    ``p_s`` (Constant, MPa) loads the sealed arc and is mirrored into the film's
    Dirichlet value at the sealed end; the groove bottom moves by the offset of
    ``bottom.counterpart``; the rod speed is ``film.V_counter[1]`` (mm/s).
    ``roughness``: a rough rod (mixed film); ``transient``: the time scheme of a
    reciprocating film (:func:`cycle_stepper`: the lumped content rate, an open air
    end supplied with the content ``supply``).
    """

    def __init__(self, v: Params, U: float, mesh: int, comm: MPI.Comm, name: str = "ehl_oring",
                 roughness: Roughness | None = None, transient: str | None = None) -> None:
        self.user = bool(v.mesh_file)
        if self.user:
            msh, ft, names, extent = _user_section(v, comm)
        else:
            extent, names = None, NAMES
        center, a, r_rod, r_g, z_w = geometry(v, extent)
        self.center, self.a, self.r_rod = center, a, r_rod
        if not self.user:
            msh, _, ft = oring_section(*center, a, mesh, h_l=0.1 / 2 ** arc_halvings(v),
                                       comm=comm)
        mat = {"mu1": v.mu1, "mu2": v.mu2, "kappa": v.kappa}
        E = 3 * (mat["mu1"] + mat["mu2"])
        deg = v.degree
        self.body = body = Body(msh, ft, names, "axisymmetric", ("mooney-rivlin", mat),
                                degree=deg, quadrature_degree=2 * deg, name="oring",
                                formulation=v.formulation)
        p0 = min(P_MOUNT, number_list(v.p_s, "p_s")[0])
        self.p_s = fem.Constant(msh, p0)
        body.add_follower_pressure("sealed", self.p_s)
        # the ring starts touching the groove bottom and the air-side wall
        self.r_g0, self.r_g = center[0] + a - 1e-3 * a, r_g
        self.bottom = Contact(body, "housing", rigid_plane([self.r_g0, 0.0], [-1.0, 0.0]),
                              E / a, name="bottom")
        self.wall = Contact(body, "housing", rigid_plane([0.0, z_w], [0.0, -1.0]), E / a,
                            name="wall")
        # film scales: h_ref of Blok's inverse theory at W_REF, ε relative to 12μℓ²/h_ref³
        h_ref, ell = inverse_film(v.mu, U, W_REF), 0.25 * a
        self.cavitation = cav = cavitation_model(v)
        eps = v.eps * 12 * v.mu * ell**2 / h_ref**3
        self.film = film = Film(body, "lubricated", rigid_plane([r_rod, 0.0], [1.0, 0.0]),
                                Fluid(viscosity(v), density(v, cav)),
                                scales=FilmScales(pressure=max(p0, 1.0), film=h_ref,
                                                  speed=abs(U)),
                                cavitation=named_cavitation(cav, eps),
                                roughness=roughness, V_counter=[0.0, U], supg=v.supg,
                                rtol=1e-8, require_open=True)
        # film rtol 1e-8: the Reynolds rows of the thick-film flanks (h up to 10³ times
        # the film of the contact) have a round-off floor of ≈ 4e-8 mm/s (measured),
        # above 1e-10 of the default
        # p = p_s at the sealed-side end of Γ_l, p = 0 at the air-side end
        zs = film.sub.geometry.x[:, 1]
        z_lo = comm.allreduce(float(zs.min(initial=np.inf)), op=MPI.MIN)
        z_hi = comm.allreduce(float(zs.max(initial=-np.inf)), op=MPI.MAX)
        tol = 1e-8 * a
        if self.user:
            self._check_ends(film, z_lo, z_hi, tol, v.mesh_file)
        sealed = lambda y: np.isclose(y[1], z_lo, atol=tol)   # noqa: E731
        air = lambda y: np.isclose(y[1], z_hi, atol=tol)      # noqa: E731
        if transient is not None:      # reciprocating: the air end open in both strokes
            film.transient(transient, lumped=True)
            self.supply = film.add_inflow(air)
        if cav == "penalty":
            self.p_end = film.add_pressure_bc(sealed, p0)
            film.add_pressure_bc(air, 0.0)
        elif U > 0 or transient is not None:
            # JFO outstroke (a reciprocating film's both strokes): flooded inlet at p_s
            # on the sealed side, an outlet (p = 0 where cavitated) on the air side
            # (a flooded inlet: its pressure's Constant, never None)
            self.p_end = cast("fem.Constant", film.add_inlet(sealed, pressure=p0))
        else:
            # JFO instroke: flooded inlet from the air side, outlet into the sealed fluid
            film.add_inlet(air)
            self.p_end = film.add_reservoir(sealed, p0)
        Xq = film.Q.tabulate_dof_coordinates()
        film.p.x.array[:] = np.where(Xq[:, 1] < center[1], p0, 0.0)
        film.jfo_initial_guess(downstream=(0.0, math.copysign(1.0, U)))
        self.components = [body, film, self.bottom, self.wall]
        # stall_window: over-long mount steps stall far from the solution; cut them early
        self.problem = Problem(self.components, name=name, max_it=40, max_backtracks=10,
                               line_search="admissible", stall_window=10)
        self.iterations: list[Iterations] = []
        self._post: dict[str, Any] | None = None

    @staticmethod
    def _check_ends(film: Film, z_lo: float, z_hi: float, tol: float, path: str) -> None:
        """Raise InputError unless Γ_l is one open curve ending at its z extremes, alone there.

        The end conditions p = p_s at z_lo and p = 0 at z_hi are located by the
        height: each must find one node, the end of the curve.
        """
        ends = film_boundary(film)
        n = film.Q.dofmap.index_map.size_local
        z = film.Q.tabulate_dof_coordinates()[:n, 1]
        comm = film.sub.comm
        at = [comm.allreduce(int(np.sum(np.isclose(z, zk, atol=tol))), op=MPI.SUM)
              for zk in (z_lo, z_hi)]
        ok = len(ends) == 2 and np.allclose(np.sort(ends[:, 1]), [z_lo, z_hi], atol=tol)
        if not ok or at != [1, 1]:
            raise InputError(f"the group 'lubricated' of {path!r} must be one open curve "
                             f"ending at its lowest and highest z, each the only node "
                             f"there (has {len(ends)} end point(s))")

    # -- parameters and continuation ---------------------------------------------------
    def set_pressure(self, p_s: float) -> None:
        """Sealed pressure p_s (MPa) on the sealed arc and at the sealed end of the film."""
        # (DOLFINx types Constant.value's setter NDArray; it takes a float)
        self.p_s.value = float(p_s)  # type: ignore[assignment]
        self.p_end.value = float(p_s)  # type: ignore[assignment]

    @property
    def U(self) -> float:
        """Rod speed (mm/s)."""
        return float(cast("fem.Constant", self.film.V_counter).value[1])   # the rod's

    def _march(self, parameter: ConstantParameter, target: float, steps: int,
               geometric: bool = False) -> None:
        Continuation(self.problem, parameter, record=self.iterations).march(
            target, steps, predictor=False, geometric=geometric)

    def mount(self, steps: int) -> None:
        """Squeeze the ring: the groove bottom is moved to r_g in ``steps``.

        The trace and then the Reynolds equation are first solved alone on the
        initial geometry (the coupled Newton starts from a film pressure
        consistent with the gap).
        """
        film = self.film
        for sub in ([film.u_s], [film.p] + ([film.lam] if film.lam is not None else [])):
            Problem(self.components, unknowns=sub, name="oring_start").solve_by_homotopy()
        self.iterations.append(self.problem.solve_by_homotopy().iterations)
        bottom = cast("AnalyticObstacle", self.bottom.counterpart)   # the rigid plane's
        self._march(ConstantParameter(bottom.offset, 0),
                    self.r_g - self.r_g0, steps)

    def ramp(self, p_s: float, steps: int) -> None:
        """Raise the sealed pressure to ``p_s`` (MPa) in ``steps``."""
        self._march(ConstantParameter(self.p_s, None, on_set=self.set_pressure), p_s, steps)

    def speed(self, U: float, steps: int) -> None:
        """Move the rod speed geometrically to ``U`` (mm/s, same sign) in ``steps``."""
        s = math.copysign(1.0, U)
        rod = cast("fem.Constant", self.film.V_counter)   # the rod's velocity
        self._march(ConstantParameter(rod, 1, scale=s), abs(U), steps,
                    geometric=True)

    # -- results -----------------------------------------------------------------------
    def _forms(self) -> dict[str, Any]:
        if self._post is None:
            body, film = self.body, self.film
            t = ax.follower_pressure_traction(self.p_s, body.u, ufl.FacetNormal(body.mesh))
            ds = body.ds(body.tag("sealed"))
            Qc = fem.functionspace(film.sub, ("DG", 0))
            xs = ufl.SpatialCoordinate(film.sub) + film.u_s
            pts = Qc.element.interpolation_points
            self._post = {
                "sealed": [fem.form(t[i] * body.weight * ds) for i in range(2)],
                "Qc": Qc,
                "q": fem.Expression(ax.film_flux(film.kin, film.p, film.mu_p, film.grad_gamma,
                                                  film.lam),
                                    pts),
                "z": fem.Expression(xs[1], pts)}
        return self._post

    def forces(self) -> dict[str, npt.NDArray[np.float64]]:
        """Return the r, z forces (N, whole circumference) on the ring: film, p_s, bottom, wall."""
        comm = self.body.mesh.comm
        sealed = np.array([comm.allreduce(fem.assemble_scalar(f), op=MPI.SUM)
                           for f in self._forms()["sealed"]])
        return {"film": self.film.force(), "sealed": sealed, "bottom": self.bottom.force(),
                "wall": self.wall.force()}

    def profile(self) -> dict[str, npt.NDArray[np.float64]] | None:
        """Film data on rank 0 (None elsewhere), sorted by the current axial position.

        Nodal: z (current axial position = position on the rod, mm), h (mm), p (MPa)
        and, with JFO cavitation, the void fraction lam (-); cellwise: z_cell, q
        (flux per unit circumference, mm²/s).
        """
        pr = self.film.profile()
        post = self._forms()
        q, zc = fem.Function(post["Qc"]), fem.Function(post["Qc"])
        q.interpolate(post["q"])
        zc.interpolate(post["z"])
        nc = post["Qc"].dofmap.index_map.size_local
        cells = self.body.mesh.comm.gather((zc.x.array[:nc].copy(), q.x.array[:nc].copy()),
                                           root=0)
        if pr is None:
            return None
        z = pr["x"][:, 1]
        o, zcell = np.argsort(z, kind="stable"), np.concatenate([c[0] for c in cells])
        oc = np.argsort(zcell, kind="stable")
        out = {"z": z[o], "h": pr["h"][o], "p": pr["p"][o], "z_cell": zcell[oc],
               "q": np.concatenate([c[1] for c in cells])[oc]}
        if "lam" in pr:
            out["lam"] = pr["lam"][o]
        return out

    def sealed_arc_radii(self) -> list[float]:
        """Return the current radii r (mm) of the end points φ = −135°, −45° of the sealed arc.

        The built section only (a user's section need not have nodes there).
        """
        if self.user:
            raise ValueError("sealed_arc_radii needs the built section (no mesh_file)")
        V, u = self.body.V, self.body.u
        n = V.dofmap.index_map.size_local
        X = V.tabulate_dof_coordinates()
        out = []
        for t in (math.radians(-135), math.radians(-45)):
            pt = np.array(self.center) + self.a * np.array([math.cos(t), math.sin(t)])
            k = np.nonzero(np.linalg.norm(X[:n, :2] - pt, axis=1) < 1e-6 * self.a)[0]
            val = float(X[k[0], 0] + u.x.array[2 * k[0]]) if len(k) else None
            out.append(next(r for r in self.body.mesh.comm.allgather(val) if r is not None))
        return out

    def measures(self) -> dict[str, float]:
        """Film measures on all ranks (see ``UNITS``)."""
        prof = self.profile()
        res = None
        if self.body.mesh.comm.rank == 0:
            assert prof is not None   # rank 0 holds the gathered profile
            z, h, p = prof["z"], prof["h"], prof["p"]
            k, i = int(np.argmax(p)), int(np.argmin(h))
            ps = float(self.p_s.value)
            thr = ps + 0.5 * (p[k] - ps)      # loaded zone: half the rise above p_s
            hot = z[p > thr]
            qz = prof["q"][(prof["z_cell"] > hot.min()) & (prof["z_cell"] < hot.max())]
            if not qz.size:    # a loaded zone of one node (near a reversal): no cell inside
                qz = np.array([np.nan])
            res = {"p_max": float(p[k]), "z_p_max": parabolic_vertex(z, p),
                   "h_at_p_max": float(h[k]),
                   "h_min": float(h[i]), "z_h_min": parabolic_vertex(z, h, "min"),
                   "h_mean": float(np.mean(h[p > thr])), "flux": float(np.median(qz)),
                   "flux_spread": float((qz.max() - qz.min()) / abs(np.median(qz))),
                   "oscillation": oscillation_indicator(h, p, thr)}
        res = self.body.mesh.comm.bcast(res, root=0)
        f = self.film.force()
        circ = 2 * math.pi * self.r_rod
        res["load_per_circumference"] = float(f[0]) / circ
        res["friction_force_per_circumference"] = float(f[1]) / circ
        res["leakage"] = circ * res["flux"]
        return res


def build(v: Params, U: float, mesh: int | None = None, comm: MPI.Comm = MPI.COMM_WORLD,
          name: str = "ehl_oring", **kw: Any) -> ORingSeal:
    """:class:`ORingSeal` of the values ``v`` at speed U (mm/s) and mesh density ``mesh``.

    ``name``: the problem's name, options prefix ``tribofx_<name>_``; ``kw``: the
    seal's ``roughness`` and ``transient``.
    """
    return ORingSeal(v, U, v.mesh if mesh is None else mesh, comm, name, **kw)


def solve_to(seal: ORingSeal, v: Params, U: float, p_s_targets: Sequence[float],
             on_state: Callable[[float], object] | None = None,
             journal: SweepVariant | None = None) -> list[Iterations]:
    """Mount, raise p_s, go to speed U, then the other p_s; on_state(p_s) after each target.

    ``journal``: the stroke's variant of a sweep, which journals the targets as its
    leg ``p_s`` (a resumed run skips the mount and the targets reached, and the next
    ramp starts from the restored state as in an uninterrupted run).  Returns the
    Newton iterations per continuation step.
    """
    for k in journalled_points(journal, "p_s", len(p_s_targets)):
        if k == 0:
            seal.mount(v.mount_steps)
        p_s = p_s_targets[k]
        seal.ramp(p_s, v.ramp_steps)
        if k == 0 and seal.U != U:
            seal.speed(U, v.speed_steps)
        if on_state is not None:
            on_state(p_s)
    return list(seal.iterations)


def axial_balance(seal: ORingSeal) -> float:
    """Sum of the axial forces on the ring relative to the axial force of p_s (−)."""
    f = seal.forces()
    total = sum(val[1] for val in f.values())
    return abs(total) / abs(f["sealed"][1])


def rod_speed(U: float, period: float) -> Callable[[float], npt.NDArray[np.float64]]:
    """Return t ↦ (0, U cos(2πt/T)) (mm/s), the rod's velocity in (r, z)."""
    return lambda t: np.array([0.0, U * math.cos(2 * math.pi * t / period)])


class AirLayer:
    """The layer the rod carries out at the air end and brings back (see the module docstring).

    ``history`` holds the outstroke's (t, c) at the air end, c = θh (mm); kept in
    the stepper's history, so a checkpoint carries it.
    """

    def __init__(self, history: dict[str, list[float]], period: float) -> None:
        self.h, self.period = history, float(period)
        self.h.setdefault("t", [])
        self.h.setdefault("c", [])

    def record(self, t: float, c: float, U: float) -> None:
        """Keep the content c (mm) at the air end at time t (s) while U > 0 (outstroke).

        A time not after the last one kept is skipped (a step cut and tried again
        records its start once).
        """
        if U > 0 and (not self.h["t"] or t > self.h["t"][-1]):
            self.h["t"].append(float(t))
            self.h["c"].append(float(c))

    def supply(self, t: float) -> float:
        """Content brought back at time t (mm): the air end's at the mirror time 2t_r − t."""
        if not self.h["t"]:
            return 0.0       # nothing carried out yet (the supply only acts in an instroke)
        T = self.period
        t_rev = (math.floor(t / T - 0.25) + 0.25) * T    # the last reversal out → in
        return float(np.interp(2 * t_rev - t, self.h["t"], self.h["c"]))


def reforming(U: float, T: float, t: float) -> float:
    """Return ω of the vertex-rule Couette flux at t: 1 in the instroke, 0 in the outstroke.

    In the instroke the starved film from the air end reforms in front of the
    contact; in the outstroke the film ruptures at the air-side outlet
    (:func:`tribofx.forms.jfo.jfo_on_surface`).
    """
    return 1.0 if rod_speed(U, T)(t)[1] < 0 else 0.0


def air_end(seal: ORingSeal) -> tuple[float, float, float]:
    """(θh, h, 2π r) at the air end of the film (the highest z of Γ_l), every rank."""
    prof = seal.film.profile(everywhere=True)
    k = int(np.argmax(prof["X"][:, 1]))
    return (1 - prof["lam"][k]) * prof["h"][k], prof["h"][k], 2 * math.pi * prof["x"][k, 0]


def transient_seal(v: Params, U: float) -> ORingSeal:
    """Build the seal of ``v`` at rod speed U (mm/s), its film transient (``scheme``), unsolved."""
    E_star = 3 * (v.mu1 + v.mu2) / 0.75      # ν = 1/2, the rod rigid
    rough = rough_pair(v.sigma, E_star, v.mu_b) if v.sigma > 0 else None
    return build(v, U, roughness=rough, transient=v.scheme, name="ehl_oring_cycle")


def cycle_stepper(v: Params, checkpoint: str | os.PathLike[str] | None = None,
                  verbose: bool = False, start: bool = True, seal: ORingSeal | None = None
                  ) -> CycleStepper:
    """Build the seal of ``v`` at U, transient, solve its steady outstroke; return the Stepper.

    ``start``: mount and pressurise to the first p_s at U (False: a state to be
    restored from a checkpoint).  ``seal``: a seal of :func:`transient_seal` in
    the state to start from instead (nothing built or solved).  The schedule
    sets, at t_{n+1} of each step, the rod speed, the air end's supply
    (``stepper.layer``, an :class:`AirLayer`, which first records the air end's
    content of the state at t_n) and ω of :func:`reforming`; they are part of the
    state.  Returns the Stepper, with ``stepper.seal`` the
    :class:`~tribofx.cases.ehl_oring.ORingSeal`.
    """
    U, T = v.U, v.period
    if seal is None:
        seal = transient_seal(v, U)
        if start:
            solve_to(seal, v, U, number_list(v.p_s, "p_s")[:1])
    film = seal.film
    layer = AirLayer({}, T)

    def supply(t: float) -> float:
        """Keep the layer of the state at t_n; return the supply brought back at t (s)."""
        layer.record(stepper.t, air_end(seal)[0], rod_speed(U, T)(stepper.t)[1])
        return layer.supply(t)

    assert film.vertex_couette is not None   # a lumped JFO film on a curve has ω
    # (a CycleStepper once it holds its seal and layer, the next line)
    stepper = cast("CycleStepper", Stepper(
        seal.components, film, parameters=[seal.p_s, seal.p_end],
        checkpoint=checkpoint, name="ehl_oring_cycle", verbose=verbose,
        problem_kw={"max_it": 40, "max_backtracks": 10,
                    "line_search": "admissible", "stall_window": 10},
        schedule=[(cast("fem.Constant", film.V_counter), rod_speed(U, T)),
                  (seal.supply, supply),
                  (film.vertex_couette, lambda t: reforming(U, T, t))]))
    stepper.seal, stepper.layer = seal, layer
    return stepper


def run_cycle(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
              checkpoint: str | os.PathLike[str] | None = None, resume: bool = False
              ) -> CycleStepper:
    """Mount, pressurise to the first p_s at U, then step the cycles; returns the stepper."""
    T = v.period
    stepper = cycle_stepper(v, checkpoint, verbose, start=not resume)
    seal, film = stepper.seal, stepper.seal.film
    keys = ("time", "rod_speed", "h_min", "friction_force", "flux_air", "flux_sealed",
            "content", "supply")
    sr = SlowTimeRecords(stepper, v, record, keys, vtx_fields(seal), resume)
    stepper.layer.h = stepper.history.setdefault("air_layer", stepper.layer.h)  # on resume

    def log(st: Stepper, its: int) -> None:
        u = float(cast("fem.Constant", film.V_counter).value[1])   # the rod's speed
        m = seal.measures()
        q_sealed, q_air = film.consistent_fluxes()
        sr.log(its, {"time": st.t, "rod_speed": u, "h_min": m["h_min"],
                     "friction_force": m["friction_force_per_circumference"] * 2 * math.pi
                     * seal.r_rod, "flux_air": q_air, "flux_sealed": q_sealed,
                     "content": film.content(), "supply": float(seal.supply.value)})

    if not resume:
        log(stepper, 0)
    with sr.closing(report=lambda: _report(sr.hist, record, T, seal, v.scheme)):
        stepper.run(v.cycles * T, FixedStep(T / v.cycle_steps), progress=progress,
                    on_step=sr.written(lambda st, rep: log(st, rep.iterations)))
    return stepper


def integral(t: npt.NDArray[np.float64], q: Sequence[float] | npt.NDArray[np.float64],
             scheme: str) -> npt.NDArray[np.float64]:
    """Q(t_n) = ∫₀^t_n q dt by the film's own scheme over the recorded steps ``t`` (s).

    c₀(Q_{n+1} − Q_n) + c₁(Q_n − Q_{n−1}) = Δt_{n+1} q(t_{n+1}), the weights of
    :meth:`tribofx.interfaces.Film.begin_step` (the first
    step, and every step of "euler", backward Euler).  A content whose rate is q
    changes by exactly Q.
    """
    Q, prev = np.zeros(len(t)), 0.0
    for n in range(len(t) - 1):
        dt = t[n + 1] - t[n]
        bdf2 = Scheme.of(scheme).bdf2
        c0, c1 = bdf2_coefficients(dt / prev) if bdf2 and prev > 0 else (1.0, 0.0)
        dQ = Q[n] - Q[n - 1] if n > 0 else 0.0
        Q[n + 1] = Q[n] + (dt * q[n + 1] - c1 * dQ) / c0
        prev = dt
    return Q


def _report(hist: dict[str, list[Any]], record: RunRecord, T: float, seal: ORingSeal,
            scheme: str) -> None:
    """Per-step series, the leakage, intake and content change of each completed cycle, the film."""
    units = {"time": "s", "rod_speed": "mm/s", "h_min": "mm", "friction_force": "N",
             "flux_air": "mm^3/s", "flux_sealed": "mm^3/s", "content": "mm^3",
             "supply": "mm"}
    for key, vals in hist.items():
        record.result(key, vals, units[key])
    t = np.asarray(hist["time"])
    Q = {"leakage": integral(t, hist["flux_air"], scheme),
         "intake": integral(t, hist["flux_sealed"], scheme),
         "content_change": np.asarray(hist["content"])}
    per: dict[str, list[float]] = {key: [] for key in Q}
    for k in range(int(t[-1] / T + 1e-9) if len(t) else 0):
        sel = np.flatnonzero((t >= k * T - 1e-12) & (t <= (k + 1) * T + 1e-12))
        for key, q in Q.items():
            per[key].append(float(q[sel[-1]] - q[sel[0]]))
    for key, vals in per.items():
        record.result(f"{key}_per_cycle", vals, "mm^3")
    if MPI.COMM_WORLD.rank == 0:
        record.profile = {"cycle": hist}
    record.result("time_reached", float(t[-1]) if len(t) else 0.0, "s")
    prof = seal.film.profile(everywhere=True)
    record.result("final_film", np.column_stack([prof["X"][:, 1], prof["h"], prof["p"],
                                                 prof["lam"]]).tolist(),
                  "mm (z), mm (h), MPa (p), - (λ) per node of the film at the last step")


name = "ehl-oring"
#: writes a checkpoint every step: `--resume` continues an interrupted run
resumable = True
doc = "soft-EHL of a reciprocating O-ring seal (axisymmetric, housing contact)"


@dataclass(frozen=True)
class Params(FluidParams):
    """The parameters of ``ehl-oring`` (``--set KEY=VALUE``)."""

    p_s: str = param("1", "MPa", "sealed pressures (comma-separated, increasing)")
    U: float = param(400.0, "mm/s", "rod speed (> 0 outstroke, < 0 instroke)")
    stroke: str = param(
        "single", "-",
        "single (sign of U), both (U and −U, steady) or "
        "cycle (transient: U cos(2πt/period) from the steady outstroke; first p_s; "
        "tribofx.cases.ehl_oring)",
        choices=("single", "both", "cycle"))
    period: float = param(0.1, "s", "stroke=cycle: period of the rod's motion", lower=0)
    cycle_steps: int = param(
        40, "-",
        "stroke=cycle: time steps per period (halved on "
        "Newton failure)",
        lower=4)
    cycles: float = param(1.0, "-", "stroke=cycle: periods to run", lower=0)
    scheme: str = param(
        "euler", "-",
        "stroke=cycle: time scheme of the film, euler "
        "or bdf2",
        choices=("euler", "bdf2"))
    sigma: float = param(
        0.0, "mm",
        "stroke=cycle: RMS roughness σ of the rod (0: "
        "smooth; > 0: mixed film, Patir–Cheng flow, Greenwood–Tripp asperities, "
        "ηβσ = σ/β = 0.1)",
        lower=0, closed=True)
    mu_b: float = param(
        0.1, "-",
        "boundary friction of the asperities (sigma > 0)",
        lower=0, closed=True)
    mu: float = param(5e-8, "MPa·s", "oil viscosity", lower=0)
    mesh: int = param(
        4, "-",
        "mesh density n (element 0.1/n mm on the film arc)",
        lower=1, upper=32, closed=True)
    arc_refine: int | None = param(
        None, "-",
        "halvings of the element size on the film arc "
        "(0.1/(n·2^k) mm; the bulk keeps 0.4/n mm; default: 1 with stroke=cycle, "
        "else 0)",
        lower=0, upper=3, closed=True)
    degree: int = param(1, "-", "Lagrange degree of the displacement", choices=(1, 2))
    formulation: str = formulation_param("mixed")
    squeeze: float = param(0.1, "-", "radial squeeze (d − groove depth)/d", lower=0, upper=0.3)
    d: float = param(3.5, "mm", "cross-section diameter", lower=0)
    r_rod: float = param(10.0, "mm", "rod radius", lower=0)
    mu1: float = param(2.93, "MPa", "Mooney–Rivlin μ₁", lower=0)
    mu2: float = param(0.73, "MPa", "Mooney–Rivlin μ₂", lower=0, closed=True)
    kappa: float = param(3660.0, "MPa", "bulk modulus", lower=0)
    cavitation: str = param(
        "auto", "-",
        "penalty (ε⁻¹ min(p, 0), Swift–Stieber limit), jfo (mass-conserving: void "
        "fraction λ, flooded inlet, natural outlet) or auto: jfo with the mixed solid, "
        "penalty with the displacement one (a locked, zig-zag surface makes JFO's "
        "semismooth iteration cycle)",
        choices=("auto", "penalty", "jfo"))
    eps: float = param(1e-4, "-", "cavitation penalty ε relative to 12μℓ²/h_ref³", lower=0)
    supg: bool = param(True, "-", "SUPG in the Reynolds equation")
    gap0: float = param(0.02, "mm", "initial clearance to the rod", lower=0)
    mount_steps: int = param(10, "-", "squeeze increments", lower=1)
    ramp_steps: int = param(4, "-", "p_s increments per target", lower=1)
    speed_steps: int = param(3, "-", "geometric speed increments", lower=1)
    study: str = param(
        "none", "-",
        "none or mesh (density study, Figs. 18–19)",
        choices=("none", "mesh"))
    mesh_levels: str = param("1,2,4", "-", "densities of study=mesh")
    mesh_file: str = param(
        "", "-",
        "your own cross-section: a 2D gmsh .msh in (r, z) with physical groups "
        "lubricated (Γ_l facing the rod, one open curve), sealed (loaded by p_s), "
        "housing (touches groove bottom/wall); replaces d (its radial extent) and "
        "mesh; moved to r_min = r_rod + gap0, z extent centred at 0")


def validate(v: Params) -> None:
    """Parse the lists and check the consistency of the values."""
    viscosity(v)
    density(v, cavitation_model(v))
    ps = number_list(v.p_s, "p_s")
    if any(p <= 0 for p in ps):
        raise InputError("p_s must be > 0 MPa (frictionless housing: p_s holds the ring)")
    if ps != sorted(ps):
        raise InputError("p_s must be increasing")
    if v.U == 0:
        raise InputError("U must be nonzero (mm/s)")
    if v.stroke == "cycle" and (v.U < 0 or cavitation_model(v) != "jfo"
                                   or v.study != "none"):
        raise InputError("stroke=cycle starts from the outstroke (U > 0) and needs "
                         "cavitation=jfo (mass-conserving) and study=none")
    if v.sigma > 0 and v.stroke != "cycle":
        raise InputError("sigma (a rough rod) is built for stroke=cycle")
    levels = number_list(v.mesh_levels, "mesh_levels")
    if any(k < 1 or k != int(k) for k in levels):
        raise InputError("mesh_levels must be positive integers")
    if v.mesh_file:
        if v.study != "none" or v.arc_refine:
            raise InputError("mesh_file works with study=none and arc_refine=0 only")
    elif v.gap0 >= 0.5 * v.d:
        raise InputError("gap0 must be below the cross-section radius")


UNITS = {"p_max": "MPa", "z_p_max": "mm", "h_at_p_max": "mm", "h_mean": "mm", "h_min": "mm",
         "z_h_min": "mm", "flux": "mm^2/s", "leakage": "mm^3/s",
         "load_per_circumference": "N/mm", "friction_force_per_circumference": "N/mm",
         "oscillation": "-", "flux_spread": "-", "axial_balance": "-"}


def progress_total(v: Params) -> int:
    """Points the progress bar counts: the sealed pressures of every stroke, or the steps."""
    if v.stroke == "cycle":
        return nominal_steps(v.cycles * v.period, v.period / v.cycle_steps)
    return len(number_list(v.p_s, "p_s")) * (1 if v.stroke == "single" else 2)


def run(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
        checkpoint: str | os.PathLike[str] | None = None, resume: bool = False
        ) -> ORingSeal | CycleStepper:
    """Mount, pressurise and solve each stroke; optionally the mesh study.

    ``checkpoint``: directory of the sweep's checkpoint, written after every
    sealed pressure of every stroke (:class:`tribofx.restart.SweepJournal`:
    the seal's state, its records and the number of pressures reached);
    ``resume``: continue from it (a stroke restarts at its next pressure,
    ramped from the saved state; ``study=mesh`` is run again whole).
    """
    record.data["parameters"]["arc_refine"]["value"] = arc_halvings(v)   # as used
    if v.stroke == "cycle":
        return run_cycle(v, record, progress, verbose, checkpoint, resume)
    comm = MPI.COMM_WORLD
    U = v.U
    p_targets = number_list(v.p_s, "p_s")
    journal = SweepJournal(checkpoint, comm, v, resume)
    speeds = [U] if v.stroke == "single" else [abs(U), -abs(U)]
    profiles: dict[str, Any] = {"strokes": {}, "mesh": None, "U": abs(U)}
    prob = None
    for Us in speeds:
        tag = "out" if Us > 0 else "in"
        t_start = time.perf_counter()   # the wall time counts the build too
        prob = build(v, math.copysign(max(abs(Us), 1000.0), Us),
                     name=options_name("ehl_oring", f"{tag}stroke"))
        record.data["num_dofs"] = prob.problem.num_dofs
        state = prob.problem.state_fields() + [prob.p_s, prob.p_end,
                                               cast("fem.Constant", prob.film.V_counter)]
        # u and p at each sealed pressure of the stroke (ParaView time series; the
        # "time" is the index of the state, its p_s in series_points)
        sv = SweepVariant(journal, tag, prob, state, record, vtx_fields(prob),
                          f"{tag}stroke_", {"states": [], "measures": [], "wall_time": 0.0},
                          comm, progress, progress_key="points", newton=False)
        rec = sv.records
        points, states, measures = rec["points"], rec["states"], rec["measures"]
        t0 = t_start - rec["wall_time"]
        if sv.resumed:
            sv.resume()
            prob.problem.refresh()
            prob.iterations.extend(rec["its"])
        for p_s, m in zip(points, measures):
            _record(record, tag, p_s, m)

        def on_state(p_s: float, prob: ORingSeal = prob, tag: str = tag,
                     rec: dict[str, Any] = rec, sv: SweepVariant = sv, t0: float = t0) -> None:
            sv.write(p_s)
            m = prob.measures()
            m["axial_balance"] = axial_balance(prob)
            rec["measures"].append(m)
            _record(record, tag, p_s, m)
            pr = prob.profile()
            if pr is not None:
                rec["states"].append({"p_s": p_s,
                                      **{k: pr[k].tolist() for k in ("z", "h", "p")}})
            if progress is not None:
                progress.update(1)
            rec["its"][:] = list(prob.iterations)
            rec["wall_time"] = time.perf_counter() - t0

        with sv:
            its = solve_to(prob, v, Us, p_targets, on_state, journal=sv)
        record.data["newton_iterations"].append({tag: its})
        record.result(f"{tag}_wall_time", time.perf_counter() - t0, "s")
        profiles["strokes"][tag] = states
    if v.study == "mesh":
        profiles["mesh"] = mesh_study(v, record)
    record.result("p_s", p_targets, "MPa")
    if comm.rank == 0:
        record.profile = profiles
    assert prob is not None   # one or two strokes, each builds its seal
    return prob


def _record(record: RunRecord, tag: str, p_s: float, m: Mapping[str, float]) -> None:
    """Record the results of one sealed pressure of a stroke (``<tag>_ps<p_s>_…``)."""
    for k, unit in UNITS.items():
        record.result(f"{tag}_ps{p_s:g}_{k}", m[k], unit)


def mesh_study(v: Params, record: RunRecord) -> list[dict[str, Any]]:
    """Outstroke at the first p_s on the densities ``levels``; returns the profiles."""
    rows: list[dict[str, Any]]
    out: list[dict[str, Any]]
    rows, out = [], []
    U = abs(v.U)
    for n in [int(k) for k in number_list(v.mesh_levels, "mesh_levels")]:
        t0 = time.perf_counter()
        seal = build(v, max(U, 1000.0), mesh=n, name=options_name("ehl_oring", f"density{n}"))
        its = solve_to(seal, v, U, number_list(v.p_s, "p_s")[:1])
        m = seal.measures()
        row: dict[str, Any]
        row = {"mesh": n, "num_dofs": seal.problem.num_dofs, "h_at_p_max": m["h_at_p_max"],
               "h_mean": m["h_mean"],
               "h_min": m["h_min"], "p_max": m["p_max"], "oscillation": m["oscillation"],
               "newton_iterations": its, "wall_time": time.perf_counter() - t0}
        if rows:
            row["d_h_mean"] = abs(row["h_mean"] - rows[-1]["h_mean"]) / row["h_mean"]
        rows.append(row)
        pr = seal.profile()
        if pr is not None:
            out.append({"mesh": n, **{k: pr[k].tolist() for k in ("z", "h", "p")}})
    record.result("mesh_study", rows)
    return out


def vtx_fields(seal: ORingSeal | CycleStepper) -> dict[str, list[fem.Function]]:
    """Displacement (bulk) and film pressure (Γ_l submesh) of the seal (or its cycle's)."""
    seal = cast("ORingSeal", getattr(seal, "seal", seal))   # a cycle's stepper holds it
    return {"displacement": [seal.body.u], "pressure": [seal.film.p]}


def plot(profile: dict[str, Any], outdir: Path) -> None:
    """``profiles.png`` (Fig. 17) and ``mesh_study.png`` (Figs. 18–19), or ``cycle.png``."""
    if "cycle" in profile:
        plot_oring_cycle(profile["cycle"], outdir)
    else:
        plot_oring(profile, outdir)

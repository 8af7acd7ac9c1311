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
  p = p_s / 0 at the sealed / air end, penalty cavitation ε⁻¹ min(p, 0), SUPG;
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

Default data (mm, N, s, MPa), after Stupkiewicz (2009) and Stupkiewicz &
Marciniszyn (Tribol. Int. 42, 2009) where the chapter fixes them:

* μ₁ + μ₂ = 3.66 MPa (chapter §8.1); split μ₁ = 2.93, μ₂ = 0.73 (μ₂/μ₁ = 0.25,
  a common ratio for NBR, our choice); κ = 1000 (μ₁ + μ₂) = 3660 MPa;
* d = 3.5 mm, r_rod = 10 mm, squeeze 10 % (typical dynamic O-ring gland);
* oil viscosity μ = 5e-8 MPa·s (0.05 Pa·s), U = 400 mm/s (Fig. 18: outstroke,
  p_s = 1 MPa, U = 400 mm/s);
* mesh density n: element size 0.1/n mm on Γ_l, 0.4/n mm in the bulk; P1
  displacement (default; the chapter's zigzag film oscillations come from the
  piecewise-linear boundary), P1 pressure.

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

import math
import time

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from .. import interrupt
from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms import ehl_axisym as ax
from ..interfaces import Contact, Film
from ..meshes.oring import HOUSING, LUBRICATED, SEALED, oring_section
from ..meshes.user import read_user_mesh
from ..obstacles import rigid_plane
from ..output import VTXSeries
from ..params import InputError, Param, number_list
from ..plots import plot_oring
from ..positions import oscillation_indicator, parabolic_vertex
from ..problem import NewtonDivergence, Problem
from ..references import inverse_film
from ..restart import SweepJournal, sweep_stem
from .film_setup import film_boundary

__all__ = ["EHLORingCase", "ORingSeal", "axial_balance", "build", "solve_to"]

P_MOUNT = 0.1        # MPa, sealed pressure during the squeeze
W_REF = 20.0         # MPa/mm, nominal inlet gradient of the film scale h_ref
NAMES = {"lubricated": LUBRICATED, "sealed": SEALED, "housing": (SEALED, HOUSING)}
USER_GROUPS = ("lubricated", "sealed", "housing")   # the groups of a user's section


def geometry(v, extent=None):
    """Centre, radius, rod radius, final groove bottom and air-side wall (mm).

    ``extent``: the half extents (r, z) of a user's section (None: the built
    circle, radius d/2); the centre is that of its bounding box, the radius a
    the radial half extent, d = 2a.
    """
    a, b = extent if extent is not None else (0.5 * v["d"],) * 2
    r_rod = v["r_rod"]
    center = (r_rod + a + v["gap0"], 0.0)
    return center, a, r_rod, r_rod + 2 * a * (1 - v["squeeze"]), b - 0.005


def _user_section(v, comm):
    """Read a user's section, move it into place (see the module docstring).

    Returns ``(mesh, facet_tags, names, (a, b))``, a and b the half extents in r
    and z (mm).
    """
    msh, ft, tags = read_user_mesh(v["mesh_file"], comm, 2, USER_GROUPS)
    x = msh.geometry.x
    lo = np.array([comm.allreduce(float(np.min(x[:, k], initial=np.inf)), op=MPI.MIN)
                   for k in range(2)])
    hi = np.array([comm.allreduce(float(np.max(x[:, k], initial=-np.inf)), op=MPI.MAX)
                   for k in range(2)])
    a, b = 0.5 * (hi - lo)
    if v["gap0"] >= a:
        raise InputError(f"gap0 = {v['gap0']} mm must be below half the radial extent of "
                         f"the section ({a:.4g} mm)")
    x[:, 0] += v["r_rod"] + v["gap0"] - lo[0]
    x[:, 1] -= 0.5 * (lo[1] + hi[1])
    names = {"lubricated": tags["lubricated"], "sealed": tags["sealed"],
             "housing": (tags["sealed"], tags["housing"])}
    return msh, ft, names, (a, b)


class ORingSeal:
    """The configured seal: ``body``, ``film``, ``bottom``/``wall`` contacts, ``problem``.

    ``p_s`` (Constant, MPa) loads the sealed arc and is mirrored into the film's
    Dirichlet value at the sealed end; the groove bottom moves by the offset of
    ``bottom.counterpart``; the rod speed is ``film.V_counter[1]`` (mm/s).
    """

    def __init__(self, v, U, mesh, comm):
        self.user = bool(v["mesh_file"])
        if self.user:
            msh, ft, names, extent = _user_section(v, comm)
        else:
            extent, names = None, NAMES
        center, a, r_rod, r_g, z_w = geometry(v, extent)
        self.center, self.a, self.r_rod = center, a, r_rod
        if not self.user:
            msh, _, ft = oring_section(*center, a, mesh, comm=comm)
        mat = {"mu1": v["mu1"], "mu2": v["mu2"], "kappa": v["kappa"]}
        E = 3 * (mat["mu1"] + mat["mu2"])
        deg = v["degree"]
        self.body = body = Body(msh, ft, names, "axisymmetric", ("mooney-rivlin", mat),
                                degree=deg, quadrature_degree=2 * deg, name="oring")
        p0 = min(P_MOUNT, number_list(v["p_s"], "p_s")[0])
        self.p_s = fem.Constant(msh, p0)
        body.add_follower_pressure("sealed", self.p_s)
        # the ring starts touching the groove bottom and the air-side wall
        self.r_g0, self.r_g = center[0] + a - 1e-3 * a, r_g
        self.bottom = Contact(body, "housing", rigid_plane([self.r_g0, 0.0], [-1.0, 0.0]),
                              E / a, name="bottom")
        self.wall = Contact(body, "housing", rigid_plane([0.0, z_w], [0.0, -1.0]), E / a,
                            name="wall")
        # film scales: h_ref of Blok's inverse theory at W_REF, ε relative to 12μℓ²/h_ref³
        h_ref, ell = inverse_film(v["mu"], U, W_REF), 0.25 * a
        self.film = film = Film(body, "lubricated", rigid_plane([r_rod, 0.0], [1.0, 0.0]),
                                v["mu"], V_counter=[0.0, U], supg=v["supg"],
                                cavitation="penalty",
                                eps=v["eps"] * 12 * v["mu"] * ell**2 / h_ref**3,
                                p_c=max(p0, 1.0), film_scale=h_ref, speed_scale=abs(U),
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
            self._check_ends(film, z_lo, z_hi, tol, v["mesh_file"])
        self.p_end = film.add_pressure_bc(lambda y: np.isclose(y[1], z_lo, atol=tol), p0)
        film.add_pressure_bc(lambda y: np.isclose(y[1], z_hi, atol=tol), 0.0)
        Xq = film.Q.tabulate_dof_coordinates()
        film.p.x.array[:] = np.where(Xq[:, 1] < center[1], p0, 0.0)
        self.components = [body, film, self.bottom, self.wall]
        # stall_window: over-long mount steps stall far from the solution; cut them early
        self.problem = Problem(self.components, name="ehl_oring", max_it=40, max_backtracks=10,
                               line_search="admissible", stall_window=10)
        self.iterations = []
        self._post = None

    @staticmethod
    def _check_ends(film, z_lo, z_hi, tol, path):
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
    def set_pressure(self, p_s):
        """Sealed pressure p_s (MPa) on the sealed arc and at the sealed end of the film."""
        self.p_s.value = float(p_s)
        self.p_end.value = float(p_s)

    @property
    def U(self):
        """Rod speed (mm/s)."""
        return float(self.film.V_counter.value[1])

    def _march(self, parameter, target, steps, geometric=False):
        Continuation(self.problem, parameter, record=self.iterations).march(
            target, steps, predictor=False, geometric=geometric)

    def mount(self, steps):
        """Squeeze the ring: the groove bottom is moved to r_g in ``steps``.

        The trace and then the Reynolds equation are first solved alone on the
        initial geometry (the coupled Newton starts from a film pressure
        consistent with the gap).
        """
        for sub in ([self.film.u_s], [self.film.p]):
            Problem(self.components, unknowns=sub, name="oring_start").solve()
        self.iterations.append(self.problem.solve().iterations)
        self._march(ConstantParameter(self.bottom.counterpart.offset, 0),
                    self.r_g - self.r_g0, steps)

    def ramp(self, p_s, steps):
        """Raise the sealed pressure to ``p_s`` (MPa) in ``steps``."""
        self._march(ConstantParameter(self.p_s, None, on_set=self.set_pressure), p_s, steps)

    def speed(self, U, steps):
        """Move the rod speed geometrically to ``U`` (mm/s, same sign) in ``steps``."""
        s = math.copysign(1.0, U)
        self._march(ConstantParameter(self.film.V_counter, 1, scale=s), abs(U), steps,
                    geometric=True)

    # -- results -----------------------------------------------------------------------
    def _forms(self):
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
                "q": fem.Expression(ax.film_flux(film.kin, film.p, film.mu_c, film.grad_gamma),
                                    pts),
                "z": fem.Expression(xs[1], pts)}
        return self._post

    def forces(self):
        """Return the r, z forces (N, whole circumference) on the ring: film, p_s, bottom, wall."""
        comm = self.body.mesh.comm
        sealed = np.array([comm.allreduce(fem.assemble_scalar(f), op=MPI.SUM)
                           for f in self._forms()["sealed"]])
        return {"film": self.film.force(), "sealed": sealed, "bottom": self.bottom.force(),
                "wall": self.wall.force()}

    def profile(self):
        """Film data on rank 0 (None elsewhere), sorted by the current axial position.

        Nodal: z (current axial position = position on the rod, mm), h (mm), p (MPa);
        cellwise: z_cell, q (flux per unit circumference, mm²/s).
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
        return {"z": z[o], "h": pr["h"][o], "p": pr["p"][o], "z_cell": zcell[oc],
                "q": np.concatenate([c[1] for c in cells])[oc]}

    def sealed_arc_radii(self):
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

    def measures(self):
        """Film measures on all ranks (see ``EHLORingCase.UNITS``)."""
        prof = self.profile()
        res = None
        if self.body.mesh.comm.rank == 0:
            z, h, p = prof["z"], prof["h"], prof["p"]
            k, i = int(np.argmax(p)), int(np.argmin(h))
            ps = float(self.p_s.value)
            thr = ps + 0.5 * (p[k] - ps)      # loaded zone: half the rise above p_s
            hot = z[p > thr]
            qz = prof["q"][(prof["z_cell"] > hot.min()) & (prof["z_cell"] < hot.max())]
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


def build(v, U, mesh=None, comm=MPI.COMM_WORLD):
    """:class:`ORingSeal` of the values ``v`` at speed U (mm/s) and mesh density ``mesh``."""
    return ORingSeal(v, U, v["mesh"] if mesh is None else mesh, comm)


def solve_to(seal, v, U, p_s_targets, on_state=None, done=0):
    """Mount, raise p_s, go to speed U, then the other p_s; on_state(p_s) after each target.

    ``done``: the number of targets already reached by the state of ``seal``
    (restored from a checkpoint; the mount and those targets are skipped, the
    next ramp starts from that state as in an uninterrupted run).  Returns the
    Newton iterations per continuation step.
    """
    if done == 0:
        seal.mount(v["mount_steps"])
    for k, p_s in enumerate(p_s_targets[done:], start=done):
        seal.ramp(p_s, v["ramp_steps"])
        if k == 0 and seal.U != U:
            seal.speed(U, v["speed_steps"])
        if on_state is not None:
            on_state(p_s)
    return list(seal.iterations)


def axial_balance(seal):
    """Sum of the axial forces on the ring relative to the axial force of p_s (−)."""
    f = seal.forces()
    total = sum(val[1] for val in f.values())
    return abs(total) / abs(f["sealed"][1])


class EHLORingCase:
    """Case ``ehl-oring``; see the module docstring."""

    name = "ehl-oring"
    doc = "soft-EHL of a reciprocating O-ring seal (axisymmetric, housing contact)"
    params = (
        Param("p_s", str, "1", "MPa", "sealed pressures (comma-separated, increasing)"),
        Param("U", float, 400.0, "mm/s", "rod speed (> 0 outstroke, < 0 instroke)"),
        Param("stroke", str, "single", "-", "single (sign of U) or both (U and −U)",
              choices=("single", "both")),
        Param("mu", float, 5e-8, "MPa·s", "oil viscosity", lower=0),
        Param("mesh", int, 4, "-", "mesh density n (element 0.1/n mm on the film arc)",
              lower=1, upper=32, closed=True),
        Param("degree", int, 1, "-", "Lagrange degree of the displacement", choices=(1, 2)),
        Param("squeeze", float, 0.1, "-", "radial squeeze (d − groove depth)/d", lower=0,
              upper=0.3),
        Param("d", float, 3.5, "mm", "cross-section diameter", lower=0),
        Param("r_rod", float, 10.0, "mm", "rod radius", lower=0),
        Param("mu1", float, 2.93, "MPa", "Mooney–Rivlin μ₁", lower=0),
        Param("mu2", float, 0.73, "MPa", "Mooney–Rivlin μ₂", lower=0, closed=True),
        Param("kappa", float, 3660.0, "MPa", "bulk modulus", lower=0),
        Param("eps", float, 1e-4, "-", "cavitation penalty ε relative to 12μℓ²/h_ref³",
              lower=0),
        Param("supg", bool, True, "-", "SUPG in the Reynolds equation"),
        Param("gap0", float, 0.02, "mm", "initial clearance to the rod", lower=0),
        Param("mount_steps", int, 10, "-", "squeeze increments", lower=1),
        Param("ramp_steps", int, 4, "-", "p_s increments per target", lower=1),
        Param("speed_steps", int, 3, "-", "geometric speed increments", lower=1),
        Param("study", str, "none", "-", "none or mesh (density study, Figs. 18–19)",
              choices=("none", "mesh")),
        Param("mesh_levels", str, "1,2,4", "-", "densities of study=mesh"),
        Param("mesh_file", str, "", "-",
              "your own cross-section: a 2D gmsh .msh in (r, z) with physical groups "
              "lubricated (Γ_l facing the rod, one open curve), sealed (loaded by p_s), "
              "housing (touches groove bottom/wall); replaces d (its radial extent) and "
              "mesh; moved to r_min = r_rod + gap0, z extent centred at 0"),
    )

    @staticmethod
    def validate(v):
        """Parse the lists and check the consistency of the values."""
        ps = number_list(v["p_s"], "p_s")
        if any(p <= 0 for p in ps):
            raise InputError("p_s must be > 0 MPa (frictionless housing: p_s holds the ring)")
        if ps != sorted(ps):
            raise InputError("p_s must be increasing")
        if v["U"] == 0:
            raise InputError("U must be nonzero (mm/s)")
        levels = number_list(v["mesh_levels"], "mesh_levels")
        if any(k < 1 or k != int(k) for k in levels):
            raise InputError("mesh_levels must be positive integers")
        if v["mesh_file"]:
            if v["study"] != "none":
                raise InputError("mesh_file works with study=none only")
        elif v["gap0"] >= 0.5 * v["d"]:
            raise InputError("gap0 must be below the cross-section radius")

    @staticmethod
    def progress_total(v):
        """Points the progress bar counts: the sealed pressures of every stroke."""
        return len(number_list(v["p_s"], "p_s")) * (1 if v["stroke"] == "single" else 2)

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, checkpoint=None, resume=False):
        """Mount, pressurise and solve each stroke; optionally the mesh study.

        ``checkpoint``: directory of the sweep's checkpoint, written after every
        sealed pressure of every stroke (:class:`tribofx.restart.SweepJournal`:
        the seal's state, its records and the number of pressures reached);
        ``resume``: continue from it (a stroke restarts at its next pressure,
        ramped from the saved state; ``study=mesh`` is run again whole).
        """
        comm = MPI.COMM_WORLD
        U = v["U"]
        p_targets = number_list(v["p_s"], "p_s")
        journal = SweepJournal(checkpoint, comm, v, resume)
        speeds = [U] if v["stroke"] == "single" else [abs(U), -abs(U)]
        profiles = {"strokes": {}, "mesh": None, "U": abs(U)}
        prob = None
        for Us in speeds:
            tag = "out" if Us > 0 else "in"
            rec = journal.records(tag, points=[], states=[], measures=[], its=[],
                                  wall_time=0.0)
            points, states, measures = rec["points"], rec["states"], rec["measures"]
            done = len(points)
            t0 = time.perf_counter() - rec["wall_time"]
            prob = build(v, math.copysign(max(abs(Us), 1000.0), Us))
            interrupt.arm()   # gmsh resets the SIGTERM handler
            record.data["num_dofs"] = prob.problem.num_dofs
            state = prob.problem.state_fields() + [prob.p_s, prob.p_end, prob.film.V_counter]
            if done:
                journal.restore(tag, state)
                prob.problem.refresh()
                prob.iterations.extend(rec["its"])
                if progress is not None:   # the states restored by a resume
                    progress.update(done)
            for p_s, m in zip(points, measures):
                cls._record(record, tag, p_s, m)
            # u and p at each sealed pressure of the stroke (ParaView time series; the
            # "time" is the index of the state, its p_s in series_points; a resumed
            # stroke writes its states into series of their own; one restored complete,
            # none)
            series = VTXSeries(comm, getattr(record, "outdir", None),
                               {sweep_stem(f"{tag}stroke_{k}_series", done): f
                                for k, f in cls.vtx_fields(prob).items()})
            record.data.setdefault("series_points", {})[tag] = points

            def on_state(p_s, prob=prob, tag=tag, rec=rec, series=series, state=state, t0=t0):
                rec["points"].append(p_s)
                series.write(len(rec["points"]) - 1)
                m = prob.measures()
                m["axial_balance"] = axial_balance(prob)
                rec["measures"].append(m)
                cls._record(record, tag, p_s, m)
                pr = prob.profile()
                if pr is not None:
                    rec["states"].append({"p_s": p_s,
                                          **{k: pr[k].tolist() for k in ("z", "h", "p")}})
                if progress is not None:
                    progress.update(1)
                rec["its"], rec["wall_time"] = list(prob.iterations), time.perf_counter() - t0
                journal.save(tag, state, rec, {"reached": len(rec["points"])})

            try:
                its = solve_to(prob, v, Us, p_targets, on_state, done=done)
            except (NewtonDivergence, interrupt.Interrupted) as err:
                err.problem = prob
                raise
            finally:
                series.close()
            record.data["newton_iterations"].append({tag: its})
            record.result(f"{tag}_wall_time", time.perf_counter() - t0, "s")
            profiles["strokes"][tag] = states
        if v["study"] == "mesh":
            profiles["mesh"] = cls.mesh_study(v, record)
        record.result("p_s", p_targets, "MPa")
        if comm.rank == 0:
            record.profile = profiles
        return prob

    @classmethod
    def _record(cls, record, tag, p_s, m):
        """Record the results of one sealed pressure of a stroke (``<tag>_ps<p_s>_…``)."""
        for k, unit in cls.UNITS.items():
            record.result(f"{tag}_ps{p_s:g}_{k}", m[k], unit)

    UNITS = {"p_max": "MPa", "z_p_max": "mm", "h_at_p_max": "mm", "h_mean": "mm", "h_min": "mm",
             "z_h_min": "mm", "flux": "mm^2/s", "leakage": "mm^3/s",
             "load_per_circumference": "N/mm", "friction_force_per_circumference": "N/mm",
             "oscillation": "-", "flux_spread": "-", "axial_balance": "-"}

    @classmethod
    def mesh_study(cls, v, record):
        """Outstroke at the first p_s on the densities ``levels``; returns the profiles."""
        rows, out = [], []
        U = abs(v["U"])
        for n in [int(k) for k in number_list(v["mesh_levels"], "mesh_levels")]:
            t0 = time.perf_counter()
            seal = build(v, max(U, 1000.0), mesh=n)
            its = solve_to(seal, v, U, number_list(v["p_s"], "p_s")[:1])
            m = seal.measures()
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

    @staticmethod
    def vtx_fields(seal):
        """Displacement (bulk) and film pressure (Γ_l submesh)."""
        return {"displacement": [seal.body.u], "pressure": [seal.film.p]}

    @staticmethod
    def plot(profile, outdir):
        """``profiles.png`` (Fig. 17) and ``mesh_study.png`` (Figs. 18–19)."""
        plot_oring(profile, outdir)

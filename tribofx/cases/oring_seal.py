"""The O-ring seal of ``ehl-oring`` (chapter §8.1) as a configured object, and its continuation.

:class:`ORingSeal` builds the axisymmetric Mooney–Rivlin ring, the film on
the rod (:class:`tribofx.interfaces.Film`, penalty cavitation, SUPG) and the
frictionless contacts with the groove bottom and the air-side wall, in one
monolithic :class:`tribofx.problem.Problem`; it mounts the ring, ramps the
sealed pressure and the rod speed, and reports the film measures.
:func:`solve_to` is the continuation of one stroke, :func:`axial_balance` the
equilibrium check.  The case (parameters, strokes, checkpoints, plots) is
:mod:`tribofx.cases.ehl_oring`.
"""

import math

import numpy as np
from dolfinx import fem
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..interfaces import Contact, Film
from ..meshes.oring import HOUSING, LUBRICATED, SEALED, oring_section
from ..meshes.user import read_user_mesh
from ..obstacles import rigid_plane
from ..params import InputError, number_list
from ..problem import Problem
from ..references import inverse_film
from .film_setup import arc_halvings, cavitation_model, density, film_boundary, viscosity
from .oring_outputs import SealOutputs

__all__ = ["NAMES", "USER_GROUPS", "ORingSeal", "axial_balance", "build", "geometry", "solve_to"]

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


class ORingSeal(SealOutputs):
    """The configured seal: ``body``, ``film``, ``bottom``/``wall`` contacts, ``problem``.

    ``p_s`` (Constant, MPa) loads the sealed arc and is mirrored into the film's
    Dirichlet value at the sealed end; the groove bottom moves by the offset of
    ``bottom.counterpart``; the rod speed is ``film.V_counter[1]`` (mm/s).
    ``roughness``: a rough rod (mixed film); ``transient``: the time scheme of a
    reciprocating film (:mod:`.oring_cycle`: the lumped content rate, an open air
    end supplied with the content ``supply``).
    """

    def __init__(self, v, U, mesh, comm, name="ehl_oring", roughness=None, transient=None):
        self.user = bool(v["mesh_file"])
        if self.user:
            msh, ft, names, extent = _user_section(v, comm)
        else:
            extent, names = None, NAMES
        center, a, r_rod, r_g, z_w = geometry(v, extent)
        self.center, self.a, self.r_rod = center, a, r_rod
        if not self.user:
            msh, _, ft = oring_section(*center, a, mesh, h_l=0.1 / 2 ** arc_halvings(v),
                                       comm=comm)
        mat = {"mu1": v["mu1"], "mu2": v["mu2"], "kappa": v["kappa"]}
        E = 3 * (mat["mu1"] + mat["mu2"])
        deg = v["degree"]
        self.body = body = Body(msh, ft, names, "axisymmetric", ("mooney-rivlin", mat),
                                degree=deg, quadrature_degree=2 * deg, name="oring",
                                formulation=v["formulation"])
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
        self.cavitation = cav = cavitation_model(v)
        self.film = film = Film(body, "lubricated", rigid_plane([r_rod, 0.0], [1.0, 0.0]),
                                viscosity(v), density=density(v), V_counter=[0.0, U],
                                supg=v["supg"], cavitation=cav, roughness=roughness,
                                eps=(v["eps"] * 12 * v["mu"] * ell**2 / h_ref**3
                                     if cav == "penalty" else None),
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
            self.p_end = film.add_inlet(sealed, pressure=p0)
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
        film = self.film
        for sub in ([film.u_s], [film.p] + ([film.lam] if film.lam is not None else [])):
            Problem(self.components, unknowns=sub, name="oring_start").solve_by_homotopy()
        self.iterations.append(self.problem.solve_by_homotopy().iterations)
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


def build(v, U, mesh=None, comm=MPI.COMM_WORLD, name="ehl_oring", **kw):
    """:class:`ORingSeal` of the values ``v`` at speed U (mm/s) and mesh density ``mesh``.

    ``name``: the problem's name, options prefix ``tribofx_<name>_``; ``kw``: the
    seal's ``roughness`` and ``transient``.
    """
    return ORingSeal(v, U, v["mesh"] if mesh is None else mesh, comm, name, **kw)


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

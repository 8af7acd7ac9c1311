"""Ironing: a stiff half-cylinder die pressed into and slid along a soft slab (2D).

The benchmark of large-deformation frictional sliding of Yang, Laursen & Meng
(IJNME 62, 2005): a neo-Hookean slab [0, L] × [0, H] (bottom held) and a die of
radius R, centred above the slab at x = R/2 + 1 and touching its top, E_die =
1000 E_slab.  The die's flat top is moved down by ``depth`` in ``press_steps``,
then along the slab by ``slide`` in ``slide_steps``; Coulomb friction μ.  The
slab's top is the slave (the finer, softer surface), the die's arc the master
(:class:`~tribofx.interfaces.TwoBodyContact`: every slave node finds its
segment on the current die surface, so nodes change segment while sliding).

Your own die (``mesh_file``): a 2D gmsh ``.msh`` with the physical groups
``arc`` (its lower boundary, the master surface) and ``top`` (where the
pressing and sliding motion is prescribed), read and checked by
:func:`tribofx.meshes.user.read_user_mesh` and placed as the case places its
own: the case's die spans R on either side of its axis x_c = R/2 + 1 and its
lowest point touches the slab's top, so a user's die of half-width b (half its
x extent) is moved so that its x extent is centred on x_c = b/2 + 1 and its
lowest ``arc`` node is on y = H (:meth:`_user_die`).  b replaces
``R`` (R = b for the case's die; the slide-off check uses it) and is reported
as ``die_half_width``; one-line error if part of the die lies below its
lowest arc node or ``top`` reaches down to it (``arc`` is not its lower
boundary).  The die's element size h_die is the mean length of its arc facets
within b of (x_c, H) (the part of the arc the slab slides along; the case's
own die has h = L/n on the whole arc), and ρ_N = E/min(L/n, h_die) (the finer
of the two surfaces, as in ``contact-two-cylinders``); reported as
``die_element_size``.

Results: the reaction force on the die (horizontal F_x, vertical F_y per unit
thickness) at every step, their ratio in steady sliding (the second half of
the sliding steps), a smoothness measure of that history, max |Δ²F| / max |F|
(second differences of the per-step forces: a node-to-segment scheme shows a
kink each time a slave node passes a master vertex), and the equilibrium of
the solved die (its support reaction, from the die's own rows, against the
contact force).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from dolfinx import fem
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms.hyperelastic import lame_parameters
from ..interfaces import TwoBodyContact
from ..meshes.block import NAMES, block_mesh
from ..meshes.ironing import ARC, TOP, die_body
from ..meshes.user import boundary_facet_size, read_user_mesh
from ..params import CaseParams, InputError, param
from ..problem import NewtonDivergence, Problem

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence
    from pathlib import Path

    import numpy.typing as npt
    from tqdm import tqdm

    from ..body import Material
    from ..output import RunRecord

__all__ = ["Model", "Params", "build", "check_slide", "doc", "name", "plot", "progress_total",
           "report", "resumable", "run", "validate", "vtx_fields"]


def _slab(comm: MPI.Comm, L: float, H: float, nx: int, ny: int, material: Material) -> Body:
    msh, tags = block_mesh(comm, (0.0, 0.0), (L, H), nx, ny)
    return Body(msh, tags, NAMES, "plane_strain", material, name="slab")


name = "contact-ironing"
resumable = False   # no per-step checkpoint
doc = "stiff half-cylinder die pressed into and slid along a soft neo-Hookean slab"


@dataclass(frozen=True)
class Params(CaseParams):
    """The parameters of ``contact-ironing`` (``--set KEY=VALUE``)."""

    E: float = param(1.0, "MPa", "Young's modulus of the slab (the die: 1000 E)", lower=0)
    nu: float = param(0.3, "-", "Poisson's ratio of slab and die", lower=-1, upper=0.5)
    friction: float = param(0.3, "-", "Coulomb coefficient", lower=0, closed=True)
    R: float = param(3.0, "mm", "die radius", lower=0)
    L: float = param(9.0, "mm", "slab length", lower=0)
    H: float = param(1.0, "mm", "slab height", lower=0)
    depth: float = param(0.5, "mm", "indentation of the die", lower=0)
    slide: float = param(4.0, "mm", "sliding distance of the die", lower=0)
    n: int = param(60, "-", "slab elements along its length", lower=4, upper=2000)
    press_steps: int = param(5, "-", "indentation steps", lower=1, upper=10000)
    slide_steps: int = param(40, "-", "sliding steps", lower=1, upper=10000)
    mesh_file: str = param(
        "", "-",
        "your own die: a 2D gmsh .msh with physical groups arc (its lower boundary, "
        "in contact) and top (moved); its x extent centred on b/2 + 1 (b its "
        "half-width, which replaces R) and its lowest arc point put on the slab top "
        "y = H; rho_N = E/min(L/n, h), h its arc facet size within b of that point")


def validate(v: Params) -> None:
    """Reject a die that would slide off the slab or indent through it.

    With ``mesh_file`` the die's half-width is known only once the mesh is
    read: :meth:`build` checks the slide then (:meth:`check_slide`).
    """
    if v.depth >= v.H:
        raise InputError("depth must be below the slab height H")
    if not v.mesh_file:
        check_slide(v, v.R)


def check_slide(v: Params, b: float) -> None:
    """Reject a slide that takes the axis of a die of half-width ``b`` off the slab."""
    if 0.5 * b + 1 + v.slide > v.L:
        if v.mesh_file:
            raise InputError(f"the die would slide off the slab: slide > L − b/2 − 1 = "
                             f"{v.L - 0.5 * b - 1:.6g} mm (b = {b:.6g} mm: the "
                             f"half-width of the die in {v.mesh_file!r})")
        raise InputError("the die would slide off the slab: slide > L − R/2 − 1")


@dataclass
class Model:
    """What :func:`build` assembles: the slab, the die, their contact, the problem.

    ``motion``: the Dirichlet value of the die's top (its prescribed displacement, a Constant);
    ``b``: the die's half-width at the slab, ``h_die``: its contact element size (mm).
    """

    slab: Body
    die: Body
    contact: TwoBodyContact
    problem: Problem
    motion: fem.Constant
    b: float
    h_die: float


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD) -> Model:
    """Slab (slave), die (master), contact, problem and the die's prescribed motion.

    The :class:`Model` also holds the die's half-width ``b`` (R, or from ``mesh_file``)
    and its arc element size ``h_die``.
    """
    h = v.L / v.n
    if v.mesh_file:
        # (without ``cells``: the mesh, its facet tags and their names)
        dmsh, dtags, names = cast("tuple[dmesh.Mesh, dmesh.MeshTags, dict[str, int]]",
                                  read_user_mesh(v.mesh_file, comm, 2, ("arc", "top")))
        b, h_die = _user_die(dmsh, dtags, names, v)
    else:
        b, h_die, names = v.R, h, {"arc": ARC, "top": TOP}
        dmsh, dtags = die_body(v.R, 0.5 * v.R + 1.0, v.H + v.R, h, comm)
    mu, lmbda = lame_parameters(v.E, v.nu)
    slab = _slab(comm, v.L, v.H, v.n, max(2, round(v.H / h)),
                 ("neo-hookean", {"mu": mu, "lmbda": lmbda}))
    slab.add_dirichlet("bottom", np.zeros(2))
    mu_d, lmbda_d = lame_parameters(1000 * v.E, v.nu)
    die = Body(dmsh, dtags, names, "plane_strain",
               ("neo-hookean", {"mu": mu_d, "lmbda": lmbda_d}), name="die")
    motion = die.add_dirichlet("top", np.zeros(2))
    contact = TwoBodyContact(slab, "top", die, "arc", rho_n=v.E / min(h, h_die),
                             friction=v.friction)
    problem = Problem([slab, die, contact], name="ironing", max_it=40)
    return Model(slab, die, contact, problem, motion, b, h_die)


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: the indentation's, then the sliding's."""
    return v.press_steps + v.slide_steps


def run(v: Params, record: RunRecord, progress: tqdm | None = None,
        verbose: bool = False) -> Model:
    """Press, then slide; the die's reaction force at every converged step."""
    run = build(v)
    contact, problem, motion = run.contact, run.problem, run.motion
    record.data["num_dofs"] = problem.num_dofs
    record.result("die_half_width", run.b, "mm")
    record.result("die_element_size", run.h_die, "mm")
    history: list[list[float]] = []

    def reaction() -> None:
        on_die = contact.forces(problem)[1]
        history.append([float(motion.value[0]), float(motion.value[1]),
                        float(on_die[0]), float(on_die[1])])
        if progress is not None:
            progress.update(1)

    try:
        # secant predictor from the second step of each phase (its start state
        # remembered): without it the first iterate of a step has zero slip
        # increments, every node that slid in the last step sits exactly on the
        # Coulomb cone, and round-off (which differs between partitions) picks
        # stick or slip for its first tangent
        for index, target, steps in ((1, -v.depth, v.press_steps),
                                     (0, v.slide, v.slide_steps)):
            phase = Continuation(problem, ConstantParameter(motion, index),
                                 verbose=verbose, on_accept=reaction,
                                 record=record.data["newton_iterations"])
            phase.remember()
            phase.march(target, steps)
    except NewtonDivergence as err:
        err.model = run
        raise
    finally:
        report(history, v, record)
        on_die = contact.forces(problem)[1]
        die = run.die
        record.result("equilibrium_error", [abs(die.reaction("top", c) + float(on_die[c]))
                                            for c in (0, 1)], "N/mm")
        record.result("equilibrium_bound", die.V.dofmap.index_map.size_global * 2
                      * die.tolerances()[die.u].atol, "N/mm")
    return run


def report(history: Sequence[Sequence[float]], v: Params, record: RunRecord) -> None:
    """Force history, friction ratio and smoothness of the sliding phase."""
    hist = np.array(history).reshape(-1, 4)
    record.result("die_position", hist[:, :2].tolist(), "mm")
    record.result("reaction_force", hist[:, 2:].tolist(), "N/mm")
    sliding = hist[v.press_steps:]
    steady = sliding[len(sliding) // 2:]     # past the transition to steady sliding
    if len(steady) >= 3:
        F = steady[:, 2:]
        record.result("force_ratio_sliding",
                      float(np.median(np.abs(F[:, 0] / F[:, 1]))), "-")
        d2 = np.abs(np.diff(F, 2, axis=0)).max(axis=0) / np.abs(F).max(axis=0)
        record.result("smoothness_Fx", float(d2[0]), "-")
        record.result("smoothness_Fy", float(d2[1]), "-")
    if MPI.COMM_WORLD.rank == 0:
        record.profile = {"position": hist[:, :2], "force": hist[:, 2:],
                          "press_steps": v.press_steps}


def vtx_fields(run: Model) -> dict[str, list[fem.Function]]:
    """Displacements of slab and die."""
    return {"slab": [run.slab.u], "die": [run.die.u]}


def plot(profile: Mapping[str, Any], outdir: Path) -> None:
    """Reaction force history of the die (``reaction.png``)."""
    from ..plots import pyplot

    plt = pyplot()
    F = profile["force"]
    k = np.arange(len(F))
    fig, ax = plt.subplots(figsize=(6, 3.8))
    ax.plot(k, F[:, 0], ".-", label="F_x (tangential)")
    ax.plot(k, F[:, 1], ".-", label="F_y (normal)")
    ax.axvline(profile["press_steps"] - 0.5, color="k", lw=0.6)
    ax.set_xlabel("step (pressing, then sliding)")
    ax.set_ylabel("reaction on the die (N/mm)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(outdir / "reaction.png", dpi=110)
    plt.close(fig)


def _user_die(msh: dmesh.Mesh, ft: dmesh.MeshTags, names: Mapping[str, int],
              v: Params) -> tuple[float, float]:
    """Place a user's die as the case places its own; return (half-width b, h_die).

    The x extent is centred on x_c = b/2 + 1 and the lowest ``arc`` node put
    on the slab's top y = H.  One-line :class:`InputError` if a node of the
    die lies below that point, or a node of ``top`` as low as it, by more
    than 1e-9 of the die's size (the arc is not its lower boundary: the die
    would start inside the slab, or press it with a face that is not in
    contact), or if the slide takes x_c off the slab (:meth:`check_slide`).
    h_die is the mean length of the arc facets within b of (x_c, H)
    (:func:`tribofx.meshes.user.boundary_facet_size`).
    """
    comm, x = msh.comm, msh.geometry.x

    def extent(a: npt.NDArray[np.float64]) -> tuple[float, float]:
        return (comm.allreduce(float(np.min(a, initial=np.inf)), op=MPI.MIN),
                comm.allreduce(float(np.max(a, initial=-np.inf)), op=MPI.MAX))

    (lo, hi), (ylo, yhi) = extent(x[:, 0]), extent(x[:, 1])
    b = 0.5 * (hi - lo)
    check_slide(v, b)

    def nodes(name: str) -> npt.NDArray[np.int32]:
        return np.unique(dmesh.entities_to_geometry(msh, 1, ft.find(names[name]),
                                                    False).ravel())

    y0, tol = extent(x[nodes("arc"), 1])[0], 1e-9 * max(hi - lo, yhi - ylo)
    y_top = extent(x[nodes("top"), 1])[0]
    path = v.mesh_file
    if ylo < y0 - tol:
        raise InputError(f"the die in {path!r} reaches {y0 - ylo:.4g} mm below its "
                         "lowest 'arc' node: 'arc' must be its lower boundary")
    if y_top <= y0 + tol:
        raise InputError(f"the die in {path!r} has 'top' as low as its lowest 'arc' "
                         "node: 'arc' must be its lower boundary")
    xc = 0.5 * b + 1.0
    x[:, 0] += xc - 0.5 * (lo + hi)
    x[:, 1] += v.H - y0
    return b, boundary_facet_size(msh, ft, names["arc"], near=((xc, v.H), b))

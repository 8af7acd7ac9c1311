"""Contact patch test: two elastic blocks, non-matching meshes, uniform pressure.

The slave block [0, 1] × [0, 0.5] lies on the master block [0, 1] × [−0.5, 0]
(the same neo-Hookean material); a dead nominal traction (0, −p) loads the
slave's top, the master's bottom is on rollers (u_y = 0) and both left sides
on rollers (u_x = 0).  The homogeneous deformation (nominal stress −p e_y⊗e_y,
the same in both blocks: no relative slip) is the exact solution, so a
formulation that passes the patch test transmits the nominal contact traction
T_N = −p at every slave node.  ``mesh_ratio`` is the number of slave elements
per master element along the interface (> 1: slave finer).

Why the single-pass node-to-segment scheme (slave-node quadrature) passes or
fails: the homogeneous state is a discrete solution iff the master nodal
forces Σ_i w_i p N_a(ξ̄_i) equal the consistent loads p ∫ N_a dx.  The slave
nodes integrate with the trapezoidal rule over the slave elements, which is
exact for a master hat function N_a iff its kinks (the master nodes) are slave
nodes: meshes nested with the slave finer (integer ``mesh_ratio``) pass the
test to solver tolerance; a coarser slave (master nodes between slave nodes
receive no force) or non-nested meshes do not.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import ufl
from dolfinx import mesh
from mpi4py import MPI

from ..body import Body
from ..forms.hyperelastic import lame_parameters
from ..interfaces import TwoBodyContact
from ..params import CaseParams, InputError, param
from ..problem import Problem

if TYPE_CHECKING:
    from collections.abc import Mapping
    from pathlib import Path

    from dolfinx import fem
    from tqdm import tqdm

    from ..body import Material
    from ..output import RunRecord

__all__ = ["Model", "Params", "build", "doc", "name", "patch_block", "plot", "progress_total",
           "resumable", "run", "validate", "vtx_fields"]


def patch_block(comm: MPI.Comm, y0: float, y1: float, n: int, name: str,
                material: Material) -> Body:
    """Block [0, 1] × [y0, y1] with n × max(2, n/2) cells, boundaries bottom, top, left."""
    msh = mesh.create_rectangle(comm, [[0.0, y0], [1.0, y1]], [n, max(2, n // 2)],
                                diagonal=mesh.DiagonalType.left)
    fdim = msh.topology.dim - 1
    where = {1: lambda x: np.isclose(x[1], y0), 2: lambda x: np.isclose(x[1], y1),
             3: lambda x: np.isclose(x[0], 0.0)}
    ents = [mesh.locate_entities_boundary(msh, fdim, f) for f in where.values()]
    e = np.concatenate(ents)
    v = np.concatenate([np.full(len(x), t, np.int32) for t, x in zip(where, ents)])
    e, first = np.unique(e, return_index=True)   # corner facets: the first tag
    tags = mesh.meshtags(msh, fdim, e, v[first])
    return Body(msh, tags, {"bottom": 1, "top": 2, "left": 3}, "plane_strain", material,
                name=name)


name = "contact-patch"
resumable = False   # no per-step checkpoint
doc = "contact patch test: two elastic blocks, non-matching meshes, uniform pressure"


@dataclass(frozen=True)
class Params(CaseParams):
    """The parameters of ``contact-patch`` (``--set KEY=VALUE``)."""

    mesh_ratio: float = param(
        2.0, "-",
        "slave elements per master element (> 1: finer)",
        lower=0.0, upper=16.0, closed=True)
    n_master: int = param(
        8, "-",
        "master elements along the interface",
        lower=1, upper=512, closed=True)
    E: float = param(10.0, "MPa", "Young's modulus of both blocks", lower=0)
    nu: float = param(0.3, "-", "Poisson's ratio of both blocks", lower=-1, upper=0.5)
    pressure: float = param(0.1, "MPa", "nominal pressure on the slave's top", lower=0)


def validate(v: Params) -> None:
    """Require at least two slave elements along the interface (a patch, not a point)."""
    n_s = round(v.mesh_ratio * v.n_master)
    if n_s < 2:
        raise InputError(f"mesh_ratio·n_master = {v.mesh_ratio * v.n_master:g} gives "
                         f"{n_s} slave element(s): the patch test needs at least 2")


@dataclass
class Model:
    """What :func:`build` assembles: the two blocks, their contact, the problem."""

    slave: Body
    master: Body
    contact: TwoBodyContact
    problem: Problem


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD) -> Model:
    """Slave and master blocks, contact and problem."""
    mu, lmbda = lame_parameters(v.E, v.nu)
    mat = ("neo-hookean", {"mu": mu, "lmbda": lmbda})
    n_s = round(v.mesh_ratio * v.n_master)
    slave = patch_block(comm, 0.0, 0.5, n_s, "slave", mat)
    master = patch_block(comm, -0.5, 0.0, v.n_master, "master", mat)
    slave.add_traction("top", ufl.as_vector([0.0, -v.pressure]))
    slave.add_dirichlet("left", 0.0, component=0)
    master.add_dirichlet("left", 0.0, component=0)
    master.add_dirichlet("bottom", 0.0, component=1)
    h = 1.0 / max(n_s, v.n_master)
    contact = TwoBodyContact(slave, "bottom", master, "top", rho_n=v.E / h)
    problem = Problem([slave, master, contact], name="contact_patch")
    return Model(slave, master, contact, problem)


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: the one solve."""
    return 1


def run(v: Params, record: RunRecord, progress: tqdm | None = None,
        verbose: bool = False) -> Model:
    """Solve once; record the mean and the largest relative deviation of the traction."""
    run = build(v)
    contact, problem = run.contact, run.problem
    record.data["num_dofs"] = problem.num_dofs
    record.data["newton_iterations"].append(problem.solve_by_homotopy(verbose=verbose).iterations)
    d = contact.nodal_data(problem)
    comm = contact.slave.mesh.comm
    w, t = d["weight_ref"], -d["T_n"]
    mean = comm.allreduce(float(np.sum(w * t)), op=MPI.SUM) / \
        comm.allreduce(float(np.sum(w)), op=MPI.SUM)
    dev = comm.allreduce(float(np.max(np.abs(t - mean), initial=0.0)), op=MPI.MAX)
    record.result("pressure_mean", mean, "MPa")
    record.result("pressure_max_deviation", dev / mean)
    record.result("nodes_in_contact", comm.allreduce(int(np.sum(d["active"])), op=MPI.SUM))
    prof = contact.gather_profile(problem)
    if comm.rank == 0:
        assert prof is not None     # gathered on rank 0
        record.profile = {"x": prof["X"][:, 0], "p": -prof["T_n"], "p_ref": v.pressure}
    if progress is not None:
        progress.update(1)
    return run


def vtx_fields(run: Model) -> dict[str, list[fem.Function]]:
    """Displacements of both blocks."""
    return {"slave": [run.slave.u], "master": [run.master.u]}


def plot(profile: Mapping[str, Any], outdir: Path) -> None:
    """Nominal contact pressure along the interface (``pressure.png``)."""
    from ..plots import pyplot

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5.5, 3.5))
    ax.plot(profile["x"], profile["p"], "o-", ms=3, label="slave nodes")
    ax.axhline(profile["p_ref"], color="k", lw=0.8, label="applied pressure")
    ax.set_xlabel("X (mm)")
    ax.set_ylabel("nominal contact pressure (MPa)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(outdir / "pressure.png", dpi=110)
    plt.close(fig)

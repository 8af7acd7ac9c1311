"""Stability of explicit wear: the critical step (eq. 31) of the pin and of the ball on a flat.

* :func:`pin_critical_step` — largest stable explicit Δt of the flat pin, from the
  growth of a node-to-node alternating wear-depth perturbation;
* :func:`ball_critical_step` — largest stable explicit Δt of the ball on a flat
  from a developed scar, from the growth of the pressure nonuniformity;
* :func:`oscillation_ratio`, :func:`checkerboard_amplitude`,
  :func:`pressure_nonuniformity` — the measures they use.

Both critical steps bisect with :func:`tribofx.stability.bisect_critical_step`;
the chapter gives only the scaling Δt_cr ∼ h/E.  Units: s, mm.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from mpi4py import MPI

from ..cases import wear_ball_flat
from ..cases.wear_ball_flat import MODEL_FRACTION
from ..output import SubRecord
from ..stability import bisect_critical_step, growth_probe

if TYPE_CHECKING:
    from types import ModuleType

    import numpy.typing as npt

    from ..cases import wear_pin
    from ..interfaces import Contact, Wear

__all__ = ["OSCILLATION_TOL", "ball_critical_step", "checkerboard_amplitude",
           "oscillation_ratio", "pin_critical_step", "pressure_nonuniformity",
           "seed_checkerboard"]

OSCILLATION_TOL = 0.7  # unstable: node-to-node oscillating part of the error > 70 %


def oscillation_ratio(err: npt.ArrayLike) -> float:
    """Share of the node-to-node alternating mode in a nodal error e_i (nodes sorted by X̂).

    ‖(e_{i−1} − 2 e_i + e_{i+1})/4‖ / ‖e_i‖ over the interior nodes: ≈ 1 for an
    alternating (checkerboard) error, O((h/L)²) for a smooth one.
    """
    err = np.asarray(err, dtype=float)
    hp = (err[:-2] - 2 * err[1:-1] + err[2:]) / 4
    den = np.linalg.norm(err[1:-1])
    return float(np.linalg.norm(hp) / den) if den > 0 else 0.0


def seed_checkerboard(wear: Wear, W: float, n: int, eps: float) -> None:
    """Add a wear-depth perturbation ε(−1)^i to the contact nodes x_i = −W/2 + i h of a flat pin."""
    w = wear.body.w
    X = w.function_space.tabulate_dof_coordinates()
    on = np.isclose(X[:, 1], 0.0, atol=1e-9 * W)
    i = np.rint((X[on, 0] + W / 2) / (W / n)).astype(int)
    w.x.array.reshape(-1, 2)[on, 1] += eps * (-1.0) ** i
    w.x.scatter_forward()


def checkerboard_amplitude(wear: Wear) -> float:
    """Amplitude of the node-to-node alternating mode of the wear depth on Γ̂_c (mm).

    Projection of d_i − mean(d) onto (−1)^i − mean((−1)^i), nodes sorted by X̂;
    the same value on every rank.
    """
    d = wear.gather_shape(root_only=False)
    assert d is not None   # root_only=False: the dict on every rank
    depth = d["depth"] - np.mean(d["depth"])
    s = (-1.0) ** np.arange(len(depth))
    s -= s.mean()
    return float(depth @ s / (s @ s))


def pin_critical_step(case: ModuleType, v: wear_pin.Params, n: int, lo: float, hi: float,
                      steps: int = 3, iters: int = 12,
                      eps: float = 1e-6) -> tuple[float, list[tuple[float, float]]]:
    """Largest stable Δt (s) of the explicit scheme on an n × n flat-ended pin (eq. 31).

    The stability probe: the flat pin in the homogeneous state (parameters ``v``
    of ``wear-pin``, R_tip forced to 0; ``case`` the pin case,
    the module :mod:`tribofx.cases.wear_pin`, whose ``build`` and ``load_up`` make
    it) gets a node-to-node alternating wear-depth
    perturbation of amplitude ε (the highest mode the mesh carries, i.e. the
    first to go unstable), the contact problem is re-solved, and ``steps``
    explicit steps are taken.  Forward Euler multiplies that mode by g = 1 − Δt kV S
    per step (S: pressure per unit depth of the mode, ∝ E/h), so Δt is stable iff
    the amplitude does not grow, |a_steps| ≤ |a_0|; a Newton failure or inverted
    mesh also counts as unstable.  Bisection on log Δt in [lo, hi] (lo stable, hi
    unstable, both checked).  Returns ``(dt_cr, probe)`` with ``probe`` the list of
    (Δt, a_steps/a_0) evaluated.
    """
    v = v.replace(scheme="explicit", R_tip=0.0)
    stepper, load = case.build(v, n=n)
    case.load_up(stepper, load, v)
    seed_checkerboard(stepper.wear, v.W, n, eps)
    stepper.problem.solve_by_homotopy()
    stepper.problem.commit()
    start = stepper.state()
    a0 = checkerboard_amplitude(stepper.wear)
    probe: list[tuple[float, float]] = []
    growth = growth_probe(stepper, start, steps,
                          lambda: checkerboard_amplitude(stepper.wear) / a0, probe)
    dt_cr = bisect_critical_step(growth, lo, hi, iters, probe=probe)
    stepper.restore(start)
    return dt_cr, probe


def pressure_nonuniformity(contact: Contact) -> float:
    """Relative standard deviation of the nodal contact pressure over the inner scar.

    Area-weighted over the active nodes within 0.7 of the contact radius of the
    half disc (the edge nodes carry partial lumped areas); 0 for a uniform pressure.
    """
    comm = contact.body.mesh.comm
    d = contact.nodal_data()
    area = comm.allreduce(float(np.sum(d["weight"][d["active"]])), op=MPI.SUM)
    a_c = math.sqrt(area / (MODEL_FRACTION * math.pi))
    r = np.linalg.norm(d["x"][:, :2], axis=1)
    sel = d["active"] & (r < 0.7 * a_c)
    w, p = d["weight"][sel], d["p"][sel]
    sw, swp, swp2 = (comm.allreduce(float(np.sum(x)), op=MPI.SUM) for x in (w, w * p, w * p * p))
    if sw <= 0:
        return math.inf
    mean = swp / sw
    return math.sqrt(max(swp2 / sw - mean * mean, 0.0)) / mean if mean > 0 else math.inf


def ball_critical_step(v: wear_ball_flat.Params, t0: float, lo: float, hi: float, steps: int = 5,
                       iters: int = 4, growth_tol: float = 2.0, comm: MPI.Comm = MPI.COMM_WORLD
                       ) -> tuple[float, list[tuple[float, float]]]:
    """Largest stable explicit Δt (s) of ``wear-ball-flat`` from a developed scar (bisection).

    The implicit scheme (``v.dt``) runs to ``t0`` on the mesh of ``v``; its
    state is copied into an explicit stepper on the same mesh, which takes one
    step of Δt and then ``steps`` more.  Wear evens out the pressure (the
    continuous problem is dissipative): an unstable Δt amplifies the highest
    mode geometrically, a stable one leaves the pressure nonuniformity
    (:func:`pressure_nonuniformity`) near its value after the first step.  The
    first step is the reference, not the state at t0: the implicit state is not
    on the explicit scheme's path, and its first step jumps to that path's
    nonuniformity whatever Δt (on a scar the implicit scheme has made very even,
    e.g. 7.5e-4 with the chapter's §5.2 element size, the jump alone is a factor
    of about 25).  Δt counts as stable iff the nonuniformity after the ``steps`` steps is
    at most ``growth_tol`` times the one after the first and no step fails
    (Newton divergence, force not reached, inverted mesh).  Bisection on log Δt
    in [lo, hi] (lo stable, hi unstable, both checked).  Returns ``(dt_cr,
    probe)``, ``probe`` the list of (Δt, nonuniformity ratio).
    """
    rec = SubRecord()
    implicit = wear_ball_flat.run(v.replace(scheme="implicit"), rec, comm=comm, t_stop=t0)
    start = implicit.state()
    stepper = wear_ball_flat.build(v.replace(scheme="explicit"), comm=comm).stepper
    if not np.array_equal(stepper.wear.body.mesh.geometry.x, implicit.wear.body.mesh.geometry.x):
        raise RuntimeError("rebuilt mesh differs from the implicit run's: cannot restore its state")
    probe: list[tuple[float, float]] = []
    growth = growth_probe(stepper, start, steps,
                          lambda: pressure_nonuniformity(stepper.wear.contact), probe, settle=1)
    return bisect_critical_step(growth, lo, hi, iters, tol=growth_tol, probe=probe), probe

"""Separation of time scales for wear under cyclic loading (chapter §4.2, eqs. 21–23; §5.1).

The deformation problem is solved on the *fast* time scale τ at a fixed worn
shape Ψ(·, t) (eq. 21): one loading cycle of duration Δτ is a standard
frictional contact problem (Lagrangian, incremental Coulomb friction).  The
wear increment of the cycle (eq. 22) is accumulated node by node from the
dissipation form (14),

    ΔW = Σ_j K T_T^j · Δs_j,      K = k/μ,

over the fast sub-steps j (Δs_j the slip increment of the node relative to the
rigid countersurface, T_T^j the nominal friction traction per unit initial
area), so stick phases (at stroke reversals) produce no wear.  The average rate
W̄̇ = ΔW/Δτ (eq. 23) drives the shape evolution law (28) on the *slow* time t
with the θ-scheme:

    (w_{n+1} − w_n)·a = −Δt [(1 − θ) W̄̇(w_n) + θ W̄̇(w_{n+1})],

θ = 0 explicit (one cycle per slow step, as in §5.1); θ > 0 by fixed-point
(Picard) iteration, each iterate re-solving a cycle on the predicted shape.

Reciprocating cycle (chapter §5.1, flat countersurface moving along e_x): at
the start of every slow step the contact memory is erased and the flat is put
at the left-most position −A (A = stroke/2); a run-in stage slides it to the
centre (fully developed sliding), then the cycle +A, −2A (to −A), +A (back to
the centre) follows: sliding distance 2·stroke per cycle, Δτ = 2·stroke/V.
Units: mm, s, MPa.
"""

import numpy as np

from .newton import NewtonDivergence

__all__ = ["ReciprocatingCycle", "TimeScaleDriver"]


class ReciprocatingCycle:
    """One fast-time reciprocating stroke cycle of the rigid countersurface.

    Args:
        stroke: peak-to-peak travel 2A (mm).
        fast_steps: sub-steps per cycle (multiple of 4; the run-in stage uses a quarter).
        V: sliding speed (mm/s); the cycle lasts Δτ = 2·stroke/V.
        axis: direction of the motion (component index of the obstacle offset).
    """

    def __init__(self, stroke, fast_steps, V, axis=0):
        if fast_steps % 4 or fast_steps < 4:
            raise ValueError(f"fast_steps = {fast_steps} must be a positive multiple of 4")
        if stroke <= 0 or V <= 0:
            raise ValueError("stroke and V must be positive")
        self.stroke, self.fast_steps, self.V, self.axis = stroke, fast_steps, V, axis
        A, m = stroke / 2, fast_steps // 4
        self.run_in = -A + A * np.arange(1, m + 1) / m  # −A → 0
        up = A * np.arange(1, m + 1) / m
        # 0 → +A → −A → 0
        self.positions = np.concatenate([up, A - A * np.arange(1, 2 * m + 1) / m, -A + up])

    @property
    def period(self):
        """Δτ (s)."""
        return 2 * self.stroke / self.V

    @property
    def distance(self):
        """Sliding distance of the countersurface per cycle, 2·stroke (mm)."""
        return 2 * self.stroke


class TimeScaleDriver:
    """Slow-time θ-scheme driven by the cycle-averaged wear rate (eqs. 21–23).

    Args:
        prob: :class:`tribofx.wear_problem.WearProblem` built with Lagrangian
            friction and ``averaged=True``; its state must be a converged contact
            solution.
        cycle: :class:`ReciprocatingCycle`.
        theta: 0 (explicit) … 1 (implicit) on the slow time.
        picard_tol: relative tolerance of the fixed-point iteration (θ > 0) on the
            nodal shape-change increment.
        max_picard: iterations allowed before the step is refused.
    """

    def __init__(self, prob, cycle, theta=0.0, picard_tol=1e-8, max_picard=20):
        if not prob.averaged or prob.lam_t is None or prob.settings.slip != "lagrangian":
            raise ValueError("TimeScaleDriver needs a WearProblem with Lagrangian friction "
                             "and averaged=True")
        self.prob, self.cycle, self.theta = prob, cycle, float(theta)
        self.picard_tol, self.max_picard = picard_tol, max_picard
        self.last_increment = None
        self.last_picard = 0

    def _move(self, pos, verbose):
        p = self.prob
        p.obstacle.offset.value[self.cycle.axis] = pos
        return p.solve(verbose=verbose).iterations

    def run_cycle(self, verbose=False):
        """Solve one loading cycle at the current (fixed) shape; returns (ΔW nodal, Newton its).

        The contact memory is erased first (friction multiplier 0, projection
        history at the current state) with the flat at −A, then the run-in and
        the cycle sub-steps are solved; ΔW = Σ_j K T_T·Δs_j (eq. 22) over the
        cycle sub-steps only.
        """
        p = self.prob
        its = self.restart(verbose)
        dW = np.zeros_like(p.rate_bar.x.array)
        for pos in self.cycle.positions:
            its += self._move(pos, verbose)
            dW += p.nodal_wear_increment()
            p.commit()
        return dW, its

    def step(self, dt, verbose=False):
        """Advance the slow time by Δt (s), i.e. Δt/Δτ cycles; returns total Newton iterations.

        On failure the state at entry is restored and :class:`NewtonDivergence`
        (or :class:`tribofx.wear_problem.MeshInversion`) is raised.
        """
        p = self.prob
        saved = p.state()
        tau = self.cycle.period
        try:
            dW, its = self.run_cycle(verbose)
            rate_n = dW / tau  # eq. 23
            w0 = p.w.x.array.copy()
            p.shape_step(dt, rate_n, verbose)
            self.last_picard = 0
            if self.theta > 0:
                dw_prev = p.w.x.array - w0
                for it in range(1, self.max_picard + 1):
                    dW1, its1 = self.run_cycle(verbose)
                    its += its1
                    rate = (1 - self.theta) * rate_n + self.theta * dW1 / tau
                    p.w.x.array[:] = w0
                    p.shape_step(dt, rate, verbose)
                    dw = p.w.x.array - w0
                    change = float(np.max(np.abs(dw - dw_prev), initial=0.0))
                    scale = float(np.max(np.abs(dw), initial=0.0))
                    change = p.mesh.comm.allreduce(change, op=_max())
                    scale = p.mesh.comm.allreduce(scale, op=_max())
                    dw_prev = dw
                    self.last_picard = it
                    if change <= self.picard_tol * max(scale, 1e-300):
                        break
                else:
                    raise NewtonDivergence(f"Picard iteration of the θ-scheme did not converge "
                                           f"in {self.max_picard} cycles")
                dW = dW1
            p.w_n.x.array[:] = w0
            # deformation on the new shape (at the centre, fully developed sliding)
            its += self.restart(verbose)
        except NewtonDivergence:
            p.restore(saved)
            raise
        self.last_increment = dW
        return its

    def restart(self, verbose=False):
        """Erase the contact memory, put the flat at −A and slide it to the centre (no wear).

        Returns the Newton iterations spent.
        """
        p = self.prob
        its = 0
        p.lam_t.x.array[:] = 0.0
        p.obstacle.offset.value[self.cycle.axis] = -self.cycle.stroke / 2
        p.commit()
        its += p.solve(verbose=verbose).iterations
        p.commit()
        for pos in self.cycle.run_in:
            its += self._move(pos, verbose)
            p.commit()
        return its


def _max():
    from mpi4py import MPI

    return MPI.MAX

"""The strokes of the O-ring seal (chapter §8.1): the run, its records and the mesh study.

:class:`ORingRun` is a base class of :class:`tribofx.cases.ehl_oring.EHLORingCase`.
"""

import math
import time

from mpi4py import MPI

from ..params import number_list
from ..plots import plot_oring, plot_oring_cycle
from ..problem import options_name
from ..restart import SweepJournal
from ..stepper import nominal_steps
from ..sweep import SweepVariant
from .film_setup import arc_halvings
from .oring_cycle import run_cycle
from .oring_seal import axial_balance, build, solve_to

__all__ = ["ORingRun"]


class ORingRun:
    """The strokes of the O-ring seal (chapter §8.1): the run, its records and the mesh study."""

    @staticmethod
    def progress_total(v):
        """Points the progress bar counts: the sealed pressures of every stroke, or the steps."""
        if v["stroke"] == "cycle":
            return nominal_steps(v["cycles"] * v["period"], v["period"] / v["cycle_steps"])
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
        record.data["parameters"]["arc_refine"]["value"] = arc_halvings(v)   # as used
        if v["stroke"] == "cycle":
            return run_cycle(cls, v, record, progress, verbose, checkpoint, resume)
        comm = MPI.COMM_WORLD
        U = v["U"]
        p_targets = number_list(v["p_s"], "p_s")
        journal = SweepJournal(checkpoint, comm, v, resume)
        speeds = [U] if v["stroke"] == "single" else [abs(U), -abs(U)]
        profiles = {"strokes": {}, "mesh": None, "U": abs(U)}
        prob = None
        for Us in speeds:
            tag = "out" if Us > 0 else "in"
            t_start = time.perf_counter()   # the wall time counts the build too
            prob = build(v, math.copysign(max(abs(Us), 1000.0), Us),
                         name=options_name("ehl_oring", f"{tag}stroke"))
            record.data["num_dofs"] = prob.problem.num_dofs
            state = prob.problem.state_fields() + [prob.p_s, prob.p_end, prob.film.V_counter]
            # u and p at each sealed pressure of the stroke (ParaView time series; the
            # "time" is the index of the state, its p_s in series_points)
            sv = SweepVariant(journal, tag, prob, state, record, cls.vtx_fields(prob),
                              f"{tag}stroke_", {"states": [], "measures": [], "wall_time": 0.0},
                              comm, progress, progress_key="points", newton=False)
            rec = sv.records
            points, states, measures = rec["points"], rec["states"], rec["measures"]
            done = len(points)
            t0 = t_start - rec["wall_time"]
            if done:
                sv.resume()
                prob.problem.refresh()
                prob.iterations.extend(rec["its"])
            for p_s, m in zip(points, measures):
                cls._record(record, tag, p_s, m)

            def on_state(p_s, prob=prob, tag=tag, rec=rec, sv=sv, t0=t0):
                sv.write(p_s)
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
                rec["its"][:] = list(prob.iterations)
                rec["wall_time"] = time.perf_counter() - t0
                sv.save({"reached": len(rec["points"])})

            with sv:
                its = solve_to(prob, v, Us, p_targets, on_state, done=done)
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

    @classmethod
    def mesh_study(cls, v, record):
        """Outstroke at the first p_s on the densities ``levels``; returns the profiles."""
        rows, out = [], []
        U = abs(v["U"])
        for n in [int(k) for k in number_list(v["mesh_levels"], "mesh_levels")]:
            t0 = time.perf_counter()
            seal = build(v, max(U, 1000.0), mesh=n, name=options_name("ehl_oring", f"density{n}"))
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
        """Displacement (bulk) and film pressure (Γ_l submesh) of the seal (or its cycle's)."""
        seal = getattr(seal, "seal", seal)
        return {"displacement": [seal.body.u], "pressure": [seal.film.p]}

    @staticmethod
    def plot(profile, outdir):
        """``profiles.png`` (Fig. 17) and ``mesh_study.png`` (Figs. 18–19), or ``cycle.png``."""
        if "cycle" in profile:
            plot_oring_cycle(profile["cycle"], outdir)
        else:
            plot_oring(profile, outdir)

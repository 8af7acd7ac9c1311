"""The load steps of the Hertz cases and their comparison with Hertz: run, results, plots.

:class:`HertzRun` is a base class of :class:`tribofx.cases.hertz.HertzCase`.
"""

import math

import numpy as np
from mpi4py import MPI

from ..continuation import ConstantParameter, Continuation
from ..problem import NewtonDivergence
from ..references import hertz_reference

__all__ = ["AXISYMMETRIC", "HertzRun", "dimension", "geometric_dim", "hertz_dim"]

#: the ``dim`` of a sphere modelled by its meridian section (an axisymmetric body)
AXISYMMETRIC = "axisymmetric"


def dimension(text):
    """Parse ``dim``: 2, 3 or "axisymmetric" (ValueError otherwise)."""
    text = str(text).strip()
    return AXISYMMETRIC if text == AXISYMMETRIC else int(text)


def geometric_dim(dim):
    """Dimension of the mesh: 2 for the cylinder and the meridian section, else 3."""
    return 2 if dim == AXISYMMETRIC else dim


def hertz_dim(dim):
    """Dimension of the Hertz reference: 2 (line contact, the cylinder) or 3 (a sphere)."""
    return 3 if dim == AXISYMMETRIC else dim


class HertzRun:
    """The load steps of the Hertz cases and their comparison with Hertz: run, results, plots."""

    @staticmethod
    def vtx_fields(run):
        """Fields written for ParaView: displacement (bulk) and nominal pressure (Γ_c)."""
        body, contact, _ = run
        return {"displacement": [body.u], "contact": [contact.lam_n]}

    @staticmethod
    def plot(profile, outdir):
        """Pressure profile against Hertz (``pressure.png``)."""
        from ..plots import plot_hertz_pressure

        plot_hertz_pressure(profile, outdir / "pressure.png")

    @staticmethod
    def model_fraction(dim):
        """Fraction of the full body whose force the model gives (symmetry).

        A half cylinder, a quarter sphere; the meridian section's forces are those
        of the revolved (full) sphere, its measures weighted by 2πR.
        """
        return {2: 0.5, 3: 0.25, AXISYMMETRIC: 1.0}[dim]

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, comm=MPI.COMM_WORLD):
        """Load the body to ``load`` and record contact size and peak pressure.

        The plane's position δ is driven by :meth:`Continuation.reach` so that the
        normal contact force equals each load increment.  ``comm``: the
        communicator of the mesh (e.g. COMM_SELF for a serial run inside a parallel
        test).
        """
        R, dim = v["R"], hertz_dim(v["dim"])
        body, contact, problem = run = cls.build(v, comm)
        frac = cls.model_fraction(v["dim"])
        record.data["num_dofs"] = problem.num_dofs
        a_h, p_h = hertz_reference(dim, v["E"], v["nu"], R, v["load"])
        axis = geometric_dim(v["dim"]) - 1
        control = Continuation(problem, ConstantParameter(contact.counterpart.offset, axis),
                               response=lambda: contact.force()[axis], verbose=verbose,
                               record=record.data["newton_iterations"])
        targets = [frac * v["load"] * (k + 1) / v["steps"] for k in range(v["steps"])]
        delta = a_h**2 / R if dim == 3 else 0.5 * a_h**2 / R
        try:
            for k, target in enumerate(targets):
                delta = control.reach(target, delta * (1 if k == 0 else (k + 1) / k))
                if progress is not None:
                    progress.update(1)
        except NewtonDivergence as err:
            err.problem = run  # restored to the last converged load step
            raise
        finally:
            cls._report(contact, v, record, frac, a_h, p_h)
        return run

    @staticmethod
    def _report(contact, v, record, frac, a_h, p_h):
        dim, gdim = v["dim"], geometric_dim(v["dim"])
        area, pmax = contact.measures()
        # half-width; the radius of a quarter disc's area; that of the revolved disc's
        size = {2: area, 3: math.sqrt(4 * area / math.pi),
                AXISYMMETRIC: math.sqrt(area / math.pi)}[dim]
        force = contact.force()
        key = "contact_half_width" if dim == 2 else "contact_radius"
        record.result(key, size, "mm")
        record.result(f"hertz_{key}", a_h, "mm")
        record.result("p_max", pmax, "MPa")
        record.result("hertz_p_max", p_h, "MPa")
        record.result(f"{key}_rel_error", size / a_h - 1)
        record.result("p_max_rel_error", pmax / p_h - 1)
        record.result("contact_element_size", v["E"] / contact.rho_n, "mm (h of rho_N = E/h)")
        if hertz_dim(dim) == 3:   # a sphere: the plane's travel from first contact
            delta = abs(float(contact.counterpart.offset.value[gdim - 1]))
            record.result("approach", delta, "mm")
            record.result("hertz_approach", a_h**2 / v["R"], "mm (half-space)")
        record.result("normal_load_full_body", float(force[gdim - 1] / frac),
                      "N/mm" if dim == 2 else "N")
        record.result("tangential_force_modelled_part", [float(f) for f in force[: gdim - 1]],
                      "N/mm" if dim == 2 else "N")
        # weighted L2 distance of the nodal pressures from the Hertz distribution
        d = contact.nodal_data()
        rr = d["x"][:, 0] if gdim == 2 else np.linalg.norm(d["x"][:, :2], axis=1)
        ph = p_h * np.sqrt(np.clip(1 - (rr / a_h) ** 2, 0, None))
        comm = contact.body.mesh.comm
        num = comm.allreduce(float(np.sum(d["weight"] * (d["p"] - ph) ** 2)), op=MPI.SUM)
        den = comm.allreduce(float(np.sum(d["weight"] * ph**2)), op=MPI.SUM)
        record.result("pressure_profile_rel_l2_error", math.sqrt(num / den))
        prof = contact.gather_profile()
        if comm.rank == 0:
            r = (prof["x"][:, 0] if gdim == 2
                 else np.linalg.norm(prof["x"][:, :2], axis=1))
            record.profile = {"r": r, "p": prof["p"], "a": a_h, "p0": p_h, "dim": dim}

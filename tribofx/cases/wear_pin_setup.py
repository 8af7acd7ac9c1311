"""Loading of the wear pin and the user's pin mesh (chapter §4.4).

:class:`PinSetup` is a base class of :class:`tribofx.cases.wear.WearPinCase`: the
load-up of the contact before the slow time, and a user's pin mesh
(``mesh_file``) placed on the plane with its approach.
"""

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..continuation import ConstantParameter, Continuation
from ..meshes.user import boundary_facet_size
from ..references import hertz

__all__ = ["PinSetup"]


class PinSetup:
    """Loading of the wear pin and the user's pin mesh (chapter §4.4)."""

    @staticmethod
    def _user_pin(msh, ft, names):
        """Move a user's pin so that its lowest tip point is at y = 0; (width, tip element size).

        The width is the x extent of the mesh, the element size the mean length of
        the tip facets (the augmentation ρ_N = E/h).
        """
        comm = msh.comm
        x = msh.geometry.x
        tip = np.unique(dmesh.entities_to_geometry(
            msh, 1, ft.find(names["contact"]), False).ravel())
        y0 = comm.allreduce(float(np.min(x[tip, 1], initial=np.inf)), op=MPI.MIN)
        x[:, 1] -= y0
        lo = comm.allreduce(float(np.min(x[:, 0], initial=np.inf)), op=MPI.MIN)
        hi = comm.allreduce(float(np.max(x[:, 0], initial=-np.inf)), op=MPI.MAX)
        return hi - lo, boundary_facet_size(msh, ft, names["contact"])

    @staticmethod
    def load_up(stepper, load, v, verbose=False):
        """Unworn contact under the full traction (load factor 0 → 1 by Continuation).

        Newton starts from the rigid translation δ₀ = a²/(2R) + qH/E of the pin (a
        the 2D Hertz half-width of the tip, ν = 0.3, at most W/2), so that the tip
        nodes start active; a failed solve halves the load increment.  Returns
        the Newton iterations spent.
        """
        R = v["R_tip"]
        a = min(hertz(v["q"] * v["W"], R, v["E"], 0.3, line=True).a, v["W"] / 2) if R else 0.0
        delta0 = (a * a / (2 * R) if a else 0.0) + v["q"] * v["H"] / v["E"]
        if v["mesh_file"]:   # a user's tip: its middle half starts in contact
            delta0 = PinSetup._user_approach(stepper.wear.contact, v)
        stepper.wear.body.u.x.array.reshape(-1, 2)[:, 1] = -delta0
        load.value = 0.0
        control = Continuation(stepper.problem, ConstantParameter(load), verbose=verbose)
        control.march(1.0, steps=1, predictor=False)
        return int(sum(control.record))

    @staticmethod
    def _user_approach(contact, v):
        """Return the initial approach of a user's pin: tip height at |x| = W/4 plus qH/E."""
        msh = contact.body.mesh
        comm = msh.comm
        x = msh.geometry.x
        lo, hi = (comm.allreduce(f(x[:, 0]), op=o) for f, o in
                  ((np.min, MPI.MIN), (np.max, MPI.MAX)))
        H = comm.allreduce(float(np.max(x[:, 1])), op=MPI.MAX)
        d = contact.nodal_data()
        xs = d["X"]
        quarter = 0.25 * (hi - lo)
        near = np.abs(np.abs(xs[:, 0] - 0.5 * (lo + hi)) - quarter) <= 0.25 * quarter
        rise = comm.allreduce(float(np.max(xs[near, 1], initial=0.0)), op=MPI.MAX)
        return rise + v["q"] * H / v["E"]

"""A user's die for the ironing case (``mesh_file``): read, placed and checked.

:class:`IroningUser` is a base class of :class:`tribofx.cases.ironing.IroningCase`.
"""

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..meshes.user import boundary_facet_size
from ..params import InputError

__all__ = ["IroningUser"]


class IroningUser:
    """A user's die for the ironing case (``mesh_file``): read, placed and checked."""

    @classmethod
    def _user_die(cls, msh, ft, names, v):
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

        def extent(a):
            return (comm.allreduce(float(np.min(a, initial=np.inf)), op=MPI.MIN),
                    comm.allreduce(float(np.max(a, initial=-np.inf)), op=MPI.MAX))

        (lo, hi), (ylo, yhi) = extent(x[:, 0]), extent(x[:, 1])
        b = 0.5 * (hi - lo)
        cls.check_slide(v, b)

        def nodes(name):
            return np.unique(dmesh.entities_to_geometry(msh, 1, ft.find(names[name]),
                                                        False).ravel())

        y0, tol = extent(x[nodes("arc"), 1])[0], 1e-9 * max(hi - lo, yhi - ylo)
        y_top = extent(x[nodes("top"), 1])[0]
        path = v["mesh_file"]
        if ylo < y0 - tol:
            raise InputError(f"the die in {path!r} reaches {y0 - ylo:.4g} mm below its "
                             "lowest 'arc' node: 'arc' must be its lower boundary")
        if y_top <= y0 + tol:
            raise InputError(f"the die in {path!r} has 'top' as low as its lowest 'arc' "
                             "node: 'arc' must be its lower boundary")
        xc = 0.5 * b + 1.0
        x[:, 0] += xc - 0.5 * (lo + hi)
        x[:, 1] += v["H"] - y0
        return b, boundary_facet_size(msh, ft, names["arc"], near=((xc, v["H"]), b))

"""A user's pin mesh for the pin wear cases (``wear-pin``, ``wear-reciprocating``).

:func:`place_user_pin` moves the pin so that its lowest tip point is at y = 0 and
returns its width and tip element size; :func:`user_pin_approach` is the initial
approach of its tip (the rise of the tip at |x| = W/4 plus the compression qH/E),
so that the middle half of the tip starts in contact.  Units: mm, MPa.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..meshes.user import boundary_facet_size

if TYPE_CHECKING:
    from collections.abc import Mapping

    from ..interfaces import Contact
    from ..interfaces.two_body_wear import WearSurface

__all__ = ["place_user_pin", "user_pin_approach"]


def place_user_pin(msh: dmesh.Mesh, ft: dmesh.MeshTags,
                   names: Mapping[str, int]) -> tuple[float, float]:
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


def user_pin_approach(contact: Contact | WearSurface, q: float, E: float) -> float:
    """Return the initial approach of a user's pin: tip height at |x| = W/4 plus qH/E.

    ``q``: the traction on the pin's top (MPa), ``E``: its Young's modulus (MPa).
    """
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
    return rise + q * H / E

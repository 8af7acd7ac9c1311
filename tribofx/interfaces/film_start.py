"""Starting states of a soft-EHL film: the countersurface placed at a film, a dry start.

:class:`FilmStart` is a base class of :class:`tribofx.interfaces.Film` (its
methods use the film's fields, ``refresh()`` and ``_film_thickness()``).
"""

import numpy as np
import ufl
from dolfinx import fem

from .prescribed_pressure import PrescribedPressure

__all__ = ["FilmStart"]


class FilmStart:
    """Starting states of a :class:`tribofx.interfaces.Film`."""

    def place_countersurface(self, h0, at):
        """Translate a rigid countersurface along its normal so that h = ``h0`` (mm) at ``at``.

        ``at`` is a reference point; the node of Γ_l nearest to it is used.  The
        counterpart must have a rigid translation ``offset`` (mm).
        """
        if not hasattr(self.counterpart, "offset"):
            raise ValueError("place_countersurface needs a rigid countersurface (offset)")
        self.refresh()
        gdim = self.body.gdim
        n = self.Q.dofmap.index_map.size_local
        h = self._film_thickness()
        nu = fem.Function(self.V1)
        # × N·N (= 1): an Expression needs a coefficient of the submesh (ν of a plane is constant)
        nu.interpolate(fem.Expression(self.kin.nu * ufl.dot(self.N, self.N),
                                      self.V1.element.interpolation_points))
        d2 = np.sum((self._X1[:n] - np.asarray(at, float)[:gdim]) ** 2, axis=1)
        i = int(np.argmin(d2)) if n else 0
        loc = (float(d2[i]) if n else np.inf,
               (float(h[i]), nu.x.array.reshape(-1, gdim)[i].copy()) if n else None)
        _, (h_c, nu_c) = min(self.body.mesh.comm.allgather(loc), key=lambda t: t[0])
        self.counterpart.offset.value[:] += (h_c - h0) * nu_c
        self.refresh()

    def start_from_pressure(self, pressure, h0, at, verbose=False):
        """Set an initial state: the body under a prescribed film pressure, film ``h0`` at ``at``.

        ``pressure`` is a callable of the reference coordinates (3, n) → p (MPa),
        e.g. the Hertz pressure; the body is solved under it as a follower load
        (:class:`PrescribedPressure`, no shear), p is set to it (g to 0) as the
        first pressure iterate and a rigid countersurface is placed so that the
        film is ``h0`` (mm) at the node nearest to ``at``.  Returns the Newton report.
        """
        from ..problem import Problem

        if self._dry is None:
            dry = PrescribedPressure(self)
            self._dry = (dry, Problem([self.body, dry], name=f"{self.name}_dry"))
        dry, problem = self._dry
        dry.p.interpolate(pressure)
        report = problem.solve(verbose=verbose)
        self.p.x.array[:] = dry.p.x.array
        if self.g is not None:
            self.g.x.array[:] = 0.0
        self.place_countersurface(h0, at)
        return report

"""Outputs of a soft-EHL film: its forces on both walls, its thinnest point, its profile.

:class:`FilmOutputs` is the part of :class:`tribofx.interfaces.Film` that reads
a solved film: the force on the body (the traction (46) of its virtual work),
on the countersurface and its Couette part, the minimum film, the line-search
admissibility test and the nodal profile of Γ_l.
"""

import numpy as np
from dolfinx import fem
from mpi4py import MPI

from ..forms import film_traction as ft

__all__ = ["FilmOutputs"]


class FilmOutputs:
    """Post-processing of :class:`tribofx.interfaces.Film` (its base; reads its fields)."""

    def _forms(self):
        if self._post is None:
            em = [self.emap]
            gdim = self.body.gdim
            counter = ft.countersurface_traction(
                self.p, self.grad_gamma(self.p), self.kin, self.mu_p,
                factors=self.shear_factors(self.kin.h))
            self._post = {
                "force": [fem.form(self.traction[i] * self.w_solid * self.ds, entity_maps=em)
                          for i in range(gdim)],
                "couette": [fem.form(self._couette[i] * self.w_solid * self.ds, entity_maps=em)
                            for i in range(gdim)],
                "counter": [fem.form(counter[i] * self.kin.stretch * self.w_film * self.dx)
                            for i in range(gdim)],
                "asperity": None if self.asperity is None else [
                    fem.form(self.asperity[i] * self.w_solid * self.ds, entity_maps=em)
                    for i in range(gdim)],
                "y": fem.Expression(self.kin.y, self.V1.element.interpolation_points),
            }
        return self._post

    def _nodal(self, key):
        f = fem.Function(self.V1)
        f.interpolate(self._forms()[key])
        return f.x.array

    def _vector_integral(self, key):
        """Refresh the kernel data; the components of the post-processing form ``key``."""
        self.refresh()
        return np.array([self._sum(f) for f in self._forms()[key]])

    def force(self):
        """Force of the film on the modelled part of the body.

        N/mm per unit thickness in plane strain; N in 3D (a quarter model: a
        quarter of the full body's); axisymmetric: the revolved body's, N (2πR-weighted).
        """
        return self._vector_integral("force")

    def counter_force(self):
        """Force of the film on the countersurface (units and parts as :meth:`force`).

        ∫_S [−p ν + (μ/h) v_rel − (h/2) grad_S p] ds_S over the modelled part
        (:func:`forms.film_traction.countersurface_traction`): what a friction rig measures
        on the rigid counterpart.  The film's momentum balance makes this
        −:meth:`force` up to the shear where the layer's area differs from S's,
        ∫ shear (j − ds_S/dS) dS (steep flanks of a thick film); the
        geometrically linear model's traction −pN also leaves out the pressure on
        the displacement's slope, ∫ p grad_S(ν·u) ds_S (tests/test_ehl_ball.py).
        """
        return self._vector_integral("counter")

    def asperity_force(self):
        """Force of the asperity contact on the body (N; N/mm): pressure and boundary friction."""
        if self.asperity is None:
            return np.zeros(self.body.gdim)
        return self._vector_integral("asperity")

    def couette_force(self):
        """Couette drag alone (N; N/mm): ∫ −j(μ/h)(v_layer − v_counter) dS (any ``shear``)."""
        return self._vector_integral("couette")

    def min_film(self):
        """Smallest nodal film thickness on Γ_l (mm, all ranks)."""
        self.refresh()
        n = self.Q.dofmap.index_map.size_local
        return self.sub.comm.allreduce(float(self._film_thickness()[:n].min(initial=np.inf)),
                                       op=MPI.MIN)

    def admissible(self):
        """Line-search test: True, or with ``require_open`` an open film and fluid at every node.

        Open: h > 0, or on rough surfaces h > −4σ (the nominal surfaces may
        overlap where the asperities carry; the Greenwood–Tripp fit ends at 4σ).
        """
        rough = getattr(self, "roughness", None)
        floor = 0.0 if rough is None else -4 * rough.sigma
        return not self.require_open or (self.has_fluid() and self.min_film() > floor)

    def profile(self, everywhere=False):
        """Nodal X, x (current), y (projection), h, p (λ, p_a) of Γ_l, sorted by X₀.

        On rank 0 (None elsewhere), or on every rank (``everywhere``).  x and y
        are P1 nodal values (the trace interpolated at the vertices).
        """
        self.refresh()
        gdim = self.body.gdim
        n = self.Q.dofmap.index_map.size_local
        # Q, V1 (and Ql) share the P1 layout of the same submesh
        self._u1.interpolate(self.u_s)
        x = self._X1 + self._u1.x.array.reshape(-1, gdim)
        d = {"X": self._X1[:n], "x": x[:n], "y": self._nodal("y").reshape(-1, gdim)[:n],
             "h": self._film_thickness()[:n].copy(), "p": self.p.x.array[:n].copy()}
        if self.lam is not None:
            d["lam"] = self.lam.x.array[:n].copy()
        if self.asperity is not None:
            d["p_a"] = self._asperity_pressure(d["h"], n)
        return self._gather(d, "X", everywhere)

    def _asperity_pressure(self, h, n):
        """Nodal asperity pressure p_a(h) (MPa) of the roughness's law at the nodal gaps."""
        if getattr(self, "_pa_nodal", None) is None:
            hf, out = fem.Function(self.Q), fem.Function(self.Q)
            expr = fem.Expression(self._rough[2](hf), self.Q.element.interpolation_points)
            self._pa_nodal = (hf, out, expr)
        hf, out, expr = self._pa_nodal
        hf.x.array[:n] = h
        out.interpolate(expr)
        return out.x.array[:n].copy()

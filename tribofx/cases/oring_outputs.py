"""Measures of the O-ring seal (chapter §8.1): forces, film profile, sealed arc, results.

:class:`SealOutputs` is a base class of :class:`tribofx.cases.oring_seal.ORingSeal`.
"""

import math

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..forms import ehl_axisym as ax
from ..positions import oscillation_indicator, parabolic_vertex

__all__ = ["SealOutputs"]


class SealOutputs:
    """Measures of the O-ring seal (chapter §8.1): forces, film profile, sealed arc, results."""

    # -- results -----------------------------------------------------------------------
    def _forms(self):
        if self._post is None:
            body, film = self.body, self.film
            t = ax.follower_pressure_traction(self.p_s, body.u, ufl.FacetNormal(body.mesh))
            ds = body.ds(body.tag("sealed"))
            Qc = fem.functionspace(film.sub, ("DG", 0))
            xs = ufl.SpatialCoordinate(film.sub) + film.u_s
            pts = Qc.element.interpolation_points
            self._post = {
                "sealed": [fem.form(t[i] * body.weight * ds) for i in range(2)],
                "Qc": Qc,
                "q": fem.Expression(ax.film_flux(film.kin, film.p, film.mu_p, film.grad_gamma,
                                                  film.lam),
                                    pts),
                "z": fem.Expression(xs[1], pts)}
        return self._post

    def forces(self):
        """Return the r, z forces (N, whole circumference) on the ring: film, p_s, bottom, wall."""
        comm = self.body.mesh.comm
        sealed = np.array([comm.allreduce(fem.assemble_scalar(f), op=MPI.SUM)
                           for f in self._forms()["sealed"]])
        return {"film": self.film.force(), "sealed": sealed, "bottom": self.bottom.force(),
                "wall": self.wall.force()}

    def profile(self):
        """Film data on rank 0 (None elsewhere), sorted by the current axial position.

        Nodal: z (current axial position = position on the rod, mm), h (mm), p (MPa)
        and, with JFO cavitation, the void fraction lam (-); cellwise: z_cell, q
        (flux per unit circumference, mm²/s).
        """
        pr = self.film.profile()
        post = self._forms()
        q, zc = fem.Function(post["Qc"]), fem.Function(post["Qc"])
        q.interpolate(post["q"])
        zc.interpolate(post["z"])
        nc = post["Qc"].dofmap.index_map.size_local
        cells = self.body.mesh.comm.gather((zc.x.array[:nc].copy(), q.x.array[:nc].copy()),
                                           root=0)
        if pr is None:
            return None
        z = pr["x"][:, 1]
        o, zcell = np.argsort(z, kind="stable"), np.concatenate([c[0] for c in cells])
        oc = np.argsort(zcell, kind="stable")
        out = {"z": z[o], "h": pr["h"][o], "p": pr["p"][o], "z_cell": zcell[oc],
               "q": np.concatenate([c[1] for c in cells])[oc]}
        if "lam" in pr:
            out["lam"] = pr["lam"][o]
        return out

    def sealed_arc_radii(self):
        """Return the current radii r (mm) of the end points φ = −135°, −45° of the sealed arc.

        The built section only (a user's section need not have nodes there).
        """
        if self.user:
            raise ValueError("sealed_arc_radii needs the built section (no mesh_file)")
        V, u = self.body.V, self.body.u
        n = V.dofmap.index_map.size_local
        X = V.tabulate_dof_coordinates()
        out = []
        for t in (math.radians(-135), math.radians(-45)):
            pt = np.array(self.center) + self.a * np.array([math.cos(t), math.sin(t)])
            k = np.nonzero(np.linalg.norm(X[:n, :2] - pt, axis=1) < 1e-6 * self.a)[0]
            val = float(X[k[0], 0] + u.x.array[2 * k[0]]) if len(k) else None
            out.append(next(r for r in self.body.mesh.comm.allgather(val) if r is not None))
        return out

    def measures(self):
        """Film measures on all ranks (see ``EHLORingCase.UNITS``)."""
        prof = self.profile()
        res = None
        if self.body.mesh.comm.rank == 0:
            z, h, p = prof["z"], prof["h"], prof["p"]
            k, i = int(np.argmax(p)), int(np.argmin(h))
            ps = float(self.p_s.value)
            thr = ps + 0.5 * (p[k] - ps)      # loaded zone: half the rise above p_s
            hot = z[p > thr]
            qz = prof["q"][(prof["z_cell"] > hot.min()) & (prof["z_cell"] < hot.max())]
            if not qz.size:    # a loaded zone of one node (near a reversal): no cell inside
                qz = np.array([np.nan])
            res = {"p_max": float(p[k]), "z_p_max": parabolic_vertex(z, p),
                   "h_at_p_max": float(h[k]),
                   "h_min": float(h[i]), "z_h_min": parabolic_vertex(z, h, "min"),
                   "h_mean": float(np.mean(h[p > thr])), "flux": float(np.median(qz)),
                   "flux_spread": float((qz.max() - qz.min()) / abs(np.median(qz))),
                   "oscillation": oscillation_indicator(h, p, thr)}
        res = self.body.mesh.comm.bcast(res, root=0)
        f = self.film.force()
        circ = 2 * math.pi * self.r_rod
        res["load_per_circumference"] = float(f[0]) / circ
        res["friction_force_per_circumference"] = float(f[1]) / circ
        res["leakage"] = circ * res["flux"]
        return res

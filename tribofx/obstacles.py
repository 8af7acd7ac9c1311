"""Rigid countersurfaces for contact: analytic (plane, cylinder, sphere) or meshed.

An obstacle turns a UFL position x into a :class:`tribofx.forms.contact.ContactGeometry`
through the functions of ``forms/contact``.  Its rigid translation ``offset`` (mm)
is a ``dolfinx.fem.Constant`` that drivers move to load the body.

A :class:`MeshedObstacle` carries the closest-point data of the C++ kernels
(projection, normal, their first derivatives and ∂²x̄/∂x², from
:func:`tribofx.lubrication_projection.lubrication_projection`) as nodal (P1)
fields on the contact submesh; :meth:`MeshedObstacle.update` refreshes
them at the current slave node positions and is called before every residual
assembly, so that the Newton tangent stays consistent.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import ufl
from dolfinx import fem

from .forms import contact as cf

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable

    import numpy.typing as npt
    import ufl.core.expr
    from dolfinx import mesh as dmesh

    from .forms.contact import ContactGeometry
    from .protocols import Counterpart

__all__ = [
    "AnalyticObstacle",
    "MeshedObstacle",
    "rigid_cylinder",
    "rigid_plane",
    "rigid_sphere",
    "rigid_surface_mesh",
]


class _RigidMotion:
    """Rigid translation ``offset`` (mm) of a countersurface and its value at the last commit.

    The contact interface asks a counterpart for ``motion_since_commit()`` (the
    displacement of the master's material points since the last converged step,
    which carries the projection point of the Lagrangian slip), ``commit()`` and
    ``state_fields()``; a deformable master body answers the same questions.
    """

    def _init_motion(self, mesh: dmesh.Mesh, gdim: int) -> None:
        self.offset = fem.Constant(mesh, np.zeros(gdim))
        self.offset_n = fem.Constant(mesh, np.zeros(gdim))

    def motion_since_commit(self) -> ufl.core.expr.Expr:
        """UFL displacement of the master's material points since the last commit."""
        return self.offset - self.offset_n

    def commit(self) -> None:
        """Make the current position the reference of the next step's slip."""
        self.offset_n.value[:] = self.offset.value

    def state_fields(self) -> list[fem.Constant]:
        """Return the position constants."""
        return [self.offset, self.offset_n]

    def unknowns(self) -> list[fem.Function]:
        """Return no unknowns: a rigid countersurface has none."""
        return []


class AnalyticObstacle(_RigidMotion):
    """Plane, cylinder or sphere given in closed form.

    Args:
        mesh: mesh the constants live on (the contact submesh).
        shape: "plane", "cylinder" or "sphere".
        point: a point of the plane, or the centre of cylinder/sphere (mm).
        normal: unit outer normal of the plane (towards the body).
        radius: cylinder/sphere radius (mm).
        axis: unit axis of a 3D cylinder.
    """

    def __init__(self, mesh: dmesh.Mesh, shape: str, point: npt.ArrayLike,
                 normal: Iterable[float] | None = None, radius: float | None = None,
                 axis: Iterable[float] | None = None) -> None:
        if shape not in ("plane", "cylinder", "sphere"):
            raise ValueError(f"unknown obstacle shape {shape!r}")
        gdim = mesh.geometry.dim
        self.shape = shape
        self.point = np.asarray(point, dtype=float)
        self._init_motion(mesh, gdim)
        self._normal = None if normal is None else ufl.as_vector(list(map(float, normal)))
        # point and radius as Constants: another size or position reuses the compiled
        # kernels of every form and expression that sees the obstacle
        self._point = fem.Constant(mesh, self.point)
        self._radius = None if radius is None else fem.Constant(mesh, float(radius))
        self._axis = None if axis is None else ufl.as_vector(list(map(float, axis)))

    def geometry(self, x: ufl.core.expr.Expr) -> ContactGeometry:
        """Closest-point geometry of the (translated) obstacle at the UFL position ``x``."""
        c = self._point + self.offset
        if self.shape == "plane":
            return cf.plane_countersurface(x, c, self._normal)
        if self.shape == "cylinder":
            return cf.cylinder_countersurface(x, c, self._radius, self._axis)
        return cf.sphere_countersurface(x, c, self._radius)

    def update(self, x_nodes: npt.NDArray[np.float64]) -> None:
        """Nothing to refresh for a closed-form obstacle."""


class MeshedObstacle(_RigidMotion):
    """Rigid countersurface given as a surface mesh, projected by the C++ kernel.

    Its data are exact at the nodes it is updated at: a form evaluated elsewhere
    sees their P1 interpolation (see ``Film(quadrature=...)``).

    Args:
        mesh: mesh the offset constant lives on (the contact submesh).
        V_sub: vector P1 space on the contact submesh (holds the nodal data).
        nodes, facets, cell_type: surface mesh in the packing of
            :func:`tribofx.projection.closest_point_projection`.
    """

    def __init__(self, mesh: dmesh.Mesh, V_sub: fem.FunctionSpace, nodes: npt.ArrayLike,
                 facets: npt.ArrayLike, cell_type: str) -> None:
        from .lubrication_projection import lubrication_projection

        self._project = lubrication_projection
        gdim = mesh.geometry.dim
        self.nodes = np.asarray(nodes, dtype=float)
        self.facets = np.asarray(facets, dtype=np.int32)
        self.cell_type = cell_type
        self._init_motion(mesh, gdim)
        sub = V_sub.mesh
        T = fem.functionspace(sub, ("Lagrange", 1, (gdim, gdim)))
        T3 = fem.functionspace(sub, ("Lagrange", 1, (gdim, gdim, gdim)))
        S = fem.functionspace(sub, ("Lagrange", 1))
        self.x0 = fem.Function(V_sub, name="x0")
        self.gap0 = fem.Function(S, name="gap0")
        self.normal0 = fem.Function(V_sub, name="normal0")
        self.xbar0 = fem.Function(V_sub, name="xbar0")
        self.dnormal = fem.Function(T, name="dnormal_dx")
        self.dxbar = fem.Function(T, name="dxbar_dx")
        self.d2xbar = fem.Function(T3, name="d2xbar_dx2")

    def geometry(self, x: ufl.core.expr.Expr) -> ContactGeometry:
        """Second-order expansion of the kernel data about the last update point."""
        return cf.meshed_countersurface(
            x, self.x0, self.gap0, self.normal0, self.dnormal, self.xbar0, self.dxbar,
            self.d2xbar,
        )

    def update(self, x_nodes: npt.NDArray[np.float64]) -> None:
        """Project the slave nodes ``x_nodes`` (n, gdim) — ordered as the P1 dofs — and store."""
        off = self.offset.value
        res = self._project(x_nodes - off, self.nodes, self.facets, self.cell_type)
        self.x0.x.array[:] = x_nodes.ravel()
        self.gap0.x.array[:] = res.h
        self.normal0.x.array[:] = res.nu.ravel()
        self.xbar0.x.array[:] = (res.y + off).ravel()
        self.dnormal.x.array[:] = res.dnu_dx.ravel()
        self.dxbar.x.array[:] = res.dy_dx.ravel()
        self.d2xbar.x.array[:] = res.d2y_dx2.ravel()


def rigid_plane(point: npt.ArrayLike,
                normal: Iterable[float]) -> Callable[[fem.FunctionSpace], Counterpart]:
    """Counterpart factory: the rigid plane through ``point`` with unit normal ``normal``."""
    return lambda Vs: AnalyticObstacle(Vs.mesh, "plane", point, normal=normal)


def rigid_cylinder(center: npt.ArrayLike, radius: float, axis: Iterable[float] | None = None
                   ) -> Callable[[fem.FunctionSpace], Counterpart]:
    """Counterpart factory: a rigid cylinder (disc in 2D) of ``radius`` about ``center``."""
    return lambda Vs: AnalyticObstacle(Vs.mesh, "cylinder", center, radius=radius, axis=axis)


def rigid_sphere(center: npt.ArrayLike,
                 radius: float) -> Callable[[fem.FunctionSpace], Counterpart]:
    """Counterpart factory: a rigid sphere of ``radius`` about ``center``."""
    return lambda Vs: AnalyticObstacle(Vs.mesh, "sphere", center, radius=radius)


def rigid_surface_mesh(nodes: npt.ArrayLike, facets: npt.ArrayLike,
                       cell_type: str) -> Callable[[fem.FunctionSpace], Counterpart]:
    """Counterpart factory: a rigid surface mesh projected by the C++ kernel.

    ``nodes`` (n, gdim) float, ``facets`` (m, k) int32, ``cell_type`` as for
    :func:`tribofx.projection.closest_point_projection`.
    """
    return lambda Vs: MeshedObstacle(Vs.mesh, Vs, nodes, facets, cell_type)

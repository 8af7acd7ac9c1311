"""gmsh mesh-size field shared by the mesh builders: refinement around one point."""

from __future__ import annotations

import gmsh

__all__ = ["point_refinement"]


def point_refinement(
    h_fine: float, h_coarse: float, r_fine: float, R: float, point_tag: int
) -> None:
    """Size h_fine within r_fine of gmsh point ``point_tag``, growing to h_coarse over 0.6 R.

    Also sets the meshing options (frontal-Delaunay surfaces, smoothed and
    optimised tetrahedra) of the current gmsh model.
    """
    f = gmsh.model.mesh.field
    d = f.add("Distance")
    f.setNumbers(d, "PointsList", [point_tag])
    t = f.add("Threshold")
    f.setNumber(t, "InField", d)
    f.setNumber(t, "SizeMin", h_fine)
    f.setNumber(t, "SizeMax", h_coarse)
    f.setNumber(t, "DistMin", r_fine)
    f.setNumber(t, "DistMax", r_fine + 0.6 * R)
    f.setAsBackgroundMesh(t)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    # regular surface triangles (frontal-Delaunay) and optimised tetrahedra keep
    # the nodal contact pressures of linear elements smooth
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.Smoothing", 5)
    gmsh.option.setNumber("Mesh.Optimize", 1)
    gmsh.option.setNumber("Mesh.OptimizeNetgen", 1)

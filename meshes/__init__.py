"""gmsh model builders returning DOLFINx meshes and tags."""

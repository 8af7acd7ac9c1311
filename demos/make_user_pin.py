# # Your own geometry: a pin with a flat-shouldered tip for ``wear-pin``
#
# ``tribofx run wear-pin --set mesh_file=PATH`` replaces the case's pin (a
# rectangle with a circular-arc tip, structured mesh) by any 2D gmsh mesh whose
# physical groups carry the case's boundary names (``tribofx list`` shows them):
#
# * ``contact``: the tip, the potential contact surface (its lowest point is
#   moved to y = 0, the rigid flat);
# * ``top``: the loaded face (uniform traction q);
# * ``sides``: the lateral faces (x fixed, and the shape change's x component).
#
# This script writes such a pin: a flat middle half and parabolic shoulders
# y = c (|x| − W/4)², a B-spline through 13 points, unstructured triangles:
#
#     .venv/bin/python demos/make_user_pin.py user_pin.msh
#     .venv/bin/tribofx run wear-pin --set mesh_file=user_pin.msh --out results/user_pin
#
# A mesh without a group, of the wrong dimension, or with an inverted cell stops
# with a one-line error (exit status 2).  Change ``W, H, c, h`` below, or draw
# your pin in the gmsh GUI and name the groups there.

import sys

import gmsh

W, H = 2.0, 2.0     # width and height of the pin (mm)
c = 0.4             # shoulder curvature (1/mm)
h = W / 16          # element size (mm)


def main(path):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("user_pin")
    occ = gmsh.model.occ
    xs = [-W / 2 + W * i / 12 for i in range(13)]
    tip = [occ.addPoint(x, c * max(abs(x) - W / 4, 0.0) ** 2, 0) for x in xs]
    top_right, top_left = occ.addPoint(W / 2, H, 0), occ.addPoint(-W / 2, H, 0)
    curves = [occ.addBSpline(tip), occ.addLine(tip[-1], top_right),
              occ.addLine(top_right, top_left), occ.addLine(top_left, tip[0])]
    surface = occ.addPlaneSurface([occ.addCurveLoop(curves)])
    occ.synchronize()
    gmsh.model.addPhysicalGroup(2, [surface], 1, "body")
    gmsh.model.addPhysicalGroup(1, [curves[0]], 1, "contact")
    gmsh.model.addPhysicalGroup(1, [curves[2]], 2, "top")
    gmsh.model.addPhysicalGroup(1, [curves[1], curves[3]], 3, "sides")
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.model.mesh.generate(2)
    gmsh.write(path)
    gmsh.finalize()
    print(f"wrote {path}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "user_pin.msh")

"""A user's own gmsh mesh (``mesh_file=PATH``): a pin of another tip shape, and bad meshes.

The pin here is built in the test by gmsh with a geometry the case cannot make
(a flat middle half, parabolic shoulders, a B-spline tip and an unstructured
mesh), so the run exercises the reader, the group names and the geometry
taken from the mesh.  Reference: Archard's global balance of steady sliding,
worn area = k q W V T (every load passes through the contact, the sliding speed
is V everywhere), with W the width read from the mesh; it holds to the wear
rows' tolerance, independent of the tip shape.
"""

import json
import os
import subprocess
import sys

import gmsh
import pytest

ENV = dict(os.environ, UCX_TLS="self,sm,tcp")
CLI = [sys.executable, "-m", "tribofx.cli"]
W, H = 2.0, 2.0


def _pin(path, n=16, groups=("contact", "top", "sides"), dim=2, flip=False, body=True):
    """Write a pin mesh: flat middle half, shoulders y = 0.4 (|x| − W/4)², sides, top."""
    gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
    gmsh.model.add("user_pin")
    occ = gmsh.model.occ
    xs = [-W / 2 + W * i / 12 for i in range(13)]
    tip = [occ.addPoint(x, 0.4 * max(abs(x) - W / 4, 0.0) ** 2, 0) for x in xs]
    tr, tl = occ.addPoint(W / 2, H, 0), occ.addPoint(-W / 2, H, 0)
    curves = [occ.addBSpline(tip), occ.addLine(tip[-1], tr), occ.addLine(tr, tl),
              occ.addLine(tl, tip[0])]
    surf = occ.addPlaneSurface([occ.addCurveLoop(curves)])
    if dim == 3:
        occ.extrude([(2, surf)], 0, 0, 1.0)
    occ.synchronize()
    if dim == 3:
        gmsh.model.addPhysicalGroup(3, [1], 1, "body")
    elif body:
        gmsh.model.addPhysicalGroup(2, [surf], 1, "body")
    named = {"contact": [curves[0]], "top": [curves[2]], "sides": [curves[1], curves[3]]}
    for tag, name in enumerate(groups, start=1):
        gmsh.model.addPhysicalGroup(1, named.get(name, [curves[2]]), tag, name)
    gmsh.option.setNumber("Mesh.MeshSizeMax", W / n)
    gmsh.model.mesh.generate(dim)
    gmsh.write(str(path))
    gmsh.finalize()
    if flip:   # swap two nodes of the first triangle: one inverted cell
        lines = path.read_text().splitlines()
        i = lines.index("$Elements") + 2
        while lines[i].split()[1] != "2":
            i += 1
        f = lines[i].split()
        f[-1], f[-2] = f[-2], f[-1]
        lines[i] = " ".join(f)
        path.write_text("\n".join(lines) + "\n")
    return path


def _run(*args):
    return subprocess.run(CLI + list(args), capture_output=True, text=True, env=ENV,
                          timeout=900)


def test_user_pin_wears_by_archard(tmp_path):
    mesh = _pin(tmp_path / "pin.msh")
    out = tmp_path / "run"
    p = _run("run", "wear-pin", "--set", f"mesh_file={mesh}", "--set", "T=400",
             "--set", "dt=200", "--out", str(out), "--quiet")
    assert p.returncode == 0, p.stderr
    s = json.loads((out / "summary.json").read_text())
    par = {k: v["value"] for k, v in s["parameters"].items()}
    area = s["results"]["wear_volume"]["value"][-1]
    ref = par["k"] * par["q"] * W * par["V"] * par["T"]
    # tolerance: the wear rows' relative tolerance 1e-7 of each step, two steps
    print(f"worn area {area!r} against k q W V T = {ref!r}")
    assert abs(area / ref - 1) < 1e-6
    assert s["parameters"]["mesh_file"]["value"] == str(mesh)


@pytest.mark.parametrize("make,fragment", [
    (lambda d: d / "missing.msh", "does not exist"),
    (lambda d: (d / "junk.msh").write_text("this is not a mesh\n") and d / "junk.msh",
     "cannot read mesh file"),
    (lambda d: _pin(d / "three.msh", dim=3, n=4), "is 3D, the case needs a 2D mesh"),
    (lambda d: _pin(d / "nosides.msh", groups=("contact", "top")),
     "no physical group 'sides'"),
    (lambda d: _pin(d / "flip.msh", flip=True), "inverted or degenerate cell"),
    # gmsh saves only the elements of physical groups: without a surface group the
    # file holds the boundary curves alone
    (lambda d: _pin(d / "nobody.msh", body=False), "the case needs a 2D mesh"),
])
def test_bad_user_mesh(tmp_path, make, fragment):
    mesh = make(tmp_path)
    out = tmp_path / "out"
    p = _run("run", "wear-pin", "--set", f"mesh_file={mesh}", "--out", str(out), "--quiet")
    assert p.returncode == 2, p.stderr
    lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, p.stderr
    assert fragment in lines[0] and "Traceback" not in p.stderr
    assert not out.exists()   # nothing written


def test_documented_example_mesh_is_accepted(tmp_path):
    """demos/make_user_pin.py (the README's example) writes a mesh the reader accepts."""
    from pathlib import Path

    from mpi4py import MPI
    from tribofx.meshes.pin import NAMES
    from tribofx.meshes.user import read_user_mesh

    script = Path(__file__).parents[1] / "demos" / "make_user_pin.py"
    path = tmp_path / "user_pin.msh"
    p = subprocess.run([sys.executable, str(script), str(path)], capture_output=True,
                       text=True, env=ENV, timeout=300)
    assert p.returncode == 0, p.stderr
    msh, ft, names = read_user_mesh(path, MPI.COMM_SELF, 2, tuple(NAMES))
    assert set(names) == set(NAMES)
    assert msh.topology.index_map(2).size_global > 100


def _half_ellipsoid(path, R=5.0, stretch=1.4, h_fine=0.1, h_coarse=1.5, r_fine=0.0,
                    groups=("contact", "loaded", "symmetry_y"), shift_y=0.0):
    """Write a half ball y ≥ 0 stretched along x (radii stretch R, R, R), centre (0, 0, R).

    The case's own ball is a sphere with a point-refined gmsh mesh; this one has
    other curvatures (an elliptic contact) and a size field by distance from the
    lowest point.  ``shift_y`` moves the body off the symmetry plane (a bad mesh).
    """
    gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("user_ball")
    occ = gmsh.model.occ
    ball = occ.addSphere(0, 0, R, R)
    occ.dilate([(3, ball)], 0, 0, R, stretch, 1.0, 1.0)
    box = occ.addBox(-stretch * R, 0, 0, 2 * stretch * R, R, R)
    occ.intersect([(3, ball)], [(3, box)])
    if shift_y:
        occ.translate(occ.getEntities(3), 0, shift_y, 0)
    occ.synchronize()
    named = {"contact": [], "loaded": [], "symmetry_y": []}
    for d, tag in gmsh.model.getEntities(2):
        _, y, z = occ.getCenterOfMass(d, tag)
        key = "symmetry_y" if abs(y - shift_y) < 1e-8 else "loaded" if abs(z - R) < 1e-8 \
            else "contact"
        named[key].append(tag)
    gmsh.model.addPhysicalGroup(3, [t for _, t in gmsh.model.getEntities(3)], 1, "body")
    for tag, name in enumerate(groups, start=1):
        gmsh.model.addPhysicalGroup(2, named[name], tag, name)

    def size(dim, tag, x, y, z, lc):
        r = (x * x + (y - shift_y) ** 2 + z * z) ** 0.5
        return h_fine + (h_coarse - h_fine) * min(1.0, max(r - r_fine, 0.0) / R)

    gmsh.model.mesh.setSizeCallback(size)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.model.mesh.generate(3)
    gmsh.write(str(path))
    gmsh.finalize()
    return path


def test_user_ball_wears_by_archard(tmp_path):
    """wear-ball-flat on an elliptic half ball: worn volume = k F V t (Archard, global).

    The flat is positioned every step so that the contact force is F to 1e-8
    relative (the force control), and the worn volume is the integrated rate to
    the Newton tolerance, so the volume is k F V t to ~1e-7 whatever the shape.
    """
    mesh = _half_ellipsoid(tmp_path / "ball.msh")
    out = tmp_path / "run"
    p = _run("run", "wear-ball-flat", "--set", f"mesh_file={mesh}", "--set", "T=200",
             "--set", "dt=100", "--out", str(out), "--quiet")
    assert p.returncode == 0, p.stderr
    s = json.loads((out / "summary.json").read_text())
    par = {k: v["value"] for k, v in s["parameters"].items()}
    r = {k: v["value"] for k, v in s["results"].items()}
    ref = par["k"] * par["F"] * par["V"] * par["T"]
    print(f"worn volume {r['wear_volume'][-1]!r} against k F V T = {ref!r}; "
          f"h at first contact {r['h_contact_zone']!r} mm")
    assert abs(r["wear_volume"][-1] / ref - 1) < 1e-6
    # the size the case takes from the mesh (the mean longest edge of the contact
    # facets within a_H = 0.15 mm of the lowest point) is the size field there,
    # 0.1 mm, at most 0.1 + (1.5 − 0.1) 0.15/5 = 0.142 mm, up to gmsh's edge-length
    # adaptation (edges between 1/√2 and √2 of the field)
    assert 0.1 / 2**0.5 <= r["h_contact_zone"] <= 0.142 * 2**0.5


@pytest.mark.parametrize("kw,fragment", [
    ({"groups": ("contact", "loaded")}, "no physical group 'symmetry_y'"),
    ({"shift_y": 0.5}, "is not on the plane y = 0"),
])
def test_bad_user_ball(tmp_path, kw, fragment):
    mesh = _half_ellipsoid(tmp_path / "bad.msh", h_fine=0.6, h_coarse=2.0, **kw)
    out = tmp_path / "out"
    p = _run("run", "wear-ball-flat", "--set", f"mesh_file={mesh}", "--out", str(out),
             "--quiet")
    assert p.returncode == 2, p.stderr
    lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and fragment in lines[0], p.stderr
    assert not out.exists()


@pytest.mark.mpi
def test_facet_size_with_the_boundary_on_one_rank():
    """boundary_facet_size when a rank owns none of the tagged facets (2 ranks: one does).

    Reference: one boundary facet of a uniform 8 × 8 square, of length 1/8 exactly
    (2D: the mean longest edge is that length); the same value on every rank.
    """
    import numpy as np
    from dolfinx import mesh as dmesh
    from mpi4py import MPI
    from tribofx.meshes.user import boundary_facet_size

    comm = MPI.COMM_WORLD
    msh = dmesh.create_unit_square(comm, 8, 8)
    facets = dmesh.locate_entities_boundary(
        msh, 1, lambda x: np.isclose(x[0], 0.0) & (x[1] < 0.125 + 1e-12))
    ft = dmesh.meshtags(msh, 1, facets, np.full(len(facets), 7, dtype=np.int32))
    owned = facets < msh.topology.index_map(1).size_local
    assert comm.allreduce(int(owned.sum()), op=MPI.SUM) == 1
    h = boundary_facet_size(msh, ft, 7)
    h_near = boundary_facet_size(msh, ft, 7, near=((0.0, 0.0), 0.01))   # nearest facet
    assert comm.allgather(h) == [h] * comm.size
    assert h == pytest.approx(0.125, rel=1e-12) and h_near == pytest.approx(0.125, rel=1e-12)

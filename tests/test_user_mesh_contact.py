"""A user's own gmsh mesh (``mesh_file``) for the Hertz cases, against Hertz; bad meshes.

Each body is built here by gmsh as the case cannot build it: cut lower than the
case's centre plane (the loaded face at 0.8 R, 0.6 R in 3D), refined by a box
(not the case's disk around the contact point), meshed by plain Delaunay
without smoothing or Netgen optimisation, and placed away from the origin (the
case moves it).  The
references are the Hertz closed forms (:func:`tribofx.references.hertz_reference`,
:func:`tribofx.references.hertz`) of the case's parameters, with tolerances
from an error estimate:

* contact size: the measured size is the sum of the lumped nodal weights of the
  active nodes, h/2 beyond the last active node, and the discrete edge of
  contact lies within one element of the true one, so |a − a_H| ≤ h_edge, the
  longest contact element (measured on the mesh written here) that touches
  0.5 a_H ≤ r ≤ 1.5 a_H;
* peak pressure: the load is exact (load control), and p₀ = 2P/(πa) (line) or
  3P/(2πa²) (point) moves with the contact size as −δa/a (−2δa/a), so
  |p_max/p₀ − 1| ≤ h_edge/a_H (2 h_edge/a_H in 3D, where the nodal peak of
  unstructured linear tetrahedra also carries noise of that order);
* model error of finite strain and finite body size against the linear,
  half-space theory: first order in a/R*, bounded by ε = a_H/R* (2.4 % in 2D,
  4 % in 3D, 4.8 % for two cylinders; a check of the bound, not a reference:
  the built 2D mesh at levels 4 and 5 (a/96, a/192) is within 0.5 % in a and
  0.6 % in p₀ of Hertz at a/R = 0.024).

So |a/a_H − 1| ≤ h_edge/a_H + ε and |p_max/p₀ − 1| ≤ c h_edge/a_H + ε (c = 1, 2).
"""

import json
import os
import subprocess
import sys

import gmsh
import numpy as np
import pytest
from cli_checks import assert_one_line_error
from mpi4py import MPI

from tribofx.references import hertz, hertz_reference

ENV = dict(os.environ, UCX_TLS="self,sm,tcp", OMP_NUM_THREADS="1")
CLI = [sys.executable, "-m", "tribofx.cli"]
R, E, NU = 10.0, 10.0, 0.3
LOAD_2D, LOAD_3D = 0.05, 0.1
# where the test puts the bodies (the case moves them): symmetry plane, contact plane
X0, Y0 = 3.0, -2.0


def _run(*args):
    return subprocess.run(CLI + list(args), capture_output=True, text=True, env=ENV,
                          timeout=900)


def _results(out):
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "ok", s["status"]
    return s, {k: v["value"] for k, v in s["results"].items()}


def _box_field(lo, hi, h_in, h_out, thickness):
    """Size h_in inside the box [lo, hi], growing to h_out over ``thickness`` outside."""
    f = gmsh.model.mesh.field
    b = f.add("Box")
    for k, (a, c) in enumerate(zip(lo, hi)):
        f.setNumber(b, f"{'XYZ'[k]}Min", a)
        f.setNumber(b, f"{'XYZ'[k]}Max", c)
    f.setNumber(b, "VIn", h_in)
    f.setNumber(b, "VOut", h_out)
    f.setNumber(b, "Thickness", thickness)
    f.setAsBackgroundMesh(b)
    for k in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
        gmsh.option.setNumber(f"Mesh.{k}", 0)


def _write(path, dim, groups, skip):
    """Add the named boundary groups but ``skip``, mesh, write; the contact elements.

    Returns the contact elements (simplices of dimension dim − 1) as an array
    (n, dim, 3) of their node coordinates.
    """
    for tag, (name, ents) in enumerate(groups.items(), start=10):
        if name not in skip:
            gmsh.model.addPhysicalGroup(dim - 1, ents, tag, name)
    gmsh.model.mesh.generate(dim)
    elems = []
    for e in groups["contact"]:
        _, _, conn = gmsh.model.mesh.getElements(dim - 1, e)
        node_tags, coords, _ = gmsh.model.mesh.getNodes(dim - 1, e, includeBoundary=True)
        where = {t: c for t, c in zip(node_tags, coords.reshape(-1, 3))}
        elems.append(np.array([[where[t] for t in el]
                               for el in conn[0].reshape(-1, dim)]))
    gmsh.write(str(path))
    gmsh.finalize()
    return np.concatenate(elems)


def _start(name):
    gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Algorithm", 5)      # Delaunay (the case: frontal-Delaunay)
    gmsh.option.setNumber("Mesh.Smoothing", 0)
    gmsh.model.add(name)


def cylinder_2d(path, h0, box, radius=R, below=False, skip=()):
    """x ≥ X0 half of the cylinder touching y = Y0 (from above, or ``below``), cut at 0.8 R.

    Returns ``(path, contact elements)``: the contact elements as (n, 2, 3) node
    coordinates in the mesh's own frame.
    """
    _start("user_cylinder")
    occ = gmsh.model.occ
    s = -1.0 if below else 1.0
    disk = occ.addDisk(X0, Y0 + s * radius, 0, radius, radius)
    rect = occ.addRectangle(X0, Y0 + min(0.0, s * 0.8 * radius), 0, radius, 0.8 * radius)
    occ.intersect([(2, disk)], [(2, rect)])
    occ.synchronize()
    named = {"contact": [], "loaded": [], "symmetry_x": []}
    for _, c in gmsh.model.getEntities(1):
        x, y, _ = occ.getCenterOfMass(1, c)
        if abs(x - X0) < 1e-9:
            named["symmetry_x"].append(c)
        elif abs(y - (Y0 + s * 0.8 * radius)) < 1e-9:
            named["loaded"].append(c)
        else:
            named["contact"].append(c)
    gmsh.model.addPhysicalGroup(2, [t for _, t in gmsh.model.getEntities(2)], 1, "body")
    lo, hi = (X0, Y0 - box / 2 if below else Y0), (X0 + box, Y0 if below else Y0 + box / 2)
    _box_field(lo + (-1.0,), hi + (1.0,), h0, radius / 5, radius / 2)
    elems = _write(path, 2, named, skip)
    return path, elems


def sphere_3d(path, h0, box, skip=()):
    """x ≥ X0, y ≥ Y0 quarter of the sphere touching z = Y0, cut at 0.6 R; as cylinder_2d."""
    _start("user_sphere")
    occ = gmsh.model.occ
    ball = occ.addSphere(X0, Y0, Y0 + R, R)
    cut = occ.addBox(X0, Y0, Y0, R, R, 0.6 * R)
    occ.intersect([(3, ball)], [(3, cut)])
    occ.synchronize()
    named = {"contact": [], "loaded": [], "symmetry_x": [], "symmetry_y": []}
    for _, f in gmsh.model.getEntities(2):
        x, y, z = occ.getCenterOfMass(2, f)
        if abs(x - X0) < 1e-9:
            named["symmetry_x"].append(f)
        elif abs(y - Y0) < 1e-9:
            named["symmetry_y"].append(f)
        elif abs(z - (Y0 + 0.6 * R)) < 1e-9:
            named["loaded"].append(f)
        else:
            named["contact"].append(f)
    gmsh.model.addPhysicalGroup(3, [t for _, t in gmsh.model.getEntities(3)], 1, "body")
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)   # Delaunay, no Netgen optimisation
    _box_field((X0, Y0, Y0), (X0 + box, Y0 + box, Y0 + box / 2), h0, R / 4, R / 2)
    elems = _write(path, 3, named, skip)
    return path, elems


def edge_size(elems, a, axes):
    """Longest edge of the contact elements touching 0.5 a ≤ r ≤ 1.5 a (r from the axis)."""
    r = np.linalg.norm(elems[:, :, axes] - np.array([X0, Y0][: len(axes)]), axis=2)
    near = (r.max(axis=1) >= 0.5 * a) & (r.min(axis=1) <= 1.5 * a)
    k = elems.shape[1]
    edges = [np.linalg.norm(elems[:, i] - elems[:, j], axis=1)
             for i in range(k) for j in range(i + 1, k)]
    return float(np.max(np.max(edges, axis=0)[near]))


def _near_nodes(elems, r):
    """Contact nodes within r of the symmetry plane x = X0, sorted by x."""
    x = np.unique(elems.reshape(-1, 3), axis=0)
    x = x[x[:, 0] - X0 < r]
    return x[np.argsort(x[:, 0])]


def check_hertz(res, a_h, p_h, h_edge, eps, c_p, key):
    da, dp = abs(res[key] / a_h - 1), abs(res["p_max"] / p_h - 1)
    tol_a, tol_p = h_edge / a_h + eps, c_p * h_edge / a_h + eps
    print(f"{key}: {res[key]:.5g} vs Hertz {a_h:.5g} (|rel| {da:.4f} <= {tol_a:.4f}); "
          f"p_max {res['p_max']:.5g} vs {p_h:.5g} (|rel| {dp:.4f} <= {tol_p:.4f}); "
          f"h_edge = {h_edge:.4g} mm = a/{a_h / h_edge:.1f}")
    assert da <= tol_a and dp <= tol_p


def test_user_cylinder_against_hertz(tmp_path):
    a_h, p_h = hertz_reference(2, E, NU, R, LOAD_2D)
    mesh, elems = cylinder_2d(tmp_path / "cyl.msh", a_h / 16, 3 * a_h)
    out = tmp_path / "run"
    p = _run("run", "hertz", "--set", f"mesh_file={mesh}", "--set", f"load={LOAD_2D}",
             "--set", "steps=1", "--out", str(out), "--quiet")
    assert p.returncode == 0, p.stderr
    s, res = _results(out)
    assert s["parameters"]["mesh_file"]["value"] == str(mesh)
    assert res["hertz_contact_half_width"] == pytest.approx(a_h, rel=1e-14)
    # ρ_N from the user's contact facets near the axis, not from `mesh`
    assert res["contact_element_size"] == pytest.approx(a_h / 16, rel=0.3)
    check_hertz(res, a_h, p_h, edge_size(elems, a_h, [0]), a_h / R, 1, "contact_half_width")


def test_user_sphere_against_hertz(tmp_path):
    a_h, p_h = hertz_reference(3, E, NU, R, LOAD_3D)
    mesh, elems = sphere_3d(tmp_path / "sphere.msh", a_h / 6, 2 * a_h)
    out = tmp_path / "run"
    p = _run("run", "hertz", "--set", "dim=3", "--set", f"mesh_file={mesh}",
             "--set", f"load={LOAD_3D}", "--set", "steps=1", "--out", str(out), "--quiet")
    assert p.returncode == 0, p.stderr
    _, res = _results(out)
    check_hertz(res, a_h, p_h, edge_size(elems, a_h, [0, 1]), a_h / R, 2, "contact_radius")


def test_user_cylinders_against_hertz(tmp_path):
    """Both cylinders from files; the lower one the mirror image of the upper one.

    Node-to-segment contact transmits the pressure exactly only if every master
    node is a slave node (the patch test, tribofx.cases.contact_patch): the two
    meshes share their contact nodes (checked), and the equal materials keep
    them matched under the load, so the estimate of the module docstring holds.
    """
    h = hertz(LOAD_2D, R, E, NU, R, E, NU, line=True)
    up, e_up = cylinder_2d(tmp_path / "upper.msh", h.a / 16, 3 * h.a)
    low, e_low = cylinder_2d(tmp_path / "lower.msh", h.a / 16, 3 * h.a, below=True)
    top, bottom = (_near_nodes(e, 3 * h.a) for e in (e_up, e_low))
    assert np.allclose(top[:, 0], bottom[:, 0], atol=1e-9 * R)          # the same x
    assert np.allclose(top[:, 1] - Y0, Y0 - bottom[:, 1], atol=1e-9 * R)  # mirrored
    out = tmp_path / "run"
    p = _run("run", "contact-two-cylinders", "--set", f"mesh_file={up}",
             "--set", f"mesh_file2={low}", "--set", f"load={LOAD_2D}", "--out", str(out),
             "--quiet")
    assert p.returncode == 0, p.stderr
    _, res = _results(out)
    assert res["equilibrium_error"] < res["equilibrium_bound"]
    check_hertz(res, h.a, h.p0, edge_size(e_up, h.a, [0]), h.a / h.R_star, 1,
                "contact_half_width")


def _bad(tmp_path, fragment, *sets, case="hertz"):
    out = tmp_path / "out"
    p = _run("run", case, *[a for s in sets for a in ("--set", s)], "--out", str(out),
             "--quiet")
    assert_one_line_error(p, fragment, out)


@pytest.mark.parametrize("make,sets,fragment", [
    (lambda d: cylinder_2d(d / "nosym.msh", 1.0, 2.0, skip=("symmetry_x",))[0], (),
     "no physical group 'symmetry_x'"),
    (lambda d: sphere_3d(d / "ball.msh", 2.0, 2.0)[0], (), "is 3D, the case needs a 2D mesh"),
    (lambda d: cylinder_2d(d / "disc.msh", 1.0, 2.0)[0], ("dim=3",),
     "is 2D, the case needs a 3D mesh"),
    (lambda d: sphere_3d(d / "nosymy.msh", 2.0, 2.0, skip=("symmetry_y",))[0], ("dim=3",),
     "no physical group 'symmetry_y'"),
    # a radius-10 cylinder run with R = 20: the Hertz comparison would be meaningless
    (lambda d: cylinder_2d(d / "r10.msh", 0.5, 2.0)[0], ("R=20",),
     "has the radius 10 mm at its first-contact point"),
])
def test_bad_hertz_mesh(tmp_path, make, sets, fragment):
    _bad(tmp_path, fragment, f"mesh_file={make(tmp_path)}", *sets)


@pytest.mark.parametrize("key,make,fragment", [
    ("mesh_file2", lambda d: cylinder_2d(d / "noload.msh", 1.0, 2.0, below=True,
                                         skip=("loaded",))[0], "no physical group 'loaded'"),
    ("mesh_file", lambda d: sphere_3d(d / "ball.msh", 2.0, 2.0)[0],
     "is 3D, the case needs a 2D mesh"),
    # an upper cylinder given as the lower body: its highest contact point is at the
    # equator, where the contact surface is vertical
    ("mesh_file2", lambda d: cylinder_2d(d / "upside.msh", 1.0, 2.0)[0],
     "at its first-contact point (its highest node"),
])
def test_bad_two_cylinders_mesh(tmp_path, key, make, fragment):
    _bad(tmp_path, fragment, f"{key}={make(tmp_path)}", case="contact-two-cylinders")


@pytest.mark.mpi
def test_user_cylinder_parallel_equals_serial(tmp_path):
    """The same user mesh on the ranks of COMM_WORLD and on one rank: the same results.

    Same discrete problem; the secant load control stops at |P − P*| ≤ 1e-6 P*,
    so partition-dependent round-off moves results by ~1e-6 relative.
    """
    if MPI.COMM_WORLD.size < 2:
        pytest.skip("compares COMM_WORLD with COMM_SELF: run under mpiexec -n 2")
    from tribofx.cases import hertz as hertz_case
    from tribofx.output import RunRecord
    from tribofx.params import resolve

    comm = MPI.COMM_WORLD
    a_h, _ = hertz_reference(2, E, NU, R, LOAD_2D)
    path = comm.bcast(str(tmp_path / "cyl.msh"), root=0)
    if comm.rank == 0:
        cylinder_2d(path, a_h / 8, 3 * a_h)
    comm.barrier()
    values = resolve(hertz_case.Params, {"mesh_file": path, "load": str(LOAD_2D),
                                        "steps": "1"})
    hertz_case.validate(values)
    results, dofs = [], []
    for c in (comm, MPI.COMM_SELF):
        rec = RunRecord("hertz", values, None,
                        tmp_path, c)
        rec.profile = None
        hertz_case.run(values, rec, comm=c)
        results.append({k: v["value"] for k, v in rec.data["results"].items()})
        dofs.append(rec.data["num_dofs"])
    par, ser = results
    assert dofs[0] == dofs[1]
    for key in ("contact_half_width", "p_max", "normal_load_full_body",
                "pressure_profile_rel_l2_error", "contact_element_size"):
        print(key, par[key], ser[key])
        assert par[key] == pytest.approx(ser[key], rel=1e-5)

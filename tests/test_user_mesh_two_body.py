"""A user's own gmsh mesh (``mesh_file``) for the two-body cases; bad meshes.

``wear-reciprocating``: the pin is built here by gmsh as the case cannot build
it — an elliptic tip (a B-spline through points of an ellipse of semi-axes 2
and 1 mm, tip curvature radius 4 mm against the case's circle of 2 mm), width
2.5 mm (not the default W = 2), an unstructured mesh, placed away from the
block (the case moves it).  ``contact-ironing``: a half-disc die of the case's
radius meshed otherwise (two transfinite quarter arcs with a node at the
bottom, a finer arc than the case's, plain Delaunay inside), placed away from
the slab.  The references and their tolerances are derived in each test.
"""

import json
import math
import os
import subprocess
import sys

import gmsh
import numpy as np
import pytest
from cli_checks import assert_one_line_error

ENV = dict(os.environ, UCX_TLS="self,sm,tcp", OMP_NUM_THREADS="1")
CLI = [sys.executable, "-m", "tribofx.cli"]
# the user's pin: width, height, semi-axes of the elliptic tip (x, y)
W, H, AX, AY = 2.5, 2.0, 2.0, 1.0
# where the test puts the bodies (the cases move them)
X0, Y0 = 3.0, -2.0
R_DIE = 3.0        # the die's radius: the case's default R
CHEAP = ("mesh=0", "cycles=100", "dt=10", "fast_steps=8")      # as tests/test_parallel.py
IRON = ("n=30", "press_steps=3", "slide_steps=4", "slide=0.5")


def _run(case, out, *sets):
    args = [a for s in sets for a in ("--set", s)]
    return subprocess.run(CLI + ["run", case, *args, "--out", str(out), "--quiet"],
                          capture_output=True, text=True, env=ENV, timeout=900)


def _results(out):
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "ok", s["status"]
    par = {k: v["value"] for k, v in s["parameters"].items()}
    return s, par, {k: v["value"] for k, v in s["results"].items()}


def _start(name):
    gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 5)      # Delaunay
    gmsh.model.add(name)


def _finish(path, dim, groups, skip):
    """Add the named boundary groups but ``skip``, mesh in ``dim`` and write ``path``."""
    for tag, (name, ents) in enumerate(groups.items(), start=10):
        if name not in skip:
            gmsh.model.addPhysicalGroup(dim - 1, ents, tag, name)
    gmsh.model.mesh.generate(dim)
    gmsh.write(str(path))
    gmsh.finalize()
    return path


def _pin(path, width=W, h=0.2, skip=(), dim=2):
    """Write a pin of width ``width`` with an elliptic tip, its lowest point at (X0, Y0).

    Tip y − Y0 = AY (1 − √(1 − (x − X0)²/AX²)), a B-spline through 17 of its
    points; straight sides and top at Y0 + H; element size h.  ``dim=3``: the
    pin extruded by 1 mm (a mesh of the wrong dimension).
    """
    _start("user_pin")
    occ = gmsh.model.occ
    xs = np.linspace(-width / 2, width / 2, 17)
    tip = [occ.addPoint(X0 + x, Y0 + AY * (1 - math.sqrt(1 - (x / AX) ** 2)), 0) for x in xs]
    tr, tl = occ.addPoint(X0 + width / 2, Y0 + H, 0), occ.addPoint(X0 - width / 2, Y0 + H, 0)
    curves = [occ.addBSpline(tip), occ.addLine(tip[-1], tr), occ.addLine(tr, tl),
              occ.addLine(tl, tip[0])]
    surf = occ.addPlaneSurface([occ.addCurveLoop(curves)])
    if dim == 3:
        top = occ.extrude([(2, surf)], 0, 0, 1.0)
        occ.synchronize()
        gmsh.model.addPhysicalGroup(3, [t for d, t in top if d == 3], 1, "body")
        groups = {"contact": [], "top": [], "sides": []}
        for _, f in gmsh.model.getEntities(2):
            _, y, _ = occ.getCenterOfMass(2, f)
            groups["top" if abs(y - Y0 - H) < 1e-9 else "sides"].append(f)
    else:
        occ.synchronize()
        gmsh.model.addPhysicalGroup(2, [surf], 1, "body")
        groups = {"contact": [curves[0]], "top": [curves[2]], "sides": [curves[1], curves[3]]}
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    return _finish(path, dim, groups, skip)


def _die(path, m=32, upside_down=False, swap=False, skip=(), dim=2):
    """Write the half disc of radius R_DIE below its centre (X0, Y0); its longest arc chord.

    Two quarter arcs meeting at the bottom point (a node there), each with m
    transfinite segments, the top the diameter; Delaunay inside up to R/4.
    ``upside_down``: the half disc above the centre (the arc is its top);
    ``swap``: the group names swapped (arc on the diameter, top on the arcs).
    ``dim=3``: extruded by 1 mm.  Returns ``(path, longest arc chord)``.
    """
    _start("user_die")
    geo = gmsh.model.geo
    c = geo.addPoint(X0, Y0, 0)
    left, right = geo.addPoint(X0 - R_DIE, Y0, 0), geo.addPoint(X0 + R_DIE, Y0, 0)
    bottom = geo.addPoint(X0, Y0 + (R_DIE if upside_down else -R_DIE), 0)
    arcs = [geo.addCircleArc(left, c, bottom), geo.addCircleArc(bottom, c, right)]
    top = geo.addLine(right, left)
    surf = geo.addPlaneSurface([geo.addCurveLoop([*arcs, top])])
    for a in arcs:
        geo.mesh.setTransfiniteCurve(a, m + 1)
    groups = {"arc": [top], "top": arcs} if swap else {"arc": arcs, "top": [top]}
    if dim == 3:
        out = geo.extrude([(2, surf)], 0, 0, 1.0)
        geo.synchronize()
        gmsh.model.addPhysicalGroup(3, [t for d, t in out if d == 3], 1, "body")
        # the extruded faces: out = [front, volume, lateral faces of arcs[0], arcs[1], top]
        groups = {"arc": [out[2][1], out[3][1]], "top": [out[4][1]]}
    else:
        geo.synchronize()
        gmsh.model.addPhysicalGroup(2, [surf], 1, "body")
    gmsh.option.setNumber("Mesh.MeshSizeMax", R_DIE / 4)
    _finish(path, dim, groups, skip)
    return path, 2 * R_DIE * math.sin(math.pi / (4 * m))


def test_user_pin_wears_by_archard(tmp_path):
    """wear-reciprocating with the elliptic pin: Archard (14), eq. (18), the pin's load.

    Each shape step (28) sweeps exactly the volume Δt ∫ W̄̇ dŜ of its averaged
    rate, to the tolerance of the ζ rows (1e-12 × body size per unit length,
    ~1e-11 mm² per mm for surfaces of a few mm, against worn areas of 1.6e-3
    (block) to 5.3e-3 mm² (pin) here: < 1e-8 per step, two steps), whatever the
    tip's shape, so relative
    1e-7 is a safe bound for: worn pin area = K_pin × the dissipated energy
    (Archard in dissipation form, eq. 14), worn block area = K_block/K_pin ×
    worn pin area (eq. 18, both driven by the pin's dissipation) and each worn
    area = Σ Δt × its rate integral.  The pin carries F whatever its width: the
    contact force on it along y is F to the bound n_u · atol_u of the sum of
    its momentum rows (each below atol_u at a solved state) — with the default
    W = 2 in the traction instead of the mesh's 2.5 it would be 1.25 F.  The
    drive's work over the last cycle is its dissipation to the bound of the
    trapezoidal rule (the stored energy returns at the end of the cycle).
    """
    mesh = _pin(tmp_path / "pin.msh")
    out = tmp_path / "run"
    p = _run("wear-reciprocating", out, f"mesh_file={mesh}", "K_block=3e-5", *CHEAP)
    assert p.returncode == 0, p.stderr
    s, par, r = _results(out)
    assert par["mesh_file"] == str(mesh)
    # the geometry the case took from the mesh (not the defaults W = H = 2)
    assert r["pin_width"] == pytest.approx(W, rel=1e-12)
    assert r["pin_top_length"] == pytest.approx(W, rel=1e-12)
    a_pin, a_block = np.array(r["worn_area_pin"]), np.array(r["worn_area_block"])
    dt, rel = np.array(r["dt"]), 1e-7
    K_pin, K_block = par["K_pin"], par["K_block"]
    print(f"worn pin {float(a_pin[-1])!r} vs K_pin D = {K_pin * r['dissipated_energy'][-1]!r}; "
          f"block {float(a_block[-1])!r} vs K_block/K_pin pin = "
          f"{float(K_block / K_pin * a_pin[-1])!r}; "
          f"normal force {r['normal_force']} (F = {par['F']}, bound "
          f"{r['normal_force_bound']:.3g})")
    assert len(a_pin) == 3 and a_pin[-1] > 1e-3
    assert a_pin[-1] == pytest.approx(K_pin * r["dissipated_energy"][-1], rel=rel)
    assert a_block[-1] == pytest.approx(K_block / K_pin * a_pin[-1], rel=rel)
    for a, rate in ((a_pin, r["rate_integral_pin"]), (a_block, r["rate_integral_block"])):
        assert np.allclose(a[1:], np.cumsum(dt[1:] * np.array(rate[1:])), rtol=rel, atol=0)
    for N in r["normal_force"]:
        assert abs(N - par["F"]) <= r["normal_force_bound"]
    for work, diss, bound in zip(r["drive_work"][1:], r["cycle_dissipation"][1:],
                                 r["drive_work_bound"][1:]):
        assert abs(work - diss) <= bound


def test_user_die_irons_as_the_case_die(tmp_path):
    """contact-ironing with the user's die: its equilibrium, and the force against the case's die.

    Equilibrium of the solved die (reaction at its top against the contact
    force) to the case's bound n_u · atol_u.  Force at the end of pressing:
    both dies are polygons inscribed in the same circle C (radius R, lowest
    point on the slab at x_c = R/2 + 1: the case's die by construction, the
    user's because the case centres its x extent there and puts its lowest arc
    node — the bottom node — on the slab), so each lies between C and the
    concentric circle C' of radius R − s, s = R − √(R² − c²/4) the sagitta of
    the longest arc chord c of the coarser die.  A larger indenter pushed to the
    same place takes at least the force of a smaller one (frictionless linear
    elasticity; to first order here), so both forces lie between F(C) and F(C'),
    and C' is C raised by s (depth d − s) with a radius smaller by s:
    |F_user − F_case| ≤ F'(d) s + F s/R, with |∂ ln F/∂ ln R| ≤ 1 (½ for a
    cylinder on a thin layer) and F'(d) the one-sided second-order difference
    of the case's press history (exact for F ∝ d², the measured local exponent
    is ≈ 2).  Not in the bound: the die's own compliance (E_die = 1000 E, an
    elastic approach of ~1e-3 of the slab's, i.e. ~5e-4 mm) differs between
    the two meshes by a fraction of that, an order below s = 3.7e-3 mm.
    """
    from dolfinx import mesh as dmesh
    from mpi4py import MPI
    from tribofx.meshes.ironing import ARC, die_body

    mesh, c_user = _die(tmp_path / "die.msh")
    runs = {}
    for key, sets in (("case", ()), ("user", (f"mesh_file={mesh}",))):
        out = tmp_path / key
        p = _run("contact-ironing", out, *IRON, *sets)
        assert p.returncode == 0, p.stderr
        runs[key] = _results(out)
    _, par, r = runs["user"]
    assert max(r["equilibrium_error"]) <= r["equilibrium_bound"], r["equilibrium_error"]
    assert r["die_half_width"] == pytest.approx(R_DIE, rel=1e-12)
    # its arc has m equal chords: the mean facet size is the chord
    assert r["die_element_size"] == pytest.approx(c_user, rel=1e-9)
    # the case's own die, built as the case builds it: its longest arc chord
    h = par["L"] / par["n"]
    msh, ft = die_body(R_DIE, 0.5 * R_DIE + 1, par["H"] + R_DIE, h, MPI.COMM_SELF)
    x = msh.geometry.x[dmesh.entities_to_geometry(msh, 1, ft.find(ARC), False)]
    c_case = float(np.max(np.linalg.norm(x[:, 0] - x[:, 1], axis=1)))
    c = max(c_case, c_user)
    s = R_DIE - math.sqrt(R_DIE**2 - c * c / 4)
    k = par["press_steps"]
    F = np.r_[0.0, np.array(runs["case"][2]["reaction_force"])[:k, 1]]   # F(0) = 0
    F_user = r["reaction_force"][k - 1][1]
    slope = (3 * F[-1] - 4 * F[-2] + F[-3]) / (2 * par["depth"] / k)
    tol = slope * s + F[-1] * s / R_DIE
    print(f"end of pressing: F_user {F_user:.6g}, F_case {F[-1]:.6g} N/mm: "
          f"|diff| {abs(F_user - F[-1]):.3g} <= {tol:.3g} (F' {slope:.4g} N/mm^2, "
          f"s {s:.3g} mm, chords {c_case:.4g}, {c_user:.4g} mm)")
    assert abs(F_user - F[-1]) <= tol


def _bad(tmp_path, case, fragment, path, *sets):
    out = tmp_path / "out"
    p = _run(case, out, f"mesh_file={path}", *sets)
    assert_one_line_error(p, fragment, out)


@pytest.mark.parametrize("make,sets,fragment", [
    (lambda d: _pin(d / "nosides.msh", skip=("sides",)), (), "no physical group 'sides'"),
    (lambda d: _pin(d / "slab.msh", dim=3, h=0.6), (), "is 3D, the case needs a 2D mesh"),
    # the stroke check with the mesh's width: L = 4.2 < 2.5 + 2·0.5 + 1 (the default
    # W = 2 would pass it)
    (lambda d: _pin(d / "wide.msh", h=0.6), ("L=4.2",),
     "must exceed W + 2A + 1 = 4.5 mm (W = 2.5 mm"),
])
def test_bad_user_pin(tmp_path, make, sets, fragment):
    _bad(tmp_path, "wear-reciprocating", fragment, make(tmp_path), *sets)


@pytest.mark.parametrize("make,fragment", [
    (lambda d: _die(d / "notop.msh", m=6, skip=("top",))[0], "no physical group 'top'"),
    (lambda d: _die(d / "slab.msh", m=6, dim=3)[0], "is 3D, the case needs a 2D mesh"),
    (lambda d: _die(d / "upside.msh", m=6, upside_down=True)[0],
     "has 'top' as low as its lowest 'arc' node: 'arc' must be its lower boundary"),
    (lambda d: _die(d / "swapped.msh", m=6, swap=True)[0],
     "reaches 3 mm below its lowest 'arc' node: 'arc' must be its lower boundary"),
])
def test_bad_user_die(tmp_path, make, fragment):
    _bad(tmp_path, "contact-ironing", fragment, make(tmp_path))

"""Tests of the closest-point projection kernel (C++) and its NumPy twin."""

from __future__ import annotations

import numpy as np
import pytest

from tribofx import _cpp
from tribofx.projection import CELL_TYPES, ProjectionResult, closest_point_projection
from tribofx.projection_ref import closest_point_projection_ref

FIELDS = [f for f in ProjectionResult.__dataclass_fields__]


# --------------------------------------------------------------------------------------
# Mesh generators (independent of the code under test)
# --------------------------------------------------------------------------------------
def curve_mesh(n: int, cell: str, rng: np.random.Generator):
    """Polyline/P2 curve on a perturbed graph y = g(x), x in [0, 1]."""
    m = 1 if cell == "interval" else 2
    s = np.linspace(0.0, 1.0, m * n + 1)
    s[1:-1] += rng.uniform(-0.2, 0.2, len(s) - 2) / (m * n)
    y = 0.3 * np.sin(2 * np.pi * s) + 0.05 * np.sin(7 * s) + 0.01 * rng.standard_normal(len(s))
    nodes = np.c_[s, y]
    facets = [[m * i, m * i + m] + ([m * i + 1] if m == 2 else []) for i in range(n)]
    return nodes, np.array(facets, dtype=np.int32)


def surface_mesh(nx: int, cell: str, rng: np.random.Generator, jitter: float = 0.01):
    """Structured surface z = f(x, y) + noise on [0, 1]^2 (quadratic nodes on the graph)."""
    m = 2 if cell in ("triangle6", "quadrilateral9") else 1
    N = m * nx + 1
    u = np.linspace(0.0, 1.0, N)
    X, Y = np.meshgrid(u, u, indexing="xy")
    X = X + rng.uniform(-0.15, 0.15, X.shape) / (m * nx)
    Y = Y + rng.uniform(-0.15, 0.15, Y.shape) / (m * nx)
    Z = 0.2 * np.sin(3 * X) * np.cos(2 * Y) + jitter * rng.standard_normal(X.shape)
    nodes = np.c_[X.ravel(), Y.ravel(), Z.ravel()]

    def node(i, j):
        return j * N + i

    facets = []
    for j in range(0, N - 1, m):
        for i in range(0, N - 1, m):
            a, b, c, d = (i, j), (i + m, j), (i, j + m), (i + m, j + m)

            def mid(p, q):
                return node((p[0] + q[0]) // 2, (p[1] + q[1]) // 2)

            if cell == "triangle":
                facets += [[node(*a), node(*b), node(*d)], [node(*a), node(*d), node(*c)]]
            elif cell == "triangle6":
                for p, q, r in ((a, b, d), (a, d, c)):
                    facets.append([node(*p), node(*q), node(*r), mid(q, r), mid(p, r), mid(p, q)])
            elif cell == "quadrilateral":
                facets.append([node(*a), node(*b), node(*c), node(*d)])
            else:
                facets.append(
                    [node(*a), node(*b), node(*c), node(*d), mid(a, b), mid(a, c), mid(b, d),
                     mid(c, d), mid(a, d)]
                )  # fmt: skip
    return nodes, np.array(facets, dtype=np.int32)


def point_cloud(nodes: np.ndarray, facets: np.ndarray, n: int, rng: np.random.Generator):
    """Mix of points on (mesh nodes, facet node averages), near and far from the surface."""
    gdim = nodes.shape[1]
    lo, hi = nodes.min(axis=0), nodes.max(axis=0)
    size = np.linalg.norm(hi - lo)
    on_nodes = nodes[rng.choice(len(nodes), n // 10)]
    f = rng.choice(len(facets), n // 10)
    w = rng.dirichlet(np.ones(facets.shape[1]), len(f))
    averages = np.einsum("pk,pkg->pg", w, nodes[facets[f]])
    near = nodes[rng.choice(len(nodes), n // 2)] + 0.02 * size * rng.standard_normal((n // 2, gdim))
    n_far = n - len(on_nodes) - len(averages) - len(near)
    far = lo - 0.5 * size + 2.0 * size * rng.random((n_far, gdim))
    return np.concatenate([on_nodes, averages, near, far])


def assert_results_equal(a: ProjectionResult, b: ProjectionResult, scale: float = 1.0):
    # Both implementations run the identical algorithm in double precision with
    # the same operation order, so they agree to round-off; 1e-10 leaves room
    # for compiler differences (e.g. contraction) amplified by Newton solves.
    np.testing.assert_array_equal(a.facet, b.facet)
    np.testing.assert_array_equal(a.inside, b.inside)
    for f in FIELDS:
        x, y = getattr(a, f), getattr(b, f)
        assert x.shape == y.shape, f
        assert x.dtype == y.dtype, f
        if f not in ("facet", "inside"):
            np.testing.assert_allclose(x, y, rtol=1e-10, atol=1e-10 * scale, err_msg=f)


# --------------------------------------------------------------------------------------
# C++ vs NumPy twin
# --------------------------------------------------------------------------------------
@pytest.mark.parametrize("cell", ["interval", "interval3"])
def test_cpp_matches_numpy_2d(cell):
    rng = np.random.default_rng(11)
    nodes, facets = curve_mesh(40, cell, rng)
    points = point_cloud(nodes, facets, 3000, rng)
    a = closest_point_projection(points, nodes, facets, cell)
    b = closest_point_projection_ref(points, nodes, facets, cell)
    assert_results_equal(a, b)
    assert a.xi.shape == (len(points), 1) and a.dn_dx.shape == (len(points), 2, 2)
    assert 0.1 < a.inside.mean() < 0.99  # both interior and clamped cases covered


@pytest.mark.parametrize("cell", ["triangle", "triangle6", "quadrilateral", "quadrilateral9"])
def test_cpp_matches_numpy_3d(cell):
    rng = np.random.default_rng(7)
    nodes, facets = surface_mesh(6, cell, rng)
    points = point_cloud(nodes, facets, 2000, rng)
    a = closest_point_projection(points, nodes, facets, cell)
    b = closest_point_projection_ref(points, nodes, facets, cell)
    assert_results_equal(a, b)
    n = len(points)
    assert a.xi.shape == (n, 2) and a.tangents.shape == (n, 2, 3)
    assert a.curvature.shape == (n, 2, 2) and a.dxbar_dx.shape == (n, 3, 3)
    assert a.facet.dtype == np.int32 and a.inside.dtype == bool
    assert 0.1 < a.inside.mean() < 0.99
    # Closest point: no facet node is closer than the projection
    d_nodes = np.min(np.linalg.norm(points[:, None, :] - nodes[None], axis=-1), axis=1)
    assert np.all(a.distance <= d_nodes * (1 + 1e-12) + 1e-14)
    if cell in ("triangle",):
        np.testing.assert_array_equal(a.dn_dx, 0.0)
    else:
        assert np.abs(a.dn_dx).max() > 1e-3


def test_tree_search_matches_brute_force_large_mesh():
    """Many facets (deep tree) with few points: the pruned search finds the same facet."""
    rng = np.random.default_rng(3)
    nodes, facets = surface_mesh(24, "triangle", rng, jitter=0.003)
    points = point_cloud(nodes, facets, 300, rng)
    a = closest_point_projection(points, nodes, facets, "triangle")
    b = closest_point_projection_ref(points, nodes, facets, "triangle")
    assert_results_equal(a, b)


def test_ties_take_lowest_facet_index():
    # Two triangles of the plane z = 0 sharing the edge (0,0)-(1,1); points above
    # that edge are equidistant from both; order the facets both ways.
    nodes = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], dtype=float)
    f = np.array([[0, 1, 3], [0, 3, 2]])
    t = np.linspace(0.1, 0.9, 9)
    points = np.c_[t, t, 0.3 + 0 * t]
    for facets in (f, f[::-1]):
        for fn in (closest_point_projection, closest_point_projection_ref):
            r = fn(points, nodes, facets, "triangle")
            np.testing.assert_array_equal(r.facet, 0)
            np.testing.assert_allclose(r.gap, 0.3, rtol=1e-14)


def test_int64_facets_and_empty_points():
    rng = np.random.default_rng(5)
    nodes, facets = surface_mesh(3, "quadrilateral", rng)
    points = point_cloud(nodes, facets, 50, rng)
    a = closest_point_projection(points, nodes, facets.astype(np.int64), "quadrilateral")
    b = closest_point_projection(points, nodes, facets, "quadrilateral")
    assert_results_equal(a, b)
    e = closest_point_projection(np.zeros((0, 3)), nodes, facets, "quadrilateral")
    assert e.xi.shape == (0, 2) and e.dxbar_dx.shape == (0, 3, 3)


# --------------------------------------------------------------------------------------
# Analytic checks
# --------------------------------------------------------------------------------------
@pytest.mark.parametrize("cell", ["triangle", "quadrilateral"])
def test_plane_gap_is_signed_distance(cell):
    rng = np.random.default_rng(1)
    nodes, facets = surface_mesh(5, cell, rng, jitter=0.0)
    # Map onto the tilted plane through p0 with normal nz; nodes keep in-plane jitter
    nodes[:, 2] = 0.0
    R, _ = np.linalg.qr(rng.standard_normal((3, 3)))
    R *= np.sign(np.linalg.det(R))  # rotation, keeps the facet orientation
    p0 = np.array([0.3, -0.2, 0.5])
    nodes = nodes @ R.T + p0
    normal = R[:, 2]
    # Points above the interior of the patch, both sides
    uvw = np.c_[rng.uniform(0.1, 0.9, (500, 2)), rng.uniform(-2.0, 2.0, 500)]
    points = uvw @ R.T + p0
    for fn in (closest_point_projection, closest_point_projection_ref):
        r = fn(points, nodes, facets, cell)
        np.testing.assert_allclose(r.gap, uvw[:, 2], atol=1e-13)
        np.testing.assert_allclose(r.distance, np.abs(uvw[:, 2]), atol=1e-13)
        np.testing.assert_allclose(r.normal, np.tile(normal, (500, 1)), atol=1e-13)
        np.testing.assert_allclose(r.x_bar, points - uvw[:, 2:] * normal, atol=1e-13)
        np.testing.assert_allclose(r.curvature, 0.0, atol=1e-13)
        np.testing.assert_allclose(r.dn_dx, 0.0, atol=1e-12)
        # x_bar is the orthogonal projection: d x_bar / dx = I - n n^T
        P = np.eye(3) - np.outer(normal, normal)
        Pi = np.broadcast_to(P, (r.inside.sum(), 3, 3))
        np.testing.assert_allclose(r.dxbar_dx[r.inside], Pi, atol=1e-12)
        assert r.inside.mean() > 0.9


def circle_mesh(n: int, cell: str, R: float, c: np.ndarray):
    """n segments on a circle, counter-clockwise, so that the normal points outwards."""
    m = 1 if cell == "interval" else 2
    phi = np.linspace(0.0, 2 * np.pi, m * n, endpoint=False)
    nodes = c + R * np.c_[np.cos(phi), np.sin(phi)]
    facets = [[m * i, (m * i + m) % (m * n)] + ([m * i + 1] if m == 2 else []) for i in range(n)]
    return nodes, np.array(facets, dtype=np.int32)


def test_circle_gap_convergence_and_curvature():
    R, c = 0.7, np.array([0.2, -0.1])
    rng = np.random.default_rng(2)
    phi = rng.uniform(0, 2 * np.pi, 2000)
    r = R * rng.uniform(0.6, 1.5, 2000)
    points = c + r[:, None] * np.c_[np.cos(phi), np.sin(phi)]
    exact = r - R
    ns = [8, 16, 32, 64]
    err = {"interval": [], "interval3": []}
    for cell in err:
        for n in ns:
            nodes, facets = circle_mesh(n, cell, R, c)
            res = closest_point_projection(points, nodes, facets, cell)
            err[cell].append(np.abs(res.gap - exact).max())
            if cell == "interval3" and n == 32:
                # Geometric curvature kappa = -b_11 / |t|^2 (outward normal) ~ 1/R
                t2 = np.sum(res.tangents[:, 0] ** 2, axis=-1)
                kappa = -res.curvature[:, 0, 0] / t2
                np.testing.assert_allclose(kappa, 1 / R, rtol=2e-2)
    rates = {k: np.log2(np.array(v[:-1]) / np.array(v[1:])) for k, v in err.items()}
    # Linear chords: sag R (1 - cos(pi/n)) ~ h^2, so the gap error is O(h^2).
    assert np.all(rates["interval"] > 1.8), rates
    # P2 arcs interpolating the circle: the interpolation error is O(h^3) or better
    # (observed ~h^4 for uniform nodes); assert at least h^2.8 and far below P1.
    assert np.all(rates["interval3"] > 2.8), rates
    assert err["interval3"][-1] < 1e-2 * err["interval"][-1]


def sphere_mesh(nx: int, cell: str, R: float):
    """Cube-sphere of radius R with outward-oriented facets (nodes duplicated per face)."""
    quad = cell.startswith("quadrilateral")
    m = 2 if cell in ("triangle6", "quadrilateral9") else 1
    N = m * nx + 1
    u = np.linspace(-1.0, 1.0, N)
    U, V = np.meshgrid(u, u, indexing="xy")
    U, V = U.ravel(), V.ravel()
    nodes, facets = [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            P = np.empty((len(U), 3))
            P[:, axis] = sign
            P[:, (axis + 1) % 3] = U
            P[:, (axis + 2) % 3] = V
            base = sum(len(x) for x in nodes)
            nodes.append(R * P / np.linalg.norm(P, axis=1)[:, None])
            _, local = surface_mesh(nx, cell, np.random.default_rng(0))
            facets.append(local + base)
    nodes, facets = np.concatenate(nodes), np.concatenate(facets)
    # Orient outwards: flip facets whose (v1 - v0) x (v2 - v0) points inwards
    v = nodes[facets[:, :3]]
    inward = np.einsum("fi,fi->f", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), v[:, 0]) < 0
    if quad:
        perm = [0, 2, 1, 3, 5, 4, 7, 6, 8][: facets.shape[1]]
    else:
        perm = [0, 2, 1, 3, 5, 4][: facets.shape[1]]
    facets[inward] = facets[inward][:, perm]
    return nodes, facets


@pytest.mark.parametrize(
    "linear, quadratic", [("triangle", "triangle6"), ("quadrilateral", "quadrilateral9")]
)
def test_sphere_gap_convergence(linear, quadratic):
    R = 1.3
    rng = np.random.default_rng(4)
    d = rng.standard_normal((2000, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    r = R * rng.uniform(0.7, 1.4, 2000)
    points = r[:, None] * d
    exact = r - R
    ns = [4, 8, 16, 32]
    err = {}
    curv_err = []
    for cell in (linear, quadratic):
        err[cell] = []
        for nx in ns:
            nodes, facets = sphere_mesh(nx, cell, R)
            res = closest_point_projection(points, nodes, facets, cell)
            err[cell].append(np.abs(res.gap - exact).max())
            if cell == quadratic:
                # Mean curvature -1/2 g^ab b_ab ~ 1/R (outward normal); second
                # derivatives of a P2/Q2 interpolant converge like O(h).
                t = res.tangents
                G = np.einsum("pai,pbi->pab", t, t)
                H = -0.5 * np.einsum("pab,pab->p", np.linalg.inv(G), res.curvature)
                curv_err.append(np.abs(H * R - 1).mean())
    assert np.all(np.log2(np.array(curv_err[:-1]) / curv_err[1:]) > 0.8), curv_err
    assert curv_err[-1] < 0.06
    rl = np.log2(np.array(err[linear][:-1]) / np.array(err[linear][1:]))
    rq = np.log2(np.array(err[quadratic][:-1]) / np.array(err[quadratic][1:]))
    # Flat facets: O(h^2) (chord sag). Quadratic facets: O(h^3) interpolation error;
    # asserted with margin on the last two refinements (the first is pre-asymptotic).
    assert np.all(rl[1:] > 1.8), (rl, err)
    assert np.all(rq[1:] > 2.5), (rq, err)
    assert err[quadratic][-1] < 0.1 * err[linear][-1]


# --------------------------------------------------------------------------------------
# Derivatives by central finite differences
# --------------------------------------------------------------------------------------
def _fd_check(points, nodes, facets, cell, mask_fn):
    res = closest_point_projection(points, nodes, facets, cell)
    sel = mask_fn(res)
    assert sel.sum() >= 20
    x, res = points[sel], closest_point_projection(points[sel], nodes, facets, cell)
    gdim = x.shape[1]
    h = 1e-6
    for j in range(gdim):
        e = np.zeros(gdim)
        e[j] = h
        rp = closest_point_projection(x + e, nodes, facets, cell)
        rm = closest_point_projection(x - e, nodes, facets, cell)
        # Same facet and location type on both sides, else the FD is meaningless
        ok = (rp.facet == res.facet) & (rm.facet == res.facet)
        ok &= (rp.inside == res.inside) & (rm.inside == res.inside)
        assert ok.mean() > 0.95
        # Central differences: truncation O(h^2) ~ 1e-12 and round-off ~ eps/h ~ 1e-10
        # (times the conditioning of the projection), so 1e-6 is a safe tolerance.
        tol = dict(rtol=1e-6, atol=1e-6)
        fd = lambda f: (getattr(rp, f)[ok] - getattr(rm, f)[ok]) / (2 * h)  # noqa: E731
        np.testing.assert_allclose(fd("xi"), res.dxi_dx[ok][:, :, j], **tol)
        np.testing.assert_allclose(fd("x_bar"), res.dxbar_dx[ok][:, :, j], **tol)
        np.testing.assert_allclose(fd("normal"), res.dn_dx[ok][:, :, j], **tol)
        gap_fd = fd("gap")
        inside = res.inside[ok]
        np.testing.assert_allclose(gap_fd[inside], res.normal[ok][inside, j], **tol)
    return res


@pytest.mark.parametrize("cell", sorted(CELL_TYPES))
def test_derivatives_interior_fd(cell):
    rng = np.random.default_rng(9)
    if cell.startswith("interval"):
        nodes, facets = curve_mesh(12, cell, rng)
    else:
        nodes, facets = surface_mesh(4, cell, rng)
    points = point_cloud(nodes, facets, 600, rng)
    # Interior projections, not too far away (avoid the focal set of the surface)
    res = _fd_check(points, nodes, facets, cell, lambda r: r.inside & (r.distance < 0.05))
    assert np.abs(res.dxi_dx).max() > 0.1
    if cell not in ("interval", "triangle"):
        assert np.abs(res.dn_dx).max() > 1e-2


@pytest.mark.parametrize("cell", ["triangle", "triangle6", "quadrilateral", "quadrilateral9"])
def test_derivatives_clamped_to_edge_fd(cell):
    # Points beyond the boundary x = 0 of the patch project onto boundary edges
    rng = np.random.default_rng(10)
    nodes, facets = surface_mesh(4, cell, rng)
    n = 400
    points = np.c_[
        rng.uniform(-0.3, -0.05, n), rng.uniform(0.05, 0.95, n), rng.uniform(-0.2, 0.2, n)
    ]
    tdim = 2

    def on_edge(r):
        on_bnd = np.any((r.xi <= 1e-12) | (r.xi >= 1 - 1e-12), axis=1)
        if cell.startswith("triangle"):
            on_bnd |= np.abs(r.xi.sum(axis=1) - 1) <= 1e-12
        vertex = np.all(np.abs(r.dxi_dx) == 0.0, axis=(1, 2))
        return ~r.inside & on_bnd & ~vertex

    res = _fd_check(points, nodes, facets, cell, on_edge)
    # Restricted problem: d xi / dx has rank one (only the edge direction is free)
    assert np.all(np.linalg.matrix_rank(res.dxi_dx, tol=1e-10) == 1)
    assert res.xi.shape[1] == tdim


def test_vertex_projection_has_zero_derivative():
    nodes = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.5]])
    facets = np.array([[0, 1], [1, 2]])
    points = np.array([[-1.0, 0.3], [3.0, 1.0], [1.1, -0.5]])
    for fn in (closest_point_projection, closest_point_projection_ref):
        r = fn(points, nodes, facets, "interval")
        assert not r.inside.any()
        np.testing.assert_allclose(r.x_bar, nodes[[0, 2, 1]], atol=1e-15)
        np.testing.assert_array_equal(r.dxi_dx, 0.0)
        np.testing.assert_array_equal(r.dxbar_dx, 0.0)
        np.testing.assert_allclose(r.distance, np.linalg.norm(points - nodes[[0, 2, 1]], axis=1))


# --------------------------------------------------------------------------------------
# Input validation
# --------------------------------------------------------------------------------------
def _good():
    nodes = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], dtype=float)
    return np.zeros((2, 3)), nodes, np.array([[0, 1, 3], [0, 3, 2]], dtype=np.int32)


@pytest.mark.parametrize(
    "case",
    [
        "cell",
        "points_shape",
        "points_1d",
        "nodes_shape",
        "k",
        "index_high",
        "index_negative",
        "float_facets",
        "no_facets",
        "nan_points",
        "gdim_mismatch",
    ],
)
@pytest.mark.parametrize("fn", [closest_point_projection, closest_point_projection_ref])
def test_bad_input_raises(fn, case):
    points, nodes, facets = _good()
    cell = "triangle"
    if case == "cell":
        cell = "hexahedron"
    elif case == "points_shape":
        points = np.zeros((2, 2))
    elif case == "points_1d":
        points = np.zeros(3)
    elif case == "nodes_shape":
        nodes = nodes[:, :2]
    elif case == "k":
        cell = "triangle6"
    elif case == "index_high":
        facets[1, 2] = 4
    elif case == "index_negative":
        facets[0, 0] = -1
    elif case == "float_facets":
        facets = facets.astype(float)
    elif case == "no_facets":
        facets = np.zeros((0, 3), dtype=np.int32)
    elif case == "nan_points":
        points[0, 0] = np.nan
    elif case == "gdim_mismatch":
        cell = "interval"
    with pytest.raises(ValueError):
        fn(points, nodes, facets, cell)


def test_cpp_validates_directly():
    points, nodes, facets = _good()
    facets[0, 1] = 7
    with pytest.raises(ValueError, match="out of range"):
        _cpp.closest_point_projection(points, nodes, facets, "triangle")
    with pytest.raises(ValueError, match="cell_type"):
        _cpp.closest_point_projection(points, nodes, facets, "tetrahedron")
    with pytest.raises(ValueError):
        _cpp.closest_point_projection(points, nodes, facets[:, :2].copy(), "triangle")
    assert _cpp.version() == 1


def test_extension_is_built_from_this_package_version():
    """tribofx._cpp carries the version it was built as: a stale build is caught here."""
    import tribofx
    from tribofx import _cpp

    assert _cpp.__version__ == tribofx.__version__

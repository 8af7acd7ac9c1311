"""NumPy twin of the C++ closest-point projection kernel.

:func:`closest_point_projection_ref` has the signature and result of
:func:`tribofx.projection.closest_point_projection` and runs the identical
per-facet algorithm (same operations in the same order as
``cpp_kernels/src/projection.hpp``), but searches all facets by brute force,
vectorised over (point, facet) pairs. It is meant for testing and is slow for
large meshes.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from tribofx.facet_elements_ref import ELEMENTS, FacetElement, dot
from tribofx.projection import ProjectionResult, _validate

__all__ = ["closest_point_projection_ref"]

_MAX_IT = 50
_NEWTON_TOL = 1e-14
_MAX_BOUNDARY_HITS = 3
_NEWTON_STALL_TOL = 1e-8
_TIE_RTOL = 1e-12
_TIE_ATOL = 1e-300
_INTERIOR = -1
_VERTEX = -2
#: Number of (point, facet) pairs processed at once.
_PAIRS_PER_CHUNK = 200_000


def _evaluate(
    el: FacetElement, X: np.ndarray, xi: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Geometry x (m, g), tangents t (m, tdim, g), second derivatives d (m, tdim, tdim, g)."""
    N, dN, d2N = el.tabulate(xi)
    m, nn, gdim = X.shape
    x = np.zeros((m, gdim))
    t = np.zeros((m, el.tdim, gdim))
    d = np.zeros((m, el.tdim, el.tdim, gdim))
    for i in range(nn):
        Xi = X[:, i, :]
        x += N[:, i, None] * Xi
        t += dN[:, :, i, None] * Xi[:, None, :]
        d += d2N[:, :, :, i, None] * Xi[:, None, None, :]
    return x, t, d


def _along(e: tuple, t: np.ndarray) -> np.ndarray:
    """Tangent along reference direction e: sum_a e_a t_a."""
    te = e[0] * t[:, 0, :]
    for a in range(1, len(e)):
        te = te + e[a] * t[:, a, :]
    return te


def _along2(e: tuple, d: np.ndarray) -> np.ndarray:
    """Second derivative along e: sum_ab e_a e_b d_ab."""
    de = (e[0] * e[0]) * d[:, 0, 0, :]
    for a in range(len(e)):
        for b in range(len(e)):
            if a + b > 0:
                de = de + (e[a] * e[b]) * d[:, a, b, :]
    return de


def _point_on_line(a: tuple, e: tuple, s: np.ndarray) -> np.ndarray:
    return np.stack([a[k] + s * e[k] for k in range(len(a))], axis=-1)


def _line_minimiser(
    el: FacetElement, x: np.ndarray, X: np.ndarray, a: tuple, e: tuple
) -> np.ndarray:
    """Minimise 1/2 |x - x(a + s e)|^2 over s in [0, 1] for every pair."""
    m = len(x)
    if el.affine:
        gx, t, _ = _evaluate(el, X, np.broadcast_to(np.asarray(a), (m, el.tdim)))
        te = _along(e, t)
        return np.clip(dot(te, x - gx) / dot(te, te), 0.0, 1.0)
    s = np.full(m, 0.5)
    prev = np.full(m, np.inf)
    act = np.arange(m)
    for _ in range(_MAX_IT):
        if len(act) == 0:
            break
        sa = s[act]
        ga, t, d = _evaluate(el, X[act], _point_on_line(a, e, sa))
        g = x[act] - ga
        te = _along(e, t)
        de = _along2(e, d)
        r = -dot(te, g)
        tt = dot(te, te)
        h = tt - dot(g, de)
        h = np.where(h > 0.0, h, tt)
        ok = h > 0.0
        act, sa, r, h = act[ok], sa[ok], r[ok], h[ok]
        sn = np.clip(sa - r / h, 0.0, 1.0)
        step = np.abs(sn - sa)
        s[act] = sn
        done = (step <= _NEWTON_TOL) | ((step <= _NEWTON_STALL_TOL) & (step >= prev[act]))
        prev[act] = step
        act = act[~done]

    def dist2(sv: np.ndarray) -> np.ndarray:
        g = x - _evaluate(el, X, _point_on_line(a, e, sv))[0]
        return dot(g, g)

    ds, d0, d1 = dist2(s), dist2(np.zeros(m)), dist2(np.ones(m))
    return np.where((d0 < ds) & (d0 <= d1), 0.0, np.where(d1 < ds, 1.0, s))


def _strictly_inside(el: FacetElement, p: np.ndarray) -> np.ndarray:
    p0, p1 = p[:, 0], p[:, 1]
    if el.simplex:
        return (p0 > 0.0) & (p1 > 0.0) & (p0 + p1 < 1.0)
    return (p0 > 0.0) & (p0 < 1.0) & (p1 > 0.0) & (p1 < 1.0)


def _project_reference(el: FacetElement, p: np.ndarray) -> np.ndarray:
    """Euclidean projection onto the reference facet (tdim = 2)."""
    if not el.simplex:
        return np.clip(p, 0.0, 1.0)
    p0, p1 = p[:, 0], p[:, 1]
    out = p.copy()
    rest = ~((p0 >= 0.0) & (p1 >= 0.0) & (p0 + p1 <= 1.0))
    q0, q1 = p0[rest], p1[rest]
    best = None
    for a, e in zip(el.edge_start, el.edge_dir):
        t = ((q0 - a[0]) * e[0] + (q1 - a[1]) * e[1]) / (e[0] * e[0] + e[1] * e[1])
        t = np.clip(t, 0.0, 1.0)
        c0, c1 = a[0] + t * e[0], a[1] + t * e[1]
        d2 = (q0 - c0) * (q0 - c0) + (q1 - c1) * (q1 - c1)
        if best is None:
            best, b0, b1 = d2, c0, c1
        else:
            upd = d2 < best
            best = np.where(upd, d2, best)
            b0, b1 = np.where(upd, c0, b0), np.where(upd, c1, b1)
    out[rest, 0], out[rest, 1] = b0, b1
    return out


def _interior_newton(
    el: FacetElement, x: np.ndarray, X: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Projected Newton for the interior problem; returns xi and a flag for a converged minimum."""
    m = len(x)
    xi = np.empty((m, 2))
    xi[:] = el.centroid
    converged = np.zeros(m, dtype=bool)
    hits = np.zeros(m, dtype=np.int64)
    spd = np.zeros(m, dtype=bool)
    prev = np.full(m, np.inf)
    act = np.arange(m)
    for _ in range(_MAX_IT):
        if len(act) == 0:
            break
        xa = xi[act]
        gx, t, d = _evaluate(el, X[act], xa)
        g = x[act] - gx
        t0, t1 = t[:, 0], t[:, 1]
        r0, r1 = -dot(t0, g), -dot(t1, g)
        G00, G01, G11 = dot(t0, t0), dot(t0, t1), dot(t1, t1)
        H00 = G00 - dot(g, d[:, 0, 0])
        H01 = G01 - dot(g, d[:, 0, 1])
        H11 = G11 - dot(g, d[:, 1, 1])
        det = H00 * H11 - H01 * H01
        gn = ~((H00 > 0.0) & (det > 0.0))
        spd[act] = ~gn
        H00, H01, H11 = np.where(gn, G00, H00), np.where(gn, G01, H01), np.where(gn, G11, H11)
        det = np.where(gn, H00 * H11 - H01 * H01, det)
        ok = det > 0.0
        act, xa = act[ok], xa[ok]
        H00, H01, H11, det, r0, r1 = H00[ok], H01[ok], H11[ok], det[ok], r0[ok], r1[ok]
        d0 = -(H11 * r0 - H01 * r1) / det
        d1 = -(H00 * r1 - H01 * r0) / det
        xn = _project_reference(el, np.stack([xa[:, 0] + d0, xa[:, 1] + d1], axis=-1))
        step = np.maximum(np.abs(xn[:, 0] - xa[:, 0]), np.abs(xn[:, 1] - xa[:, 1]))
        xi[act] = xn
        done = (step <= _NEWTON_TOL) | ((step <= _NEWTON_STALL_TOL) & (step >= prev[act]))
        prev[act] = step
        converged[act[done]] = True
        hits[act] = np.where(_strictly_inside(el, xn), 0, hits[act] + 1)
        act = act[~done & (hits[act] != _MAX_BOUNDARY_HITS)]
    return xi, converged & spd


def _project_pairs(
    el: FacetElement, x: np.ndarray, X: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Closest point of facet X[p] to x[p] for every pair p: xi, state, squared distance."""
    m = len(x)
    state = np.full(m, _INTERIOR, dtype=np.int64)
    if el.tdim == 1:
        s = _line_minimiser(el, x, X, (0.0,), (1.0,))
        xi = s[:, None].copy()
        state[~((s > 0.0) & (s < 1.0))] = _VERTEX
    else:
        if el.affine:
            gx, t, _ = _evaluate(el, X, np.zeros((m, 2)))
            r = x - gx
            t0, t1 = t[:, 0], t[:, 1]
            b0, b1 = dot(t0, r), dot(t1, r)
            G00, G01, G11 = dot(t0, t0), dot(t0, t1), dot(t1, t1)
            det = G00 * G11 - G01 * G01
            xi = np.stack([(G11 * b0 - G01 * b1) / det, (G00 * b1 - G01 * b0) / det], axis=-1)
            found = _strictly_inside(el, xi)
        else:
            xi, converged = _interior_newton(el, x, X)
            found = converged & _strictly_inside(el, xi)
        search = ~found
        best_all = np.zeros(m)
        if not el.affine:
            # A curved facet may have several local minima: if a vertex is closer
            # than the interior minimum, search the edges as well
            g = x - _evaluate(el, X, xi)[0]
            best_all = np.where(found, dot(g, g), 0.0)
            for v in el.vertices:
                gv = x - _evaluate(el, X, np.broadcast_to(np.asarray(v), (m, 2)))[0]
                search |= found & (dot(gv, gv) < best_all)
        rest = np.flatnonzero(search)
        xr, Xr, fr = x[rest], X[rest], found[rest]
        best, bxi, bst = best_all[rest], xi[rest], state[rest]
        for k, (a, e) in enumerate(zip(el.edge_start, el.edge_dir)):
            s = _line_minimiser(el, xr, Xr, a, e)
            xe = _point_on_line(a, e, s)
            g = xr - _evaluate(el, Xr, xe)[0]
            d2 = dot(g, g)
            st = np.where((s > 0.0) & (s < 1.0), k, _VERTEX)
            upd = ((k == 0) & ~fr) | (d2 < best)
            best = np.where(upd, d2, best)
            bxi = np.where(upd[:, None], xe, bxi)
            bst = np.where(upd, st, bst)
        if len(rest):
            xi[rest] = bxi
            state[rest] = bst
    g = x - _evaluate(el, X, xi)[0]
    return xi, state, dot(g, g)


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return np.stack(
        [
            u[:, 1] * v[:, 2] - u[:, 2] * v[:, 1],
            u[:, 2] * v[:, 0] - u[:, 0] * v[:, 2],
            u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0],
        ],
        axis=-1,
    )


def _results(
    el: FacetElement, x: np.ndarray, X: np.ndarray, xi: np.ndarray, state: np.ndarray
) -> dict[str, np.ndarray]:
    """Output fields for points x projected onto facets X at (xi, state)."""
    n, gdim = x.shape
    tdim = el.tdim
    gx, t, d = _evaluate(el, X, xi)
    g = x - gx
    if gdim == 2:
        m = np.stack([t[:, 0, 1], -t[:, 0, 0]], axis=-1)
        dm = np.stack([d[:, 0, 0, 1], -d[:, 0, 0, 0]], axis=-1)[:, None, :]
    else:
        dm = np.stack(
            [_cross(d[:, 0, a], t[:, 1]) + _cross(t[:, 0], d[:, 1, a]) for a in range(tdim)],
            axis=1,
        )
        m = _cross(t[:, 0], t[:, 1])
    mnorm = np.sqrt(dot(m, m))[:, None]
    nrm = m / mnorm
    dn = np.stack(
        [(dm[:, a] - nrm * dot(nrm, dm[:, a])[:, None]) / mnorm for a in range(tdim)], axis=1
    )

    dxi = np.zeros((n, tdim, gdim))
    ii = state == _INTERIOR
    ti, di, gi = t[ii], d[ii], g[ii]
    if tdim == 1:
        A = dot(ti[:, 0], ti[:, 0]) - dot(gi, di[:, 0, 0])
        dxi[ii, 0] = ti[:, 0] / A[:, None]
    else:
        A00 = dot(ti[:, 0], ti[:, 0]) - dot(gi, di[:, 0, 0])
        A01 = dot(ti[:, 0], ti[:, 1]) - dot(gi, di[:, 0, 1])
        A11 = dot(ti[:, 1], ti[:, 1]) - dot(gi, di[:, 1, 1])
        det = A00 * A11 - A01 * A01
        i00, i01, i11 = (A11 / det)[:, None], (-A01 / det)[:, None], (A00 / det)[:, None]
        dxi[ii, 0] = i00 * ti[:, 0] + i01 * ti[:, 1]
        dxi[ii, 1] = i01 * ti[:, 0] + i11 * ti[:, 1]
        for k, e in enumerate(el.edge_dir):
            ik = state == k
            te = _along(e, t[ik])
            de = _along2(e, d[ik])
            A = dot(te, te) - dot(g[ik], de)
            ds = te / A[:, None]
            dxi[ik, 0] = e[0] * ds
            dxi[ik, 1] = e[1] * ds

    dxbar = t[:, 0, :, None] * dxi[:, 0, None, :]
    dndx = dn[:, 0, :, None] * dxi[:, 0, None, :]
    for a in range(1, tdim):
        dxbar = dxbar + t[:, a, :, None] * dxi[:, a, None, :]
        dndx = dndx + dn[:, a, :, None] * dxi[:, a, None, :]
    curv = np.empty((n, tdim, tdim))
    for a in range(tdim):
        for b in range(tdim):
            curv[:, a, b] = dot(nrm, d[:, a, b])
    return dict(
        xi=xi,
        x_bar=gx,
        gap=dot(g, nrm),
        normal=nrm,
        tangents=t,
        dxi_dx=dxi,
        dxbar_dx=dxbar,
        dn_dx=dndx,
        curvature=curv,
        inside=state == _INTERIOR,
        distance=np.sqrt(dot(g, g)),
    )


def closest_point_projection_ref(
    points: npt.ArrayLike, nodes: npt.ArrayLike, facets: npt.ArrayLike, cell_type: str
) -> ProjectionResult:
    """Brute-force NumPy version of :func:`tribofx.projection.closest_point_projection`.

    Same arguments, result, packing and algorithm per (point, facet) pair as
    the C++ kernel, but every facet is tried for every point. Among facets
    whose distance ties with the minimum ``dmin`` (``dmin >= d (1 - 1e-12) -
    1e-300``) the lowest index wins, which is the facet the tree search of the
    C++ kernel selects as well.

    Raises:
        ValueError: on inconsistent input, as the C++ entry point.

    """
    points, nodes, facets = _validate(points, nodes, facets, cell_type)
    el = ELEMENTS[cell_type]
    n, gdim = points.shape
    nf = len(facets)
    Xf = nodes[facets]
    facet = np.full(n, -1, dtype=np.int32)
    xi = np.full((n, el.tdim), np.nan)
    state = np.full(n, _VERTEX, dtype=np.int64)
    chunk = max(1, _PAIRS_PER_CHUNK // nf)
    with np.errstate(all="ignore"):
        for i0 in range(0, n, chunk):
            P = points[i0 : i0 + chunk]
            c = len(P)
            pxi, pst, pd2 = _project_pairs(el, np.repeat(P, nf, axis=0), np.tile(Xf, (c, 1, 1)))
            d = np.sqrt(pd2).reshape(c, nf)
            valid = ~np.isnan(d).all(axis=1)
            dmin = np.min(np.where(np.isnan(d), np.inf, d), axis=1)
            tie = dmin[:, None] >= d * (1.0 - _TIE_RTOL) - _TIE_ATOL
            best = np.argmax(tie, axis=1)
            sel = np.arange(c) * nf + best
            rows = np.arange(i0, i0 + c)[valid]
            facet[rows] = best[valid]
            xi[rows] = pxi[sel][valid]
            state[rows] = pst[sel][valid]
        ok = facet >= 0
        res = _results(el, points[ok], Xf[facet[ok]], xi[ok], state[ok])
    out: dict[str, np.ndarray] = {"facet": facet}
    for key, v in res.items():
        full = np.full((n, *v.shape[1:]), False if v.dtype == bool else np.nan, dtype=v.dtype)
        full[ok] = v
        out[key] = full
    return ProjectionResult(**out)

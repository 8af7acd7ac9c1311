"""Facet elements of the NumPy twin of the projection kernel: tabulation and reference geometry.

For each facet type of :func:`tribofx.projection.closest_point_projection`
(``interval``, ``interval3``, ``triangle``, ``triangle6``, ``quadrilateral``,
``quadrilateral9``) a :class:`FacetElement` holds the basis tabulation — values
(m, n), first (m, tdim, n) and second (m, tdim, tdim, n) derivatives at m
reference points — and the reference domain's centroid, vertices and edges,
in the node order of ``cpp_kernels/src/projection.hpp``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

__all__ = ["ELEMENTS", "QUAD_AB", "FacetElement", "dot", "line1", "line2"]


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Dot product over the last axis, summed left to right."""
    s = a[..., 0] * b[..., 0]
    for i in range(1, a.shape[-1]):
        s = s + a[..., i] * b[..., i]
    return s


def line1(t: np.ndarray) -> tuple[list, list, list]:
    """1D P1 basis on [0, 1] (nodes 0, 1): values, first and second derivatives."""
    one = np.ones_like(t)
    return [1.0 - t, t], [-one, one], [0.0 * one, 0.0 * one]


def line2(t: np.ndarray) -> tuple[list, list, list]:
    """1D P2 basis on [0, 1] (nodes 0, 1, 1/2): values, first and second derivatives."""
    one = np.ones_like(t)
    f = [(1.0 - t) * (1.0 - 2.0 * t), t * (2.0 * t - 1.0), 4.0 * t * (1.0 - t)]
    df = [4.0 * t - 3.0, 4.0 * t - 1.0, 4.0 - 8.0 * t]
    return f, df, [4.0 * one, 4.0 * one, -8.0 * one]


QUAD_AB = ((0, 0), (1, 0), (0, 1), (1, 1), (2, 0), (0, 2), (1, 2), (2, 1), (2, 2))


def _tab_interval(line: Callable) -> Callable:
    def tabulate(xi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        f, df, d2f = line(xi[:, 0])
        N = np.stack(f, axis=-1)
        return N, np.stack(df, axis=-1)[:, None, :], np.stack(d2f, axis=-1)[:, None, None, :]

    return tabulate


def _tab_triangle3(xi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    s, t = xi[:, 0], xi[:, 1]
    m = len(s)
    N = np.stack([1.0 - s - t, s, t], axis=-1)
    dN = np.empty((m, 2, 3))
    dN[:, 0] = (-1.0, 1.0, 0.0)
    dN[:, 1] = (-1.0, 0.0, 1.0)
    return N, dN, np.zeros((m, 2, 2, 3))


def _tab_triangle6(xi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    s, t = xi[:, 0], xi[:, 1]
    m = len(s)
    l0 = 1.0 - s - t
    N = np.stack(
        [
            l0 * (2.0 * l0 - 1.0),
            s * (2.0 * s - 1.0),
            t * (2.0 * t - 1.0),
            4.0 * s * t,
            4.0 * t * l0,
            4.0 * s * l0,
        ],
        axis=-1,
    )
    zero = 0.0 * s
    dN = np.empty((m, 2, 6))
    dN[:, 0] = np.stack(
        [1.0 - 4.0 * l0, 4.0 * s - 1.0, zero, 4.0 * t, -4.0 * t, 4.0 * (l0 - s)], axis=-1
    )
    dN[:, 1] = np.stack(
        [1.0 - 4.0 * l0, zero, 4.0 * t - 1.0, 4.0 * s, 4.0 * (l0 - t), -4.0 * s], axis=-1
    )
    d2N = np.empty((m, 2, 2, 6))
    d2N[:, 0, 0] = (4.0, 4.0, 0.0, 0.0, 0.0, -8.0)
    d2N[:, 0, 1] = (4.0, 0.0, 0.0, 4.0, -4.0, -4.0)
    d2N[:, 1, 0] = d2N[:, 0, 1]
    d2N[:, 1, 1] = (4.0, 0.0, 4.0, 0.0, -8.0, 0.0)
    return N, dN, d2N


def _tab_quadrilateral(line: Callable, nn: int) -> Callable:
    def tabulate(xi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        f, df, d2f = line(xi[:, 0])
        g, dg, d2g = line(xi[:, 1])
        m = len(xi)
        N = np.empty((m, nn))
        dN = np.empty((m, 2, nn))
        d2N = np.empty((m, 2, 2, nn))
        for i, (a, b) in enumerate(QUAD_AB[:nn]):
            N[:, i] = f[a] * g[b]
            dN[:, 0, i] = df[a] * g[b]
            dN[:, 1, i] = f[a] * dg[b]
            d2N[:, 0, 0, i] = d2f[a] * g[b]
            d2N[:, 0, 1, i] = df[a] * dg[b]
            d2N[:, 1, 0, i] = df[a] * dg[b]
            d2N[:, 1, 1, i] = f[a] * d2g[b]
        return N, dN, d2N

    return tabulate


@dataclass(frozen=True)
class FacetElement:
    """Facet type: dimensions, flags, tabulation and reference-domain edges."""

    tdim: int
    num_nodes: int
    affine: bool
    simplex: bool
    tabulate: Callable
    centroid: tuple = ()
    vertices: tuple = ()
    edge_start: tuple = ()
    edge_dir: tuple = ()


_TRI = dict(
    centroid=(1.0 / 3.0, 1.0 / 3.0),
    vertices=((0.0, 0.0), (1.0, 0.0), (0.0, 1.0)),
    edge_start=((1.0, 0.0), (0.0, 0.0), (0.0, 0.0)),
    edge_dir=((-1.0, 1.0), (0.0, 1.0), (1.0, 0.0)),
)
_QUAD = dict(
    centroid=(0.5, 0.5),
    vertices=((0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)),
    edge_start=((0.0, 0.0), (0.0, 0.0), (1.0, 0.0), (0.0, 1.0)),
    edge_dir=((1.0, 0.0), (0.0, 1.0), (0.0, 1.0), (1.0, 0.0)),
)
ELEMENTS = {
    "interval": FacetElement(1, 2, True, True, _tab_interval(line1)),
    "interval3": FacetElement(1, 3, False, True, _tab_interval(line2)),
    "triangle": FacetElement(2, 3, True, True, _tab_triangle3, **_TRI),
    "triangle6": FacetElement(2, 6, False, True, _tab_triangle6, **_TRI),
    "quadrilateral": FacetElement(2, 4, False, False, _tab_quadrilateral(line1, 4), **_QUAD),
    "quadrilateral9": FacetElement(2, 9, False, False, _tab_quadrilateral(line2, 9), **_QUAD),
}

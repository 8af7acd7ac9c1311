"""Geometry of oriented P1 contact facets (segments in 2D, triangles in 3D), in NumPy.

The conventions of the C++ two-body kernels (:mod:`tribofx.two_body`): a facet
is given by its d vertices (n, d, d); its outward unit normal is (τ_y, −τ_x)/l
in 2D and t₁ × t₂/|t₁ × t₂| in 3D; a point of it is Σ N_i(ξ) x_i with the P1
shape functions N = (1 − Σ ξ^a, ξ^1, ...).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from typing import TypeAlias

    import numpy.typing as npt

    #: a pairing of slave nodes with master facets: the master facets (m, d) (node
    #: indices) and the facet of every slave node (n,)
    Pairing: TypeAlias = tuple[npt.NDArray[np.int32], npt.NDArray[np.int32]]
    #: a pairing, or master facets alone (None in place of the facet per node)
    Segments: TypeAlias = tuple[npt.NDArray[np.int32], npt.NDArray[np.int32] | None]

__all__ = ["eulerian_slip_constants", "keep_reference_facets", "normals", "plane_coordinates",
           "same_pairing", "shape_values"]


def shape_values(xi: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """P1 facet shape functions at ξ: (n,) in 2D → (n, 2); (n, 2) in 3D → (n, 3)."""
    xi = np.asarray(xi)
    xi = xi.reshape(len(xi), 1 if xi.ndim == 1 else xi.shape[1])
    return np.c_[1 - xi.sum(axis=1), xi]


def plane_coordinates(
        x: npt.NDArray[np.float64], facet: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Coordinates of points x (n, d) on their facets (n, d, d vertices), unclamped.

    Returns ξ (n, d − 1) of the projection onto the facet's line/plane, the
    distance to that line/plane (n,) and a facet size (n,): the length in 2D,
    the square root of twice the area in 3D.
    """
    a = facet[:, 0]
    t = facet[:, 1:] - a[:, None, :]                       # (n, d-1, d) edge vectors
    m = np.einsum("nad,nbd->nab", t, t)
    rhs = np.einsum("nad,nd->na", t, x - a)
    xi = np.linalg.solve(m, rhs[..., None])[..., 0]
    foot = a + np.einsum("na,nad->nd", xi, t)
    if t.shape[1] == 1:
        size = np.sqrt(m[:, 0, 0])                        # the segment's length
    else:
        size = np.abs(np.linalg.det(m)) ** 0.25           # √(2 area): det m = (2 area)²
    return xi, np.linalg.norm(x - foot, axis=1), size


def normals(facet: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Return the unit outward normals (n, d) of oriented facets (n, d, d), as the kernels."""
    if facet.shape[1] == 2:
        t = facet[:, 1] - facet[:, 0]
        n = np.c_[t[:, 1], -t[:, 0]]
    else:
        n = np.cross(facet[:, 1] - facet[:, 0], facet[:, 2] - facet[:, 0])
    return n / np.linalg.norm(n, axis=1)[:, None]


def keep_reference_facets(xs: npt.NDArray[np.float64], xm: npt.NDArray[np.float64],
                          seg: npt.NDArray[np.int32], proj: dict[str, npt.NDArray[Any]],
                          reference: Pairing | None, sticky: float) -> dict[str, npt.NDArray[Any]]:
    """Pairing with hysteresis: a node keeps its reference facet while it still projects there.

    A node keeps ``reference[k]`` while its plane coordinates on that facet are
    within ``sticky`` of it and its distance is at most the nearest distance plus
    ``sticky`` of the facet's size: at a kink of the deformed master the nearest
    facet jumps between the neighbours of a vertex, and Newton would cycle.

    Args:
        xs: (n, d) slave positions.
        xm: master node positions.
        seg: (m, d) master facets (node indices into ``xm``).
        proj: the nearest projection (``facet`` (n,), ``xi``, ``distance`` (n,)),
            updated in place for the kept nodes (their clamped coordinates).
        reference: (segments, facet per node) or None; used only if its segments
            are ``seg`` and it has one facet per node.
        sticky: relative hysteresis.
    """
    if reference is None or not same_pairing(reference, (seg, None)) \
            or len(reference[1]) != len(xs):
        return proj
    prev, d = reference[1], xs.shape[1]
    xi, dist, size = plane_coordinates(xs, xm[seg[prev]])
    bary = np.c_[1 - xi.sum(axis=1), xi]
    keep = np.all(bary > -sticky, axis=1) & (dist <= proj["distance"] + sticky * size)
    inside = np.clip(xi, 0.0, None)
    inside /= np.maximum(inside.sum(axis=1), 1.0)[:, None]
    proj["facet"] = np.where(keep, prev, proj["facet"]).astype(np.int32)
    old = proj["xi"].reshape(len(xs), d - 1)
    proj["xi"] = np.where(keep[:, None], inside, old).reshape(proj["xi"].shape)
    return proj


def same_pairing(a: Segments | None, b: Segments | None) -> bool:
    """Whether two pairings (segments, facets) have the same segments (and facets, if given)."""
    if a is None or b is None or a[0].shape != b[0].shape or not np.array_equal(a[0], b[0]):
        return False
    return a[1] is None or b[1] is None or np.array_equal(a[1], b[1])


def eulerian_slip_constants(facet_ref: npt.NDArray[np.float64], V: npt.NDArray[np.float64],
                            dtau: float) -> npt.NDArray[np.float64]:
    """Per node the constants c of the Eulerian slip s = c^a t_a (eq. 27) on its facet.

    ``facet_ref`` (n, d, d): the reference vertices of each node's master facet; the
    master's material moves with ``V`` along its reference surface, so on a P1 facet
    F⁽²⁾V = a^b t_b with a = [T_a·T_b]⁻¹[T_a·V] (T_a the reference edge vectors), and
    the slip over the pseudo-time Δτ is s = −Δτ F⁽²⁾V: c = −Δτ a ((n,) in 2D, (n, 2)).
    """
    T = facet_ref[:, 1:] - facet_ref[:, :1]
    M = np.einsum("nad,nbd->nab", T, T)
    a = np.linalg.solve(M, np.einsum("nad,d->na", T, V)[..., None])[..., 0]
    c = -dtau * a
    return c[:, 0] if facet_ref.shape[1] == 2 else c

"""The public mesh builders of a 3D contact block and of an axisymmetric sphere section.

Geometric checks against closed forms, independent of the builders: volumes and
face areas (exact for the block's planar faces, the inscribed-polygon bound for
the sphere's curved face), the refined patch's element size, the tags.
"""

import math

import numpy as np
import pytest
import ufl
from dolfinx import fem, mesh
from mpi4py import MPI
from tribofx.meshes.block3d import NAMES, contact_block
from tribofx.meshes.hertz import AXISYMMETRIC_NAMES, sphere_section


def _integral(msh, expr, measure):
    return msh.comm.allreduce(fem.assemble_scalar(fem.form(expr * measure)), op=MPI.SUM)


def _cell_sizes_near(msh, radius):
    """Edge of the regular tetrahedron of each cell's volume, (6√2 V)^(1/3), for the owned
    cells with every vertex within ``radius`` of the origin (all ranks)."""
    tdim = msh.topology.dim
    cells = mesh.locate_entities(msh, tdim, lambda x: np.linalg.norm(x, axis=0) <= radius)
    cells = cells[cells < msh.topology.index_map(tdim).size_local]
    DG0 = fem.functionspace(msh, ("DG", 0))
    vol = fem.assemble_vector(fem.form(ufl.TestFunction(DG0) * ufl.dx)).array
    sizes = (6 * math.sqrt(2) * vol[cells]) ** (1 / 3)
    return np.concatenate(msh.comm.allgather(sizes))


@pytest.mark.mpi
@pytest.mark.parametrize("quarter", [True, False])
def test_contact_block(quarter):
    """Volume (2L)²H or L²H and top area exact to round-off (planar faces); every named
    face present with the area of its plane; cells within r_fine of the origin no
    larger than the gmsh size field allows there."""
    L, H, h_f, h_c, r_f = 4.0, 3.0, 0.25, 1.5, 0.8
    msh, ft = contact_block(L, H, h_f, h_c, r_f, quarter=quarter)
    side = L if quarter else 2 * L
    one = fem.Constant(msh, 1.0)
    assert _integral(msh, one, ufl.dx) == pytest.approx(side**2 * H, rel=1e-12)
    ds = ufl.Measure("ds", msh, subdomain_data=ft)
    assert _integral(msh, one, ds(NAMES["top"])) == pytest.approx(side**2, rel=1e-12)
    assert _integral(msh, one, ds(NAMES["bottom"])) == pytest.approx(side**2, rel=1e-12)
    lateral = 4 * side * H
    sym = _integral(msh, one, ds(NAMES["symmetry_x"])) + _integral(msh, one,
                                                                  ds(NAMES["symmetry_y"]))
    assert sym == pytest.approx(2 * L * H if quarter else 0.0, rel=1e-12, abs=1e-12)
    assert _integral(msh, one, ds(NAMES["sides"])) == pytest.approx(
        lateral / 2 if quarter else lateral, rel=1e-12)
    # gmsh's 3D Delaunay accepts edges of length in [h/√2, √2 h] of the size field h:
    # the typical (median) cell of the patch is within √2 h_fine, and no cell is near
    # the coarse size
    sizes = _cell_sizes_near(msh, r_f)
    print("patch cells", len(sizes), "median", np.median(sizes), "max", sizes.max())
    assert np.median(sizes) <= math.sqrt(2) * h_f
    assert sizes.max() < 0.5 * h_c


@pytest.mark.mpi
def test_sphere_section():
    """The meridian section of a hemisphere: its area → πR²/4 and its volume of
    revolution ∫ 2πr dA → (2/3)πR³, short of them by at most the inscribed polygon's
    deficit (each boundary chord of angle θ cuts (R²/2)(θ − sin θ) off the disc, θ ≤
    h_coarse/R·1.5 with gmsh's size tolerance: Σ ≤ (π/2)·R²θ²/12, and 2πR times that
    for the volume); the axis face has length R, the equator R."""
    R, h_f, h_c = 2.0, 0.05, 0.4
    msh, ft = sphere_section(R, h_f, h_c, 0.3)
    one = fem.Constant(msh, 1.0)
    r = ufl.SpatialCoordinate(msh)[0]
    theta = 1.5 * h_c / R
    deficit = (math.pi / 2) * R**2 * theta**2 / 12
    area = _integral(msh, one, ufl.dx)
    volume = _integral(msh, 2 * math.pi * r, ufl.dx)
    print("area", area, math.pi * R**2 / 4, "volume", volume, 2 / 3 * math.pi * R**3)
    assert math.pi * R**2 / 4 - deficit <= area <= math.pi * R**2 / 4 + 1e-12
    assert 2 / 3 * math.pi * R**3 - 2 * math.pi * R * deficit <= volume \
        <= 2 / 3 * math.pi * R**3 + 1e-12
    ds = ufl.Measure("ds", msh, subdomain_data=ft)
    assert _integral(msh, one, ds(AXISYMMETRIC_NAMES["axis"])) == pytest.approx(R, rel=1e-12)
    assert _integral(msh, one, ds(AXISYMMETRIC_NAMES["loaded"])) == pytest.approx(R, rel=1e-12)

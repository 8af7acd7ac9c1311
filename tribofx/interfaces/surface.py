"""A body's potential contact surface Γ_c: its facet submesh, P1 spaces, nodal maps, measure.

Every interface that lives on a boundary (a contact's multipliers, a wear
interface's shape multiplier, either side of a two-body contact) needs the same
things: the facet submesh of the boundary with its entity map, a scalar and a
vector P1 space on it, the map from submesh dofs to the bulk displacement dofs
of the same vertices, the reference positions of the submesh nodes, the
vertex-quadrature measure of the nodal scheme, and lumped nodal assembly.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import ufl
from dolfinx import fem, la

from ..meshes.user import num_cell_vertices
from ..submesh import facet_submesh

if TYPE_CHECKING:
    import numpy.typing as npt
    import ufl.core.expr

    from ..body import Body

__all__ = ["Surface", "node_to_dof"]


def node_to_dof(V: fem.FunctionSpace) -> npt.NDArray[np.int64]:
    """Map geometry-node index → block dof of a Lagrange space on a P1-geometry mesh."""
    msh = V.mesh
    xdm = msh.geometry.dofmaps[0]
    nv = num_cell_vertices(msh.topology.cell_type)
    if xdm.shape[1] != nv:
        raise ValueError("contact requires an affine (P1) geometry of the contact body")
    out = np.full(msh.geometry.x.shape[0], -1, dtype=np.int64)
    out[xdm.ravel()] = V.dofmap.list[:, :nv].ravel()
    return out


class Surface:
    """The boundary ``boundary`` of ``body`` as the home of interface fields.

    Attributes:
        body: the :class:`tribofx.body.Body`.
        sub, emap: facet submesh and its entity map to the body's mesh.
        Q, Vs: scalar and vector (gdim) P1 spaces on the submesh.
        sub_dofs, bulk_dofs: per submesh node, its block dof in Vs (= dof in Q)
            and the block dof of the same vertex in ``body.V``.
        X_sub: (n_sub_dofs, gdim) reference positions in Vs block-dof order.
        dsc: vertex-quadrature measure of the boundary on the body's mesh.
        n_own: number of owned submesh dofs (they come first).
    """

    def __init__(self, body: Body, boundary: str) -> None:
        msh, gdim = body.mesh, body.gdim
        self.body = body
        self.sub, self.emap, gmap = facet_submesh(msh, body.facet_tags, body.tag(boundary),
                                                  f"{body.name} {boundary}")
        self.Vs = fem.functionspace(self.sub, ("Lagrange", 1, (gdim,)))
        self.Q = fem.functionspace(self.sub, ("Lagrange", 1))
        nsub = self.sub.geometry.x.shape[0]
        self.sub_dofs = node_to_dof(self.Vs)[np.arange(nsub)]
        self.bulk_dofs = node_to_dof(body.V)[gmap[np.arange(nsub)]]
        self.X_sub = np.zeros((self.Vs.dofmap.index_map.size_local
                               + self.Vs.dofmap.index_map.num_ghosts, gdim))
        self.X_sub[self.sub_dofs] = self.sub.geometry.x[:, :gdim]
        self.dsc = ufl.Measure("ds", msh, subdomain_data=body.facet_tags,
                               subdomain_id=body.tag(boundary),
                               metadata={"quadrature_rule": "vertex", "quadrature_degree": 1})
        self.n_own = self.Q.dofmap.index_map.size_local
        self.weight = self._nodal_weight()

    def _nodal_weight(self) -> ufl.core.expr.Expr | float:
        """Return the reference measure factor of the nodal (vertex-rule) terms on this surface.

        1, except on an axisymmetric body: there the vertex rule applied to 2πR
        would give the node on the axis (R = 0) no area, so its contact row would
        vanish from the momentum equations and its multiplier column with it (a
        singular Jacobian once the node is active).  Instead ω is the P1 field with
        ω_k = ∫ φ_k 2πR dS / ∫ φ_k dS (exact quadrature): the vertex rule of
        f ω dS then gives every node its exact lumped area ∫ φ_k 2πR dS
        (π h²/3 on the axis for a first facet of length h perpendicular to it).
        """
        body = self.body
        if body.kind != "axisymmetric":
            return body.weight
        tag = self.dsc.subdomain_id()
        exact = ufl.Measure("ds", body.mesh, subdomain_data=body.facet_tags, subdomain_id=tag,
                            metadata={"quadrature_degree": 2})
        q = ufl.TestFunction(self.Q)
        area = self.nodal(q * body.weight * exact)
        length = self.nodal(q * self.dsc)
        omega = fem.Function(self.Q, name="surface_weight")
        omega.x.array[:] = np.divide(area, length, out=np.zeros_like(area), where=length > 0)
        return omega

    def nodal(self, form: fem.Form | ufl.Form) -> npt.NDArray[np.float64]:
        """Assembled (ghost-updated) vector of the linear ``form`` on the submesh dofs."""
        if not isinstance(form, fem.Form):
            form = fem.form(form, entity_maps=[self.emap])
        vec = fem.assemble_vector(form)
        vec.scatter_reverse(la.InsertMode.add)
        vec.scatter_forward()
        return vec.array.copy()

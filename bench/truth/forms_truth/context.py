# SPDX-License-Identifier: LGPL-3.0-or-later
"""Shared UFL objects of the truth model: unknowns, kinematics, measures.

Reference (neutral) configuration X, displacement u (P2 on the P2 mesh),
deformed position x = X + u, F = I + grad u, J = det F.
"""
import ufl
from dolfinx import fem

# Quadrature degrees: P2 displacement on curved P2 cells; the energy
# densities (ln J, smooth weights) are not polynomials, so the rules are
# taken generously (degree 4 in the volume and on the surface).
QDEG_VOLUME = 4
QDEG_SURFACE = 4


class Context:
    def __init__(self, mesh, facet_tags, tags, R, H, degree=2):
        self.mesh = mesh
        self.R, self.H = R, H
        self.Rs = (R * R + H * H) / (2 * H)   # sphere of the neutral skin
        self.facet_tags = facet_tags
        self.tags = tags
        self.V = fem.VectorFunctionSpace(mesh, ("Lagrange", degree))
        self.u = fem.Function(self.V, name="u")
        self.v = ufl.TestFunction(self.V)
        self.du = ufl.TrialFunction(self.V)
        self.X = ufl.SpatialCoordinate(mesh)
        self.N = ufl.FacetNormal(mesh)
        self.I = ufl.Identity(3)
        self.F = self.I + ufl.grad(self.u)
        self.J = ufl.det(self.F)
        self.dx = ufl.Measure("dx", domain=mesh, metadata={"quadrature_degree": QDEG_VOLUME})
        self._ds = ufl.Measure("ds", domain=mesh, subdomain_data=facet_tags,
                               metadata={"quadrature_degree": QDEG_SURFACE})

    def ds(self, name):
        """Surface measure on one tagged boundary part (base, skin, symmetry)."""
        return self._ds(self.tags[name])

    def constant(self, value=0.0):
        return fem.Constant(self.mesh, float(value))

    def integrate(self, expr):
        """Assemble a scalar UFL form (serial generator)."""
        return fem.assemble_scalar(fem.form(expr))


def neo_hooke_density(F, J, mu, lmbda):
    """docs/MODEL.md eq. (5): W = mu/2 (tr(F F^T) - 3 - 2 ln J) + lambda/2 (J - 1)^2."""
    return 0.5 * mu * (ufl.inner(F, F) - 3.0 - 2.0 * ufl.ln(J)) + 0.5 * lmbda * (J - 1.0) ** 2

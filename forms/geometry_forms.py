# SPDX-License-Identifier: LGPL-3.0-or-later
"""The forms that belong to no energy term (ffcx module geometry_p<degree>):

    volume       = int_B J dV              deformed volume of the model
    area_<tag>   = int_<tag> 1 dA          reference area of a tagged boundary part
    detF         = det F at the points where the energy is evaluated (inversion check)

It also provides the displacement space ('u') for the C++ side.
"""
import basix as _basix

from common import DEGREE, J, QDEG, TAGS, X, dx, ds, u  # noqa: F401

volume = J * dx
forms = [volume]
for _tag in TAGS:
    globals()["area_" + _tag] = (1 + 0 * X[0]) * ds(_tag)
    forms.append(globals()["area_" + _tag])

# The admissibility check det F > 0 where the energy is evaluated: P1 (F
# constant per cell) at the vertices and the centroid; P2 at the points of
# the volume quadrature rule (degree QDEG["volume"] = 4: 14 points, among
# them the edge midpoints) and the centroid, as FEBio checks its Jacobians
# at the integration points. A P2 cell may then dip below zero at a corner
# node between these points, where no energy is evaluated.
if DEGREE == 1:
    _points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
else:
    _points = _basix.make_quadrature(_basix.CellType.tetrahedron, QDEG["volume"])[0].tolist()
_points.append([0.25, 0.25, 0.25])
detF = J
expressions = [(detF, _points)]

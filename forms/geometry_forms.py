"""The forms that belong to no energy term (ffcx module geometry_p<degree>):

    volume       = int_B J dV              deformed volume of the model
    area_<tag>   = int_<tag> 1 dA          reference area of a tagged boundary part
    detF         = det F at the element nodes (inversion check)

It also provides the displacement space ('u') for the C++ side.
"""
from common import DEGREE, J, TAGS, X, dx, ds, u  # noqa: F401

volume = J * dx
forms = [volume]
for _tag in TAGS:
    globals()["area_" + _tag] = (1 + 0 * X[0]) * ds(_tag)
    forms.append(globals()["area_" + _tag])

# det F at the reference-cell nodes of the element (vertices and, for P2,
# edge midpoints) and the centroid.
_points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
if DEGREE == 2:
    _points += [[0, .5, .5], [.5, 0, .5], [.5, .5, 0], [0, 0, .5], [0, .5, 0], [.5, 0, 0]]
_points.append([0.25, 0.25, 0.25])
detF = J
expressions = [(detF, _points)]

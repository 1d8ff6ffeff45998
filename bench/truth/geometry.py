# SPDX-License-Identifier: LGPL-3.0-or-later
"""Neutral geometry of the truth model: the half spherical cap (x >= 0).

Written for the truth generator only (not shared with src/ or forms/).
docs/MODEL.md frame: base disc y = 0 of radius R, apex (nipple) at (0, H, 0),
symmetry plane x = 0, z cranial. The cap is the part y >= 0 of the ball of
radius Rs = (R^2 + H^2) / (2 H) centred at (0, H - Rs, 0).

The cap is split by the plane z = 0 into two volumes meshed conformingly, so
that the apex (0, H, 0), where that plane meets the symmetry arc, is a
geometric vertex and therefore a mesh vertex.
"""
import gmsh
import numpy as np
from mpi4py import MPI
from dolfinx.io import gmshio

# Facet tags of the truth mesh (own numbering, same names as docs/MODEL.md).
TAGS = {"base": 1, "skin": 2, "symmetry": 3}


def sphere_radius(R, H):
    """Rs = (R^2 + H^2) / (2 H): the sphere through the base rim and the apex."""
    return (R * R + H * H) / (2.0 * H)


def check_dimensions(R, H, mesh_size):
    if not (0 < R <= 0.5 and 0 < H <= 0.5):
        raise ValueError(f"geometry: R = {R} m and H = {H} m must lie in (0, 0.5] m")
    if H > 1.5 * R:
        raise ValueError(f"geometry: H = {H} m must be at most 1.5 R = {1.5 * R} m")
    if not (R / 400 <= mesh_size <= min(R, H) / 2):
        raise ValueError(f"geometry: mesh_size = {mesh_size} m must lie in "
                         f"[R/400, min(R, H)/2] = [{R / 400}, {min(R, H) / 2}] m")


def _cap_piece(Rs, H, z_lo, z_hi):
    """OCC volume: ball ∩ {x >= 0, y >= 0, z_lo <= z <= z_hi}."""
    ball = gmsh.model.occ.addSphere(0, H - Rs, 0, Rs)
    box = gmsh.model.occ.addBox(0, 0, z_lo, 2 * Rs, 2 * Rs, z_hi - z_lo)
    out, _ = gmsh.model.occ.intersect([(3, ball)], [(3, box)])
    return out


def _classify_surfaces(R, H, tol):
    """Tag the boundary surfaces by their centre of mass: base (y = 0),
    symmetry (x = 0), skin (the rest); the interior interface z = 0 is left
    untagged."""
    groups = {name: [] for name in TAGS}
    for dim, tag in gmsh.model.getEntities(2):
        up, _ = gmsh.model.getAdjacencies(dim, tag)
        cx, cy, cz = gmsh.model.occ.getCenterOfMass(dim, tag)
        if len(up) != 1:
            continue  # interface between the two halves
        if abs(cy) < tol:
            groups["base"].append(tag)
        elif abs(cx) < tol:
            groups["symmetry"].append(tag)
        else:
            groups["skin"].append(tag)
    for name, tags in groups.items():
        if not tags:
            raise RuntimeError(f"geometry: no surface classified as '{name}'")
    return groups


def _rim_curves(R, tol):
    """Curves of the base rim: y = 0 and x^2 + z^2 = R^2 at their midpoint."""
    rim = []
    for _, tag in gmsh.model.getEntities(1):
        lo, hi = gmsh.model.getParametrizationBounds(1, tag)
        x, y, z = gmsh.model.getValue(1, tag, [0.5 * (lo[0] + hi[0])])
        if abs(y) < tol and abs(np.hypot(x, z) - R) < tol:
            rim.append(tag)
    if not rim:
        raise RuntimeError("geometry: no curve classified as the base rim")
    return rim


def _grade_to_rim(R, mesh_size, rim_size):
    """Element size rim_size within rim_size of the base rim, growing
    linearly with the distance d to mesh_size at d = 3 mesh_size: the fixed
    base meets the free skin at the rim, where the displacement gradient is
    singular and a uniform mesh's error is largest."""
    dist = gmsh.model.mesh.field.add("Distance")
    gmsh.model.mesh.field.setNumbers(dist, "CurvesList", _rim_curves(R, 1e-6 * R))
    gmsh.model.mesh.field.setNumber(dist, "NumPointsPerCurve", 400)
    grade = gmsh.model.mesh.field.add("Threshold")
    gmsh.model.mesh.field.setNumber(grade, "InField", dist)
    gmsh.model.mesh.field.setNumber(grade, "SizeMin", rim_size)
    gmsh.model.mesh.field.setNumber(grade, "SizeMax", mesh_size)
    gmsh.model.mesh.field.setNumber(grade, "DistMin", rim_size)
    gmsh.model.mesh.field.setNumber(grade, "DistMax", 3 * mesh_size)
    gmsh.model.mesh.field.setAsBackgroundMesh(grade)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)


def build_half_cap(R, H, mesh_size, order=2, comm=MPI.COMM_WORLD, rim_size=None):
    """Mesh the half cap with gmsh (order-`order` tetrahedra, curved on the
    sphere) and return (mesh, facet_tags); with `rim_size` the elements are
    graded from rim_size at the base rim to mesh_size."""
    check_dimensions(R, H, mesh_size)
    if rim_size is not None and not (mesh_size / 10 <= rim_size <= mesh_size):
        raise ValueError(f"geometry: rim_size = {rim_size} m must lie in "
                         f"[mesh_size/10, mesh_size] = [{mesh_size / 10}, {mesh_size}] m")
    Rs = sphere_radius(R, H)
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("truth_half_cap")
        lower = _cap_piece(Rs, H, -2 * Rs, 0.0)
        upper = _cap_piece(Rs, H, 0.0, 2 * Rs)
        gmsh.model.occ.fragment(lower, upper)
        gmsh.model.occ.synchronize()
        groups = _classify_surfaces(R, H, 1e-3 * mesh_size)
        vols = [t for _, t in gmsh.model.getEntities(3)]
        gmsh.model.addPhysicalGroup(3, vols, 1)
        for name, tags in groups.items():
            gmsh.model.addPhysicalGroup(2, tags, TAGS[name])
        gmsh.option.setNumber("Mesh.MeshSizeMax", mesh_size)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.5 * (rim_size or mesh_size))
        if rim_size is not None:
            _grade_to_rim(R, mesh_size, rim_size)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay
        gmsh.option.setNumber("Mesh.Optimize", 1)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.mesh.generate(3)
        gmsh.model.mesh.setOrder(order)
        mesh, _, facets = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=3)
    finally:
        gmsh.finalize()
    return mesh, facets


def apex_index(V, H):
    """Local index of the P2 node at the apex (0, H, 0) in V's dof layout; the
    apex is a mesh vertex by construction."""
    x = V.tabulate_dof_coordinates()
    d = np.linalg.norm(x - np.array([0.0, H, 0.0]), axis=1)
    i = int(np.argmin(d))
    if d[i] > 1e-9:
        raise RuntimeError(f"geometry: no mesh node at the apex (closest {d[i]:.3g} m)")
    return i

#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""The peers' half cap for CalculiX (bench/peer/calculix_bench.sh).

    peer_inp.py mesh GEO LC OUT.msh   mesh GEO like `gmsh -3 GEO -setnumber lc LC
                                      -format msh22 -o OUT.msh`, through the gmsh
                                      library (C API; no gmsh program needed)
    peer_inp.py inp MSH OUT.inp       CalculiX deck of the mesh: C3D4, HYPERFOAM
                                      equal to eq. (5) at lambda = 0, base fixed,
                                      symmetry x = 0 sliding, gravity -z, 10 increments
    peer_inp.py apex DAT              apex (0, H, 0) displacement of the last
                                      increment in the .dat: "u_x u_y u_z" [m]

The material (meshes/peers/README.md): mu = 2100 Pa, lambda = 0, rho = 970
kg/m^3, g = 9.81 m/s^2. CalculiX's HYPERFOAM
    W = sum_i 2 mu_i / alpha_i^2 (l1^a_i + l2^a_i + l3^a_i - 3 + (J^(-a_i b_i) - 1) / b_i),
    b_i = nu_i / (1 - 2 nu_i),
with alpha_i = 2 and nu_i = 0 (b_i -> 0, (J^(-2 b) - 1) / b -> -2 ln J) is
    W = sum_i mu_i / 2 (I1 - 3 - 2 ln J),
eq. (5) at lambda = 0 with mu = mu_1 + mu_2; N = 2 as the peers ran it,
mu_1 = mu_2 = mu / 2.
"""
import ctypes
import sys

MU, RHO, G = 2100.0, 970.0, 9.81
APEX = (0.0, 0.06, 0.0)
PLANE_TOL = 1e-9  # m: gmsh puts the nodes of the planes y = 0, x = 0 on them exactly


def gmsh_call(lib, name, *args):
    ierr = ctypes.c_int(0)
    getattr(lib, name)(*args, ctypes.byref(ierr))
    if ierr.value != 0:
        raise SystemExit(f"peer_inp.py: gmsh {name} failed (error {ierr.value})")


def mesh(geo, lc, out):
    """gmsh -3 GEO -setnumber lc LC -format msh22 -o OUT through libgmsh."""
    lib = ctypes.CDLL("libgmsh.so.4.8")
    lib.gmshOptionSetNumber.argtypes = [ctypes.c_char_p, ctypes.c_double, ctypes.POINTER(ctypes.c_int)]
    args = [b"gmsh", b"-setnumber", b"lc", lc.encode()]
    argv = (ctypes.c_char_p * len(args))(*args)
    gmsh_call(lib, "gmshInitialize", len(args), argv, 0)
    gmsh_call(lib, "gmshOptionSetNumber", b"General.Terminal", 0.0)
    gmsh_call(lib, "gmshOpen", geo.encode())
    gmsh_call(lib, "gmshModelMeshGenerate", 3)
    gmsh_call(lib, "gmshOptionSetNumber", b"Mesh.MshFileVersion", 2.2)
    gmsh_call(lib, "gmshWrite", out.encode())
    gmsh_call(lib, "gmshFinalize")


def read_msh22(path):
    """Nodes {tag: (x, y, z)} and 4-node tetrahedra [(tags)] of an ASCII msh 2.2 file."""
    nodes, tets = {}, []
    with open(path) as f:
        lines = iter(f.read().split("\n"))
    for line in lines:
        if line == "$MeshFormat" and not next(lines).startswith("2.2 0"):
            raise SystemExit(f"peer_inp.py: {path} is not an ASCII msh 2.2 file")
        if line == "$Nodes":
            for _ in range(int(next(lines))):
                t, x, y, z = next(lines).split()
                nodes[int(t)] = (float(x), float(y), float(z))
        if line == "$Elements":
            for _ in range(int(next(lines))):
                f = [int(v) for v in next(lines).split()]
                if f[1] == 4:  # 4-node tetrahedron: tag, type, ntags, tags..., nodes
                    tets.append(tuple(f[3 + f[2]:]))
    return nodes, tets


def inp(msh, out):
    nodes, tets = read_msh22(msh)
    used = sorted({n for t in tets for n in t})
    base = [n for n in used if abs(nodes[n][1]) < PLANE_TOL]
    symmetry = [n for n in used if abs(nodes[n][0]) < PLANE_TOL]
    apex = min(used, key=lambda n: sum((a - b) ** 2 for a, b in zip(nodes[n], APEX)))
    if sum((a - b) ** 2 for a, b in zip(nodes[apex], APEX)) > 1e-20:
        raise SystemExit(f"peer_inp.py: no node at the apex {APEX} in {msh}")

    def node_set(name, members):
        rows = [", ".join(str(n) for n in members[i:i + 12]) for i in range(0, len(members), 12)]
        return [f"*NSET, NSET={name}"] + rows

    deck = ["*HEADING", f"peers' half cap, {len(tets)} tets / {len(used)} nodes, gravity standing", "*NODE"]
    # CalculiX reads at most 20 characters per field: 14 significant digits
    deck += [f"{n}, {nodes[n][0]:.13e}, {nodes[n][1]:.13e}, {nodes[n][2]:.13e}" for n in used]
    deck += ["*ELEMENT, TYPE=C3D4, ELSET=EALL"]
    deck += [f"{e + 1}, {t[0]}, {t[1]}, {t[2]}, {t[3]}" for e, t in enumerate(tets)]
    deck += node_set("NBASE", base) + node_set("NSYM", symmetry) + node_set("NAPEX", [apex])
    deck += ["*MATERIAL, NAME=TISSUE",
             # mu_1, alpha_1, mu_2, alpha_2, nu_1, nu_2 (module docstring)
             "*HYPERFOAM, N=2", f"{MU / 2:g}, 2., {MU / 2:g}, 2., 0., 0.",
             "*DENSITY", f"{RHO:g}",
             "*SOLID SECTION, ELSET=EALL, MATERIAL=TISSUE",
             "*BOUNDARY", "NBASE, 1, 3", "NSYM, 1, 1",
             "*STEP, NLGEOM, INC=100",
             # 10 equal increments of 0.1 (DIRECT: no automatic incrementation)
             "*STATIC, DIRECT", "0.1, 1.0",
             # residual and correction tolerances tightened from 0.005 / 0.01 to 1e-8
             "*CONTROLS, PARAMETERS=FIELD", "1.e-8, 1.e-8, , , 1.e-8, 1.e-5, 1.e-3, 1.e-8",
             "*DLOAD", f"EALL, GRAV, {G:g}, 0., 0., -1.",
             "*NODE PRINT, NSET=NAPEX", "U",
             "*END STEP", ""]
    with open(out, "w") as f:
        f.write("\n".join(deck))
    print(f"{len(tets)} tets, {len(used)} nodes, {len(base)} base nodes, {len(symmetry)} symmetry nodes, "
          f"apex node {apex}")


def apex(dat):
    """The last displacement row of set NAPEX in a CalculiX .dat file."""
    last = None
    with open(dat) as f:
        rows = f.read().split("\n")
    for i, line in enumerate(rows):
        if line.strip().startswith("displacements (vx,vy,vz) for set NAPEX"):
            for row in rows[i + 1:]:
                if row.strip():
                    last = row.split()[1:4]
                    break
    if last is None:
        raise SystemExit(f"peer_inp.py: no displacement of NAPEX in {dat}")
    print(" ".join(last))


if __name__ == "__main__":
    commands = {"mesh": (mesh, 3), "inp": (inp, 2), "apex": (apex, 1)}
    if len(sys.argv) < 2 or sys.argv[1] not in commands or len(sys.argv) != 2 + commands[sys.argv[1]][1]:
        raise SystemExit(__doc__)
    commands[sys.argv[1]][0](*sys.argv[2:])

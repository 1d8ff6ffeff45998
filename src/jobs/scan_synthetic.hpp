// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The `synthetic-patient` job: test data without real patients. A non-cap
// reference breast (src/scan/synthetic_breast.hpp: volume, ptosis, lateral
// turn, asymmetry) is meshed as a full breast, forward-solved to a posture
// with the case's material, and its deformed skin sampled to a scan: the
// skin triangles split once into four, holes cut out (discs of the given
// radius around random skin points away from the chest), Gaussian noise of
// standard deviation `noise` along each point's normal, the whole moved by
// `offset` into a "scanner" frame (axes unchanged). Written:
//   scan.<stl|ply|obj>   the scan, in millimetres
//   chest.stl            the true chest wall (a square of the plane y = 0), for --chest
//   reference.msh, case.reference.toml   the true stress-free breast (breast frame)
//   truth.json           the shape, posture, noise, offset and the loaded observables
// Serial (one MPI rank).
#include "config.hpp"
#include "output_target.hpp"
#include "posture.hpp"
#include "scan_writers.hpp"
#include "synthetic_breast.hpp"
#include <mpi.h>

namespace breastsim
{
struct SyntheticPatientRequest
{
  scan::SyntheticShape shape;
  Posture posture;
  double noise = 0.5e-3;       ///< standard deviation along the normal [m]
  int holes = 3;               ///< in [0, 10]
  double hole_radius = 0.005;  ///< [m]
  scan::ScanFormat format = scan::ScanFormat::stl_binary;
  bool points_only = false;    ///< a point cloud (PLY, OBJ)
  unsigned seed = 1;
  double mesh_size = 0.006;    ///< of the reference mesh [m]
  scan::Vec3 offset{0.1, 0.05, 1.2}; ///< scanner frame = breast frame + offset [m]
};

struct SyntheticPatientResult
{
  double volume = 0;                 ///< of the reference mesh [m^3]
  scan::Vec3 nipple_reference{}, nipple_loaded{};
  std::size_t scan_points = 0, scan_triangles = 0;
  std::string scan_file;
};

SyntheticPatientResult synthetic_patient(const Config& material, const SyntheticPatientRequest& r,
                                         const OutputTarget& out, MPI_Comm comm);
} // namespace breastsim

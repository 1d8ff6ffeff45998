// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Writers of scans (the synthetic patients' and the tests'): binary and
// ASCII STL, ASCII and binary_little_endian PLY (with faces, or vertices
// only: a point cloud), OBJ. Coordinates are written in `units` (the
// surface holds metres). std::runtime_error when the file cannot be written.
#include "scan_surface.hpp"
#include <filesystem>

namespace breastsim::scan
{
enum class ScanFormat
{
  stl_binary,
  stl_ascii,
  ply_ascii,
  ply_binary,
  obj
};

/// Write `s` as `format`; `points_only` writes no faces (PLY, OBJ: a point cloud).
void write_scan(const ScanSurface& s, const std::filesystem::path& file, ScanFormat format, Units units,
                bool points_only = false);
} // namespace breastsim::scan

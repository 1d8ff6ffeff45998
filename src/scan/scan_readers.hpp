// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Readers of skin scans: STL (ASCII and binary), PLY (ASCII and
// binary_little_endian; vertices x, y, z and an optional face list) and
// Wavefront OBJ (v and f lines; polygons split into fans). A PLY or OBJ
// without faces is a point cloud. Coordinates are scaled from the stated
// unit to metres; STL's corners are merged into shared points when their
// coordinates are equal. Every failure is an InputError naming the file and
// what is wrong: no such file, an unknown format, a truncated binary file, a
// malformed line (its number), a face index out of range.
#include "scan_surface.hpp"
#include <filesystem>

namespace breastsim::scan
{
/// Read `path` (format from its extension: .stl, .ply, .obj, any case).
ScanSurface read_scan(const std::filesystem::path& path, Units units);

/// "mm" or "m" -> Units; InputError naming `option` otherwise.
Units parse_units(const std::string& text, const std::string& option);
} // namespace breastsim::scan

// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The per-format readers behind read_scan (scan_readers.hpp): each fills
// points (in the file's unit) and triangles from the file's bytes, throwing
// InputError with `where` in the message.
#include "scan_surface.hpp"
#include <string>

namespace breastsim::scan
{
void read_stl(const std::string& bytes, const std::string& where, ScanSurface& s);
void read_ply(const std::string& bytes, const std::string& where, ScanSurface& s);
void read_obj(const std::string& bytes, const std::string& where, ScanSurface& s);
} // namespace breastsim::scan

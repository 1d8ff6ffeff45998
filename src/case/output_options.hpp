// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The last fixed section of the schema: the resource limit and the output
// formats.
#include "config.hpp"
#include <string>
#include <vector>

namespace breastsim
{
struct OutputOptions
{
  /// solver.max_memory_gb: largest estimated peak memory of a case [GB]
  /// (0: 80 % of the machine's memory; checked by Config::validate).
  double max_memory_gb = 0.0;
  bool xdmf = true; ///< output.xdmf: displacement fields as XDMF
  bool vtk = false; ///< output.vtk: also VTK files
  /// output.pictures: "none" (`breastsim view DIR` makes them on request) or
  /// "full" (matplotlib PNGs of every posture and the 3D page, about 1.5 s each)
  std::string pictures = "none";
  bool pictures_on() const { return pictures == "full"; }

  bool operator==(const OutputOptions&) const = default;
  /// Append solver.max_memory_gb, output.xdmf, output.vtk, output.pictures
  /// (defaults: the initialisers above).
  static void declare(std::vector<KeyInfo>& keys);
  static OutputOptions from(const Config& c);
};
} // namespace breastsim

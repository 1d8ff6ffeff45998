// SPDX-License-Identifier: LGPL-3.0-or-later
#include "output_options.hpp"

namespace breastsim
{
void OutputOptions::declare(std::vector<KeyInfo>& keys)
{
  const OutputOptions d;
  keys.push_back(number_key("solver.max_memory_gb", "GB", d.max_memory_gb, 0.0, 1e6,
                            "refuse a case whose estimated peak memory exceeds this (0: 80 % of "
                            "this machine's memory); the estimate is in the message"));
  keys.push_back(boolean_key("output.xdmf", d.xdmf, "write displacement fields as XDMF (ParaView)"));
  keys.push_back(boolean_key("output.vtk", d.vtk, "also write VTK files (native P2)"));
  keys.push_back(choice_key("output.pictures", d.pictures, {"none", "full"},
                            "PNG pictures and the 3D page of each posture (matplotlib, about "
                            "1.5 s a picture): none, or full; `breastsim view DIR` makes them later"));
}

OutputOptions OutputOptions::from(const Config& c)
{
  OutputOptions o;
  o.max_memory_gb = c.number("solver.max_memory_gb");
  o.xdmf = c.flag("output.xdmf");
  o.vtk = c.flag("output.vtk");
  o.pictures = c.text("output.pictures");
  return o;
}
} // namespace breastsim

#pragma once
// The final neutral state (SPEC.md): the current deformed configuration
// becomes the new stress-free reference. The mesh geometry is moved by the
// displacement and u is set to zero.
#include "model.hpp"

namespace breastsim
{
/// x_geometry += u at every geometry node, then u = 0 (collective).
/// Requires the isoparametric setting (geometry and displacement elements of
/// the same degree, as the compiled forms are).
void reset_reference(Model& model);
} // namespace breastsim

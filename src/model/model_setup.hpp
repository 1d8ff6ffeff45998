// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A case's model: the neutral mesh's model with the case's parameters and
// term switches bound, and gravity for a posture.
#include "config.hpp"
#include "model.hpp"
#include <array>
#include <memory>
#include <mpi.h>

namespace breastsim
{
/// Bind every physics key of the case and the term switches into the model.
void apply_parameters(const Config& c, Model& model);
/// The model of the case's neutral half cap (symmetry, base fixed if
/// base.fixed) with the case's parameters bound. Collective on comm.
std::unique_ptr<Model> make_neutral_model(const Config& c, MPI_Comm comm);
/// Set gravity to g and return the norm of the full (load = 1) gravity
/// load, the force scale of the Newton tolerance; leaves load = 0.
double set_gravity(Model& model, const std::array<double, 3>& g);
} // namespace breastsim

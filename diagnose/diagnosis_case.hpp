// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The case a diagnosis fits (diagnose.hpp): the user's case with the
// recording's a-priori values on the diagnosis discretisation, and back.
#include "config.hpp"
#include "diagnosis.hpp"
#include "recording.hpp"

namespace breastsim::diagnosis
{
/// The current model with the recording's a-priori values (named like --fit),
/// on the diagnosis discretisation (o.order, o.mesh_size; a user's mesh file
/// keeps its mesh).
Config with_known(const Config& current, const Recording& rec, const DiagnoseOptions& o);

/// `diagnosed` with the element order and mesh size of the user's case.
Config on_users_mesh(Config diagnosed, const Config& users);
} // namespace breastsim::diagnosis

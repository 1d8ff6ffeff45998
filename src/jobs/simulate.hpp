// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The forward simulation: mesh the neutral half breast, bind the case's
// parameters, and solve each posture from the neutral state.
#include "config.hpp"
#include "mesh_quality.hpp"
#include "output_target.hpp"
#include "posture_solve.hpp"
#include "progress.hpp"
#include <filesystem>
#include <memory>

namespace breastsim
{
struct SimulationResult
{
  MeshQuality quality;
  std::int64_t dofs = 0;
  std::string linear_solver;
  double mesh_seconds = 0;
  std::int64_t coarse_dofs = 0;      ///< grid sequencing: coarse unknowns (0: not used)
  std::vector<std::int64_t> coarse_level_dofs; ///< unknowns of every level of the ladder
  double coarse_setup_seconds = 0;   ///< coarse mesh, model and node location
  std::vector<PostureResult> postures;
};

/// Solve every requested posture of the case from the model's current
/// reference and write each displacement as <dir>/displacement_<posture>.
/// `progress`: "posture NAME (k of N)" as each posture begins, at (k - 1) / N.
std::vector<PostureResult> solve_postures(Model& model, const ObservableProbe& probe,
                                          const Config& c, const std::filesystem::path& dir,
                                          CoarseStart* coarse = nullptr, const Progress& progress = {});

/// The whole `simulate` job. Writes into `out` (replaced only on success).
/// `progress`: meshing, each posture, pictures (N + 2 stages of equal share), finished.
SimulationResult simulate(const Config& c, const OutputTarget& out, MPI_Comm comm,
                          const Progress& progress = {});

/// Short printable table of the observables of each posture.
std::string observables_table(const std::vector<PostureResult>& r);
nlohmann::json to_json(const PostureResult& r);
/// Every Newton iteration of each posture, in the order of `r`: a list of
/// {"posture", "records": [{"solve", "load", "iteration", "residual_norm_N",
/// "model_energy_J", "step", "linear_iterations", "eta", "wall_time_s"}, ...]}
/// (summary.json "newton_records"). The residual and the energy are those of
/// the solved half (the posture's "energy_J" is the full breast's, twice).
nlohmann::json newton_records_json(const std::vector<PostureResult>& r);
/// The Newton iterations of one posture as a table (printed with -v).
std::string newton_table(const PostureResult& r);
/// newton_table of each posture, each headed by `heading` (e.g. "post-operative: ").
std::string newton_tables(const std::vector<PostureResult>& r, const std::string& heading = "");
} // namespace breastsim

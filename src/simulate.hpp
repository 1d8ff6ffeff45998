#pragma once
// The forward simulation: mesh the neutral half breast, bind the case's
// parameters, and solve each posture from the neutral state.
#include "../meshes/half_cap.hpp"
#include "coarse_start.hpp"
#include "config.hpp"
#include "load_stepping.hpp"
#include "mesh_quality.hpp"
#include "observables.hpp"
#include "output_target.hpp"
#include "posture.hpp"
#include <filesystem>
#include <memory>

namespace breastsim
{
struct PostureResult
{
  Posture posture;
  Observables observables;
  LoadPathReport path;
  CoarseGuessReport coarse; ///< grid sequencing (src/coarse_start.hpp), if used
  double min_det_F = 0;     ///< smallest det F of the deformed state (element nodes)
  double seconds = 0;
};

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

/// The half-cap geometry and mesh settings of the case.
meshes::HalfCapSpec cap_spec(const Config& c);
/// Mesh the neutral half cap of the case (collective; gmsh runs on rank 0).
TaggedDolfinxMesh build_neutral_mesh(const Config& c, MPI_Comm comm);
/// Bind every physics key of the case and the term switches into the model.
void apply_parameters(const Config& c, Model& model);
NewtonOptions newton_options(const Config& c);
LoadStepOptions load_step_options(const Config& c);
/// The postures requested by the case (names first, then angles).
std::vector<Posture> requested_postures(const Config& c);

/// Set gravity to g and return the norm of the full (load = 1) gravity
/// load, the force scale of the Newton tolerance; leaves load = 0.
double set_gravity(Model& model, const std::array<double, 3>& g);

/// Solve one posture from the neutral state (u = 0): the gravity load is
/// ramped from 0 to 1 with cut-back. With `coarse` (a coarse model of the
/// same case), Newton first starts at full load from the coarse solution;
/// if that fails, from u = 0 as above. Throws SolveError naming the posture.
PostureResult solve_posture(Model& model, NewtonSolver& newton, const ObservableProbe& probe,
                            const Posture& posture, const Config& c, CoarseStart* coarse = nullptr);

/// Solve every requested posture of the case from the model's current
/// reference and write each displacement as <dir>/displacement_<posture>.
std::vector<PostureResult> solve_postures(Model& model, const ObservableProbe& probe,
                                          const Config& c, const std::filesystem::path& dir,
                                          CoarseStart* coarse = nullptr);

/// The whole `simulate` job. Writes into `out` (replaced only on success).
SimulationResult simulate(const Config& c, const OutputTarget& out, MPI_Comm comm);

/// Short printable table of the observables of each posture.
std::string observables_table(const std::vector<PostureResult>& r);
nlohmann::json to_json(const PostureResult& r);
} // namespace breastsim

// SPDX-License-Identifier: LGPL-3.0-or-later
// The nonlinear solver's building blocks: the fast Jacobian insertion, the
// Eisenstat-Walker inexact Newton method and its bookkeeping.
#include "block_csr_adder.hpp"
#include "fixtures.hpp"
#include "newton.hpp"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gtest/gtest.h>
#include <set>
#include <unistd.h>

using namespace breastsim;

namespace
{
int comm_size()
{
  int n;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

double frobenius(Mat A)
{
  PetscReal n;
  PETSC_CHECK(MatNorm(A, NORM_FROBENIUS, &n));
  return n;
}

/// Largest |u| over the constrained dofs.
double max_abs_constrained(const Model& m)
{
  const std::vector<std::int8_t> marker = m.constrained_markers();
  double v = 0;
  auto u = m.displacement()->x()->array();
  for (std::size_t i = 0; i < marker.size(); ++i)
    if (marker[i])
      v = std::max(v, std::abs(u[i]));
  return v;
}
} // namespace

class FastJacobian : public ::testing::TestWithParam<int>
{
};

/// A copy of A's values (same pattern).
PetscMat copy_of(Mat A)
{
  PetscMat B;
  PETSC_CHECK(MatDuplicate(A, MAT_COPY_VALUES, B.out()));
  return B;
}

/// |A - B|_F / |B|_F for matrices of the same pattern.
double relative_difference(Mat A, Mat B)
{
  PetscMat D = copy_of(A);
  PETSC_CHECK(MatAXPY(D.get(), -1.0, B, SAME_NONZERO_PATTERN));
  return frobenius(D.get()) / frobenius(B);
}

// Assemblies into a matrix of create_matrix() (pattern inserted and
// recorded) go straight into its CSR values: the first one searches each
// block and records the offsets, the later ones replay them. Both must equal
// PETSc's own insertion (into a duplicate the adder has not recorded), also
// after u changed. Also run on 2 ranks (ctest unit_mpi_fast_jacobian): owned
// rows into the diagonal and off-diagonal parts, ghost rows through PETSc.
TEST_P(FastJacobian, EqualsPetscInsertion)
{
  const int order = GetParam();
  auto c = fixtures::coarse_case(order, order == 1 ? 0.014 : 0.02);
  auto m = fixtures::make_model(c);
  m->set_parameter("g_vec", {0.0, -4.0, -9.0});
  fixtures::perturb(*m, 2e-3, 1);
  PetscMat A(m->create_matrix());
  BlockCsrAdder probe(3);
  probe.record(A.get());
  ASSERT_TRUE(probe.matches(A.get())) << "an AIJ Jacobian has a 3x3-blocked pattern (" << comm_size()
                                << " ranks)";
  // PETSc's insertion as the reference: into a duplicate the model's adder
  // has not recorded (A is recorded again by its next assembly).
  auto petsc_jacobian = [&]()
  {
    PetscMat R;
    PETSC_CHECK(MatDuplicate(A.get(), MAT_DO_NOT_COPY_VALUES, R.out()));
    m->assemble_jacobian(R.get());
    return R;
  };
  m->assemble_jacobian(A.get()); // searched, offsets recorded
  EXPECT_FALSE(m->last_jacobian_replayed());
  PetscMat searched = copy_of(A.get());
  m->assemble_jacobian(A.get()); // replayed
  EXPECT_TRUE(m->last_jacobian_replayed());
  PetscMat reference = petsc_jacobian();
  EXPECT_LE(relative_difference(searched.get(), reference.get()), 1e-14);
  EXPECT_LE(relative_difference(A.get(), reference.get()), 1e-14);
  // A new displacement: the replay writes the new values where PETSc does.
  A.reset();
  A = PetscMat(m->create_matrix());
  m->assemble_jacobian(A.get());
  fixtures::perturb(*m, 3e-3, 2);
  m->assemble_jacobian(A.get());
  EXPECT_TRUE(m->last_jacobian_replayed());
  reference = petsc_jacobian();
  EXPECT_LE(relative_difference(A.get(), reference.get()), 1e-14);
  EXPECT_GT(frobenius(reference.get()), 0.0);
}

INSTANTIATE_TEST_SUITE_P(P1AndP2, FastJacobian, ::testing::Values(1, 2));

// A matrix whose pattern changed after recording, or a matrix that is not
// 3x3-blocked, is never written through the recorded offsets.
TEST(BlockCsrAdder, RefusesChangedOrUnblockedPatterns)
{
  PetscMat owner;
  PETSC_CHECK(MatCreateSeqAIJ(PETSC_COMM_SELF, 6, 6, 6, nullptr, owner.out()));
  Mat A = owner.get();
  for (PetscInt i = 0; i < 6; ++i)
    for (PetscInt j = 0; j < 3; ++j)
      PETSC_CHECK(MatSetValue(A, i, j, 1.0, INSERT_VALUES)); // blocks (0,0) and (1,0)
  PETSC_CHECK(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PETSC_CHECK(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  BlockCsrAdder adder(3);
  adder.record(A);
  ASSERT_TRUE(adder.matches(A));
  // Add an element block to (1, 0) and check the values.
  const std::vector<std::int32_t> rows = {1}, cols = {0};
  std::vector<PetscScalar> v(9);
  for (int k = 0; k < 9; ++k)
    v[k] = k;
  adder.begin(A);
  adder.add(rows, cols, v);
  EXPECT_THROW(adder.add(std::vector<std::int32_t>{0}, std::vector<std::int32_t>{1}, v),
               std::runtime_error); // block (0, 1) is not in the pattern
  adder.end(A);
  for (PetscInt a = 0; a < 3; ++a)
    for (PetscInt b = 0; b < 3; ++b)
    {
      PetscInt r = 3 + a, col = b;
      PetscScalar x;
      PETSC_CHECK(MatGetValues(A, 1, &r, 1, &col, &x));
      EXPECT_EQ(x, 1.0 + 3 * a + b);
    }
  // A new nonzero changes the pattern: the recorded offsets are stale.
  PETSC_CHECK(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  PETSC_CHECK(MatSetValue(A, 0, 5, 1.0, INSERT_VALUES));
  PETSC_CHECK(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PETSC_CHECK(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  EXPECT_FALSE(adder.matches(A));
  // Row 0 now has 4 entries, rows 1 and 2 three: not blocked, never usable.
  adder.record(A);
  EXPECT_FALSE(adder.matches(A));
}

// The replay of recorded offsets: the same calls with the same key add
// through the recorded offsets; a call that differs (order, rows or
// columns) is searched, values stay right, and the next assembly records
// afresh; no key, or a re-recorded pattern, never replays.
TEST(BlockCsrAdder, ReplaysOnlyTheRecordedSequence)
{
  PetscMat owner;
  PETSC_CHECK(MatCreateSeqAIJ(PETSC_COMM_SELF, 6, 6, 6, nullptr, owner.out()));
  Mat A = owner.get();
  for (PetscInt i = 0; i < 6; ++i)
    for (PetscInt j = 0; j < 6; ++j)
      PETSC_CHECK(MatSetValue(A, i, j, 0.0, INSERT_VALUES)); // all four 3x3 blocks
  PETSC_CHECK(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PETSC_CHECK(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  BlockCsrAdder adder(3);
  adder.record(A);
  ASSERT_TRUE(adder.matches(A));
  using Call = std::pair<std::vector<std::int32_t>, std::vector<PetscScalar>>; // nodes, values
  // One assembly: each call adds values (scaled by s) on rows = cols =
  // nodes; returns whether it was replayed and checks A against a dense sum.
  auto assemble = [&](const std::vector<Call>& calls, double s, const void* key)
  {
    PETSC_CHECK(MatZeroEntries(A));
    double dense[6][6] = {};
    adder.begin(A, key);
    for (const auto& [nodes, v] : calls)
    {
      std::vector<PetscScalar> w(v);
      for (auto& x : w)
        x *= s;
      adder.add(nodes, nodes, w);
      const std::size_t n = 3 * nodes.size();
      for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = 0; b < n; ++b)
          dense[3 * nodes[a / 3] + a % 3][3 * nodes[b / 3] + b % 3] += w[a * n + b];
    }
    adder.end(A);
    for (PetscInt i = 0; i < 6; ++i)
      for (PetscInt j = 0; j < 6; ++j)
      {
        PetscScalar x;
        PETSC_CHECK(MatGetValues(A, 1, &i, 1, &j, &x));
        EXPECT_EQ(x, dense[i][j]) << "entry (" << i << ", " << j << ")";
      }
    return adder.replayed();
  };
  std::vector<PetscScalar> v36(36), v9(9);
  for (int k = 0; k < 36; ++k)
    v36[k] = 1 + k;
  for (int k = 0; k < 9; ++k)
    v9[k] = 100 + k;
  const std::vector<Call> calls = {{{0, 1}, v36}, {{1}, v9}};
  const std::vector<Call> swapped = {{{1, 0}, v36}, {{1}, v9}};
  const int key = 0, other = 0;
  EXPECT_FALSE(assemble(calls, 1.0, &key)); // records
  EXPECT_TRUE(assemble(calls, 2.0, &key));  // replays, new values
  EXPECT_TRUE(assemble(calls, 3.0, &key));
  EXPECT_FALSE(assemble(swapped, 1.0, &key)); // differs: searched
  EXPECT_FALSE(assemble(swapped, 1.0, &key)); // records afresh
  EXPECT_TRUE(assemble(swapped, 2.0, &key));
  EXPECT_FALSE(assemble({calls[0]}, 1.0, &key)); // first call differs
  EXPECT_FALSE(assemble({swapped[0]}, 1.0, &key)); // the recording was dropped
  EXPECT_TRUE(assemble({swapped[0]}, 1.0, &key));
  EXPECT_FALSE(assemble(swapped, 1.0, &key)); // more calls than recorded
  EXPECT_FALSE(assemble(calls, 1.0, &other)); // another key records
  EXPECT_TRUE(assemble(calls, 1.0, &other));
  EXPECT_FALSE(assemble(calls, 1.0, nullptr)); // no key: always searched
  adder.record(A);                              // a new recording of the pattern
  EXPECT_FALSE(assemble(calls, 1.0, &other));
  EXPECT_TRUE(assemble(calls, 1.0, &other));
}

TEST(InexactNewton, EisenstatWalkerForcing)
{
  const double g = 0.9, a = 0.5 * (1 + std::sqrt(5.0));
  // Fast residual decrease: the linear tolerance tightens with it.
  EXPECT_NEAR(eisenstat_walker_forcing(1e-3, 1e-1, 0.01, 1e-12, 1e-10, 0.5),
              g * std::pow(1e-2, a), 1e-15);
  // Slow decrease: loose, capped at eta_max.
  EXPECT_EQ(eisenstat_walker_forcing(0.9, 1.0, 0.5, 1e-12, 1e-10, 0.5), 0.5);
  // Safeguard: no sudden tightening after a loose solve (g eta_prev^a > 0.1).
  EXPECT_NEAR(eisenstat_walker_forcing(1e-4, 1.0, 0.4, 1e-12, 1e-10, 0.5), g * std::pow(0.4, a),
              1e-15);
  // Never tighter than needed to reach the Newton tolerance.
  EXPECT_NEAR(eisenstat_walker_forcing(1e-9, 1e-5, 1e-3, 1e-11, 1e-10, 0.5), 0.5e-2, 1e-15);
  // And never tighter than eta_min.
  EXPECT_EQ(eisenstat_walker_forcing(1e-12, 1.0, 1e-6, 0.0, 1e-10, 0.5), 1e-10);
  // Finishing step (residuals of the 194k-tet P1 standing solve, tol 2e-11):
  // |r| (|r| / |r_prev|)^2 = 6.8e-12 <= tol / 2, so the step is asked to reach
  // the tolerance (eta = tol / 2|r| = 5.0e-4) rather than Eisenstat-Walker's
  // 1.4e-3, which left |r| = 3.0e-11 and cost one more Newton iteration.
  EXPECT_NEAR(eisenstat_walker_forcing(1.99e-8, 1.077e-6, 0.041, 2e-11, 1e-8, 0.3),
              0.5 * 2e-11 / 1.99e-8, 1e-15);
  EXPECT_GT(g * std::pow(1.99e-8 / 1.077e-6, a), 2.5 * 0.5 * 2e-11 / 1.99e-8);
  // One step earlier the quadratic bound, 6.3e-9, is far above tol / 2:
  // Eisenstat-Walker as usual.
  EXPECT_NEAR(eisenstat_walker_forcing(1.077e-6, 1.406e-5, 0.15, 2e-11, 1e-8, 0.3),
              g * std::pow(1.077e-6 / 1.406e-5, a), 1e-15);
}

// Inexact and exact Newton reach the same equilibrium; the inexact method
// factorises less often (direct) and needs fewer Krylov iterations (AMG).
TEST(InexactNewton, SameEquilibriumAsExactNewtonWithFewerSetUps)
{
  auto c = fixtures::coarse_case();
  for (const std::string linear : {"direct", "amg"})
  {
    SCOPED_TRACE(linear);
    std::vector<double> u[2];
    int setups[2], krylov[2];
    for (int inexact = 0; inexact < 2; ++inexact)
    {
      auto m = fixtures::make_model(c);
      NewtonOptions o;
      o.linear = linear;
      o.inexact = inexact == 1;
      NewtonSolver newton(*m, o);
      const double f = set_gravity(*m, {0.0, 0.0, -9.81});
      auto rep = continuation(*m, newton, "load", 0.0, 1.0, LoadStepOptions{1.0}, "test", f);
      EXPECT_EQ(rep.failed_steps, 0);
      auto a = m->displacement()->x()->array();
      u[inexact].assign(a.begin(), a.end());
      setups[inexact] = newton.preconditioner_setups();
      krylov[inexact] = rep.linear_iterations;
      // Loose iterative solves never move the constrained dofs.
      EXPECT_EQ(max_abs_constrained(*m), 0.0);
    }
    const auto [diff, size] = fixtures::max_difference(u[1], u[0]);
    EXPECT_GT(size, 1e-3); // a real deformation (mm)
    EXPECT_LT(diff, 1e-8 * size);
    if (linear == "direct")
      EXPECT_LT(setups[1], setups[0]);
    else
      EXPECT_LT(krylov[1], krylov[0]);
  }
}

namespace
{
// The coarse case under gravity, solved by exact Newton (so that compared
// runs take the same Newton steps) with GMRES + AMG, the AMG settings as
// `amg` sets them: the displacement and the Krylov iterations.
std::pair<std::vector<double>, int> exact_amg_solve(const std::function<void(NewtonOptions&)>& amg)
{
  auto c = fixtures::coarse_case();
  auto m = fixtures::make_model(c);
  NewtonOptions o;
  o.linear = "amg";
  o.inexact = false;
  amg(o);
  NewtonSolver newton(*m, o);
  const double f = set_gravity(*m, {0.0, 0.0, -9.81});
  auto rep = continuation(*m, newton, "load", 0.0, 1.0, LoadStepOptions{1.0}, "test", f);
  EXPECT_EQ(rep.failed_steps, 0);
  auto a = m->displacement()->x()->array();
  return {std::vector<double>(a.begin(), a.end()), rep.linear_iterations};
}

// `better` reaches the same equilibrium as `baseline` (to 1e-8 relative) in
// strictly fewer Krylov iterations.
void expect_same_equilibrium_fewer_krylov(const std::function<void(NewtonOptions&)>& baseline,
                                          const std::function<void(NewtonOptions&)>& better)
{
  const auto [u0, krylov0] = exact_amg_solve(baseline);
  const auto [u1, krylov1] = exact_amg_solve(better);
  const auto [diff, size] = fixtures::max_difference(u1, u0);
  EXPECT_GT(size, 1e-3);
  EXPECT_LT(diff, 1e-8 * size);
  EXPECT_LT(krylov1, krylov0) << "Krylov iterations " << krylov1 << " against " << krylov0;
}
} // namespace

// The finest AMG level smoothed by one symmetric Gauss-Seidel sweep
// (solver.amg_fine_smoother = sor) instead of GAMG's Chebyshev/Jacobi
// (KRYLOV_SOR; the gain grows with the mesh: docs/PERFORMANCE.md).
TEST(Newton, SorOnTheFinestAmgLevelSameEquilibriumFewerKrylovIterations)
{
  expect_same_equilibrium_fewer_krylov([](NewtonOptions& o) { o.amg_fine_smoother = "chebyshev"; },
                                       [](NewtonOptions& o) { o.amg_fine_smoother = "sor"; });
}

// The W-cycle (solver.amg_cycle = w, the default) against the V-cycle
// (KRYLOV_W). GAMG builds three levels on this mesh, so the W-cycle's
// second visit to the middle level is what differs.
TEST(Newton, WCycleSameEquilibriumFewerKrylovIterations)
{
  expect_same_equilibrium_fewer_krylov([](NewtonOptions& o) { o.amg_cycle = "v"; },
                                       [](NewtonOptions& o) { o.amg_cycle = "w"; });
}

// A solve that reaches the tolerance exactly at its last allowed iteration
// has converged.
TEST(Newton, ConvergedAtTheLastAllowedIteration)
{
  auto c = fixtures::coarse_case();
  int needed = 0;
  for (int pass = 0; pass < 2; ++pass)
  {
    auto m = fixtures::make_model(c);
    NewtonOptions o;
    o.linear = "direct";
    if (pass == 1)
      o.max_iterations = needed;
    NewtonSolver newton(*m, o);
    const double f = set_gravity(*m, {0.0, 0.0, -9.81});
    m->set_parameter("load", {0.5});
    NewtonReport rep = newton.solve(f);
    ASSERT_TRUE(rep.converged) << rep.message;
    EXPECT_TRUE(rep.message.empty()) << rep.message;
    needed = rep.iterations;
  }
  EXPECT_GT(needed, 2);
}

// Every Newton iteration is recorded (NewtonReport::records): one record per
// iteration, the last one's |r| the final residual (below the tolerance),
// the Krylov counts adding up to the report's, accepted steps in (0, 1] and
// energies that never increase beyond round-off (the line search's rule).
TEST(Newton, RecordsEveryIteration)
{
  auto c = fixtures::coarse_case();
  for (const std::string linear : {"direct", "amg"})
  {
    SCOPED_TRACE(linear);
    auto m = fixtures::make_model(c);
    NewtonOptions o;
    o.linear = linear;
    NewtonSolver newton(*m, o);
    const double f = set_gravity(*m, {0.0, 0.0, -9.81});
    m->set_parameter("load", {0.5});
    const double e0 = m->energy();
    const NewtonReport rep = newton.solve(f);
    ASSERT_TRUE(rep.converged) << rep.message;
    ASSERT_GT(rep.iterations, 2);
    ASSERT_EQ(rep.records.size(), static_cast<std::size_t>(rep.iterations));
    EXPECT_GT(rep.initial_residual_norm, rep.tolerance);
    EXPECT_LE(rep.records.back().residual_norm, rep.tolerance);
    EXPECT_EQ(rep.records.back().residual_norm, rep.residual_norm);
    EXPECT_EQ(rep.records.back().energy, m->energy());
    int krylov = 0;
    double e_prev = e0;
    for (const NewtonRecord& r : rep.records)
    {
      krylov += r.linear_iterations;
      EXPECT_GT(r.step, 0.0);
      EXPECT_LE(r.step, 1.0);
      EXPECT_GE(r.eta, 1e-10);
      EXPECT_LE(r.eta, o.forcing_max);
      EXPECT_GE(r.seconds, 0.0);
      EXPECT_LE(r.energy, e_prev + 1e-12 * std::abs(e_prev));
      e_prev = r.energy;
    }
    EXPECT_EQ(krylov, rep.linear_iterations);
  }
}

// A load path keeps every Newton solve (LoadPathReport::solves), accepted
// and rejected, with the parameter value it solved at.
TEST(LoadStep, RecordsEveryNewtonSolveOfThePath)
{
  auto c = fixtures::coarse_case();
  auto m = fixtures::make_model(c);
  NewtonSolver newton(*m, NewtonOptions{});
  const double f = set_gravity(*m, {0.0, 0.0, -9.81});
  LoadStepOptions steps;
  steps.initial_step = 0.25;
  const LoadPathReport rep = continuation(*m, newton, "load", 0.0, 1.0, steps, "test", f);
  ASSERT_EQ(rep.solves.size(), static_cast<std::size_t>(rep.steps + rep.failed_steps));
  EXPECT_GE(rep.steps, 2);
  int newton_its = 0, krylov = 0, converged = 0;
  double last = 0;
  for (const PathSolve& s : rep.solves)
  {
    EXPECT_EQ(s.newton.records.size(), static_cast<std::size_t>(s.newton.iterations));
    newton_its += s.newton.iterations;
    krylov += s.newton.linear_iterations;
    converged += s.newton.converged ? 1 : 0;
    if (s.newton.converged)
    {
      EXPECT_GT(s.value, last);
      last = s.value;
    }
  }
  EXPECT_EQ(converged, rep.steps);
  EXPECT_EQ(newton_its, rep.newton_iterations);
  EXPECT_EQ(krylov, rep.linear_iterations);
  EXPECT_EQ(rep.solves.front().value, 0.25);
  EXPECT_EQ(rep.solves.back().value, 1.0);
  EXPECT_TRUE(rep.solves.back().newton.converged);
}

// `simulate` writes the records into summary.json ("newton_records", one
// entry per posture in the order of "postures", one object per iteration),
// and the posture objects keep exactly their keys.
TEST(Newton, RecordsInSummaryJson)
{
  namespace fs = std::filesystem;
  Config c = fixtures::coarse_case();
  c.set("postures.names", std::vector<std::string>{"standing", "supine"});
  const fs::path out = fs::temp_directory_path() / ("breastsim_newton_records_" + std::to_string(getpid()));
  fs::remove_all(out);
  const SimulationResult res = simulate(c, OutputTarget::claim(out.string(), {}, MPI_COMM_WORLD),
                                        MPI_COMM_WORLD);
  std::ifstream f(out / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(f);
  ASSERT_EQ(j["postures"].size(), 2u);
  ASSERT_EQ(j["newton_records"].size(), 2u);
  for (std::size_t p = 0; p < 2; ++p)
  {
    const auto& posture = j["postures"][p];
    std::set<std::string> keys;
    for (const auto& [k, v] : posture.items())
      keys.insert(k);
    EXPECT_EQ(keys, (std::set<std::string>{"base_perimeter_m", "coarse_level_newton_iterations",
                                           "coarse_newton_iterations", "coarse_start", "energy_J",
                                           "failed_load_steps", "linear_iterations", "load_steps",
                                           "min_det_F", "newton_iterations", "nipple_m", "posture",
                                           "projection_m", "theta_deg", "volume_m3", "wall_time_s",
                                           "z_max_m", "z_min_m"}));
    const auto& entry = j["newton_records"][p];
    EXPECT_EQ(entry["posture"], posture["posture"]);
    const auto& records = entry["records"];
    ASSERT_EQ(records.size(), posture["newton_iterations"].get<std::size_t>());
    const auto& last = records.back();
    EXPECT_EQ(last["load"].get<double>(), 1.0);
    EXPECT_LE(last["residual_norm_N"].get<double>(), res.postures[p].path.solves.back().newton.tolerance);
    // The solved half's energy; the observables report the full breast.
    EXPECT_NEAR(2 * last["model_energy_J"].get<double>(), posture["energy_J"].get<double>(),
                1e-12 * std::abs(posture["energy_J"].get<double>()));
    int krylov = 0;
    for (const auto& r : records)
    {
      for (const char* k : {"solve", "load", "iteration", "residual_norm_N", "model_energy_J", "step",
                            "linear_iterations", "eta", "wall_time_s"})
        EXPECT_TRUE(r.contains(k)) << k;
      krylov += r["linear_iterations"].get<int>();
    }
    EXPECT_EQ(krylov, posture["linear_iterations"].get<int>());
  }
  fs::remove_all(out);
}

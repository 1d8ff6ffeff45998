// SPDX-License-Identifier: LGPL-3.0-or-later
#include "output.hpp"
#include "errors.hpp"
#include "input_file.hpp"
#include "interrupt.hpp"
#include "log.hpp"
#include "on_root.hpp"
#include "safe_write.hpp"
#include <sys/stat.h>
#include <cerrno>
#include <cstring>
#include <dolfinx/io/VTKFile.h>
#include <fmt/format.h>
#include <dolfinx/io/XDMFFile.h>
#include <fstream>
#include <map>
#include <mutex>
#include <hdf5.h>
#include <unistd.h>

namespace breastsim
{
namespace fs = std::filesystem;

namespace
{
std::mutex g_stagings_mutex;
std::map<fs::path, fs::path> g_stagings; ///< staging folder -> the result folder it becomes

/// `file` as the user will find it: a file in a staging folder named by its
/// place in the result folder.
fs::path as_user_sees(const fs::path& file)
{
  std::lock_guard<std::mutex> lock(g_stagings_mutex);
  for (const auto& [staging, final] : g_stagings)
  {
    const fs::path rel = file.lexically_relative(staging);
    if (!rel.empty() && *rel.begin() != "..")
      return rel == "." ? final : final / rel;
  }
  return file;
}

/// The message for a failed write of `file` with error `err` (errno): the
/// device is full, the file is larger than the file-size limit, or `what`.
std::string write_failure(const fs::path& file, int err, const std::string& what)
{
  std::error_code ec;
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  const auto space = fs::space(dir, ec);
  const std::string shown = as_user_sees(file).string();
  if (err == ENOSPC || err == EDQUOT || (!ec && space.available < (1u << 20)))
    return fmt::format("cannot write '{}': no space left on device ({} bytes free)", shown,
                       ec ? 0 : space.available);
  if (err == EFBIG)
    return fmt::format("cannot write '{}': File too large (beyond the file-size limit, ulimit -f)",
                       shown);
  return fmt::format("cannot write '{}': {}", shown, what);
}
} // namespace

OutputDir::OutputDir(const OutputTarget& target, MPI_Comm comm)
    : _final(target.path()), _rules(target.rules()), _comm(comm)
{
  long pid = rank_of(comm) == 0 ? static_cast<long>(getpid()) : 0;
  MPI_Bcast(&pid, 1, MPI_LONG, 0, comm);
  _staging = staging_path(_final, pid);
  on_root(comm,
          [&]
          {
            // mkdir, not create_directories: fails on anything of that name, a link included
            if (::mkdir(_staging.c_str(), 0755) != 0)
            {
              const int err = errno;
              throw InputError(fmt::format(
                  "refusing to write the result into '{}': {}", _final.string(),
                  err == EEXIST ? fmt::format("'{}' beside it is in the way (breastsim builds its "
                                              "result there while it runs; move it away)",
                                              _staging.filename().string())
                                : fmt::format("cannot create a folder in '{}': {}",
                                              _final.parent_path().string(), std::strerror(err))));
            }
            interrupt::register_path(_staging);
            {
              std::lock_guard<std::mutex> lock(g_stagings_mutex);
              g_stagings[_staging] = _final;
            }
            write_marker(_staging, "staging");
          });
}

OutputDir::~OutputDir()
{
  {
    std::lock_guard<std::mutex> lock(g_stagings_mutex);
    g_stagings.erase(_staging);
  }
  int finalized = 0;
  MPI_Finalized(&finalized);
  const int rank = finalized ? 0 : rank_of(_comm);
  if (!_committed && rank == 0)
  {
    std::error_code ec;
    fs::remove_all(_staging, ec);
    interrupt::unregister_path(_staging);
  }
}

void OutputDir::commit()
{
  MPI_Barrier(_comm);
  on_root(_comm,
          [&]
          {
            if (auto why = refusal_reason(_final, _rules)) // changed during the run?
              throw InputError(*why + " (it changed during the run; the new result was discarded)");
            write_marker(_staging, "complete");
            const fs::path old = _final.parent_path() / (_final.filename().string() + ".old-"
                                                         + std::to_string(getpid()));
            const bool had_old = fs::exists(fs::symlink_status(_final));
            if (fs::exists(fs::symlink_status(old)))
              throw InputError(fmt::format("refusing to replace '{}': '{}' beside it is in the way "
                                           "(move it away)",
                                           _final.string(), old.filename().string()));
            if (had_old)
            {
              interrupt::register_path(old);
              fs::rename(_final, old);
            }
            fs::rename(_staging, _final);
            interrupt::unregister_path(_staging);
            if (had_old)
            {
              fs::remove_all(old);
              interrupt::unregister_path(old);
            }
          });
  _committed = true;
  MPI_Barrier(_comm);
}

void OutputDir::commit_files()
{
  MPI_Barrier(_comm);
  on_root(_comm,
          [&]
          {
            if (auto why = refusal_reason(_final, _rules)) // changed meanwhile?
              throw InputError(*why);
            std::vector<fs::path> staged; // relative paths of the staged files
            for (const auto& e : fs::recursive_directory_iterator(_staging))
              if (e.is_regular_file() && e.path().filename() != result_marker)
                staged.push_back(e.path().lexically_relative(_staging));
            auto in_the_way = [&](const fs::path& rel, bool folder)
            {
              const auto st = fs::symlink_status(_final / rel);
              return fs::exists(st) && !(folder ? fs::is_directory(st) : fs::is_regular_file(st));
            };
            for (const auto& rel : staged) // all checked before anything moves
              for (fs::path p = rel; !p.empty(); p = p.parent_path())
                if (in_the_way(p, p != rel))
                  throw InputError(fmt::format("refusing to write '{}': it is {}",
                                               (_final / p).string(), entry_kind(_final / p)));
            for (const auto& rel : staged) // rename replaces the entry, never follows a link
            {
              fs::create_directories((_final / rel).parent_path());
              fs::rename(_staging / rel, _final / rel);
            }
            write_marker(_final, "complete");
          });
  MPI_Barrier(_comm);
}

void write_json(const fs::path& file, const nlohmann::json& j, MPI_Comm comm)
{
  write_text(file, j.dump(2) + "\n", comm);
}

void write_text(const fs::path& file, const std::string& text, MPI_Comm comm)
{
  on_root(comm,
          [&]
          {
            try
            {
              write_file_nofollow(file, text);
            }
            catch (const std::system_error& e)
            {
              throw std::runtime_error(write_failure(file, e.code().value(), e.code().message()));
            }
          });
}

void write_owned_json(const fs::path& file, nlohmann::json j, MPI_Comm comm)
{
  if (j.is_object())
    j["written_by"] = "breastsim";
  const fs::path tmp = file.parent_path() / ("." + file.filename().string() + ".partial-"
                                             + std::to_string(getpid()));
  // The temporary sibling is created new (O_EXCL, never through a link); a
  // failure names the file the user asked for, not the temporary one.
  on_root(comm,
          [&]
          {
            try
            {
              write_file_nofollow(tmp, j.dump(2) + "\n", Existing::refuse);
            }
            catch (const std::system_error& e)
            {
              if (e.code().value() == EEXIST || e.code().value() == ELOOP)
                throw InputError(fmt::format("cannot write '{}': '{}' beside it is in the way "
                                             "(breastsim writes there first; move it away)",
                                             file.string(), tmp.filename().string()));
              throw std::runtime_error(write_failure(file, e.code().value(), e.code().message()));
            }
            interrupt::register_path(tmp);
            std::error_code ec;
            fs::rename(tmp, file, ec);
            if (ec)
            {
              fs::remove(tmp, ec);
              interrupt::unregister_path(tmp);
              throw std::runtime_error(write_failure(file, ec.value(), ec.message()));
            }
            interrupt::unregister_path(tmp);
          });
}

void refresh_marker(const fs::path& dir, MPI_Comm comm)
{
  on_root(comm, [&] { write_marker(dir, "complete"); });
}

namespace
{
/// Collective. Whether dolfinx's XDMF writer can evaluate `u` at every
/// geometry node: it evaluates at each node in the last cell holding it, by
/// a pull-back (a Newton solve on a curved P2 cell) that fails where a
/// reference reset left a cell nearly folded at a node. Affine (P1) cells
/// always pass.
bool xdmf_can_evaluate(const dolfinx::fem::Function<T>& u)
{
  const auto& mesh = *u.function_space()->mesh();
  const auto& g = mesh.geometry();
  bool ok = true;
  if (g.cmap().degree() > 1)
  {
    const std::size_t n = g.x().size() / 3;
    std::vector<std::int32_t> cells(n, -1);
    const auto& dofmap = g.dofmap();
    for (std::int32_t c = 0; c < dofmap.num_nodes(); ++c)
      for (const std::int32_t node : dofmap.links(c))
        cells[node] = c;
    const std::size_t vs = u.function_space()->element()->value_size();
    std::vector<T> values(n * vs);
    try
    {
      u.eval(g.x(), {n, 3}, cells, values, {n, vs});
    }
    catch (const std::runtime_error&)
    {
      ok = false;
    }
  }
  bool all = ok;
  MPI_Allreduce(&ok, &all, 1, MPI_C_BOOL, MPI_LAND, mesh.comm());
  return all;
}
} // namespace

void write_fields(Model& model, const fs::path& stem, bool xdmf, bool vtk)
{
  auto u = model.displacement();
  auto mesh = model.mesh().mesh;
  fs::path file = stem.string() + ".h5";
  if (xdmf && !xdmf_can_evaluate(*u))
  {
    // Curved P2 cells that XDMF's node evaluation cannot pull back: the
    // native P2 VTK file carries the same field without evaluation.
    log::warn("{}: XDMF cannot evaluate the displacement at every node of this curved P2 mesh "
              "(dolfinx's pull-back fails on a strongly curved cell); written as VTK (native P2) "
              "instead",
              stem.filename().string());
    xdmf = false;
    vtk = true;
  }
  // HDF5 prints its error stack (HDF5-DIAG, dozens of lines) on a failed
  // write; breastsim reports the failure once, naming the file.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  try
  {
    if (xdmf)
    {
      dolfinx::io::XDMFFile f(mesh->comm(), stem.string() + ".xdmf", "w");
      f.write_mesh(*mesh);
      f.write_function(*u, 0.0);
    }
    file = stem.string() + ".pvd";
    if (vtk)
    {
      dolfinx::io::VTKFile f(mesh->comm(), file.string(), "w");
      f.write<T>({*u}, 0.0);
    }
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(write_failure(file, errno, e.what())); // errno of HDF5's failed write
  }
}

void write_mesh_xdmf(const TaggedDolfinxMesh& m, const fs::path& file)
{
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); // one message instead of HDF5's error stack
  try
  {
    dolfinx::io::XDMFFile f(m.mesh->comm(), file.string(), "w");
    f.write_mesh(*m.mesh);
    m.mesh->topology_mutable().create_connectivity(2, 3);
    f.write_meshtags(*m.facets, "/Xdmf/Domain/Grid[@Name='" + m.mesh->name + "']/Geometry");
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(write_failure(file, errno, e.what()));
  }
}
} // namespace breastsim

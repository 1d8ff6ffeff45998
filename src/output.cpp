#include "output.hpp"
#include <dolfinx/io/VTKFile.h>
#include <dolfinx/io/XDMFFile.h>
#include <fstream>
#include <unistd.h>

namespace breastsim
{
namespace fs = std::filesystem;

OutputDir::OutputDir(fs::path final_dir, MPI_Comm comm) : _final(std::move(final_dir)), _comm(comm)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  long pid = rank == 0 ? static_cast<long>(getpid()) : 0;
  MPI_Bcast(&pid, 1, MPI_LONG, 0, comm);
  _staging = _final.string() + ".partial-" + std::to_string(pid);
  if (rank == 0)
  {
    fs::remove_all(_staging);
    fs::create_directories(_staging);
  }
  MPI_Barrier(comm);
}

OutputDir::~OutputDir()
{
  int rank = 0;
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized)
    MPI_Comm_rank(_comm, &rank);
  if (!_committed && rank == 0)
  {
    std::error_code ec;
    fs::remove_all(_staging, ec);
  }
}

void OutputDir::commit()
{
  MPI_Barrier(_comm);
  int rank;
  MPI_Comm_rank(_comm, &rank);
  if (rank == 0)
  {
    fs::remove_all(_final);
    if (_final.has_parent_path())
      fs::create_directories(_final.parent_path());
    fs::rename(_staging, _final);
  }
  _committed = true;
  MPI_Barrier(_comm);
}

void write_json(const fs::path& file, const nlohmann::json& j, MPI_Comm comm)
{
  write_text(file, j.dump(2) + "\n", comm);
}

void write_text(const fs::path& file, const std::string& text, MPI_Comm comm)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
  {
    std::ofstream f(file);
    f << text;
    if (!f)
      throw std::runtime_error("cannot write " + file.string());
  }
}

void write_fields(Model& model, const fs::path& stem, bool xdmf, bool vtk)
{
  auto u = model.displacement();
  auto mesh = model.mesh().mesh;
  if (xdmf)
  {
    dolfinx::io::XDMFFile f(mesh->comm(), stem.string() + ".xdmf", "w");
    f.write_mesh(*mesh);
    f.write_function(*u, 0.0);
  }
  if (vtk)
  {
    dolfinx::io::VTKFile f(mesh->comm(), stem.string() + ".pvd", "w");
    f.write<T>({*u}, 0.0);
  }
}
} // namespace breastsim

// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim serve`: the surgeon's planning app (an HTTP server on this
// machine; docs/APP.md). The hidden `--run-job FOLDER` is how the server runs
// each job in a process of its own.
#include "app_server.hpp"
#include "errors.hpp"
#include "interrupt.hpp"
#include "job_runner.hpp"
#include "command.hpp"
#include <filesystem>
#include <memory>
#include <mpi.h>

namespace breastsim::cli
{
Command add_serve_command(CLI::App& root)
{
  struct Options
  {
    app::ServeOptions serve;
    std::string run_job;
  };
  auto o = std::make_shared<Options>();
  auto* sub = root.add_subcommand("serve", "the planning app: a web page and JSON API on this machine "
                                           "(http://127.0.0.1:8080/ by default; docs/APP.md)");
  auto* host = sub->add_option("--host", o->serve.host,
                               "address to listen on (default 127.0.0.1; other addresses only when given)");
  sub->add_option("--port", o->serve.port, "port (default 8080; 0: any free port, printed at start)");
  sub->add_option("--data", o->serve.data,
                  "folder of the jobs and their results (default results/serve; kept across restarts)");
  sub->add_option("--workers", o->serve.workers, "jobs solved at the same time (default 1, at most 16)");
  sub->add_option("--max-body", o->serve.max_body, "largest request body in bytes (default 1048576)");
  sub->add_option("--max-upload", o->serve.max_upload,
                  "largest scan file uploaded to the page in bytes (default 67108864)");
  sub->add_option("--run-job", o->run_job, "run one job of the server (internal)")->group("");
  return {sub, [o, host]()
          {
            if (!o->run_job.empty())
              return app::run_job(o->run_job);
            int size = 1;
            MPI_Comm_size(MPI_COMM_WORLD, &size);
            if (size != 1)
              throw InputError("breastsim serve runs as one process (not under mpirun -n " +
                               std::to_string(size) + ")");
            interrupt::ignore_broken_pipe(); // a browser that hung up must not stop the server
            o->serve.host_given = host->count() > 0;
            o->serve.program = std::filesystem::read_symlink("/proc/self/exe").string();
            return app::serve(o->serve);
          }};
}
} // namespace breastsim::cli

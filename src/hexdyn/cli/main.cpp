// hexdyn's entry point: the command line of cli/command.hpp, with this program's sweep.
//
// Built twice (src/CMakeLists.txt): `hexdyn`, which links no MPI and hands `hexdyn sweep` to
// `hexdyn-sweep` (exec, same arguments, same process), and `hexdyn-sweep`
// (HEXDYN_CLI_MPI), which runs the sweep over MPI (mpi/mpi_sweep.hpp). So run, validate,
// envelope and replay start without loading or initialising MPI.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>

#include "hexdyn/cli/command.hpp"
#include "hexdyn/process/launch.hpp"
#ifdef HEXDYN_CLI_MPI
#include "hexdyn/mpi/mpi_sweep.hpp"
#endif

namespace {

#ifdef HEXDYN_CLI_MPI
/// `hexdyn sweep`: the sweep over MPI. The output is checked against every input of the
/// sweep by run_sweep, before any work.
int sweep(const hexdyn::cli::Args& a) {
  return hexdyn::run_sweep({a.input, a.output, a.keep_runs, a.resume, a.verbose, a.progress_s});
}
#else
/// `hexdyn sweep ...`, its arguments checked: replaces this process by hexdyn-sweep with the
/// same arguments, found next to this program (the build tree) or in ../libexec/hexdyn/ (an
/// installation). Returns only when it cannot, with the exit status of an internal error.
int sweep(const hexdyn::cli::Args& a) {
  char self[4096];
  const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
  std::string dir = ".";
  if (n > 0) {
    self[n] = '\0';
    dir = std::string(self);
    dir = dir.substr(0, dir.find_last_of('/'));
  }
  std::string tried;
  for (const std::string& path : {dir + "/hexdyn-sweep", dir + "/../libexec/hexdyn/hexdyn-sweep"}) {
    ::execv(path.c_str(), a.argv);
    tried += (tried.empty() ? "" : ", ") + path + " (" + std::strerror(errno) + ")";
  }
  if (!hexdyn::launched_as_secondary_rank())
    std::cerr << "hexdyn: internal error: sweep: cannot start hexdyn-sweep: " << tried << "\n";
  return 4;
}
#endif

}  // namespace

int main(int argc, char** argv) { return hexdyn::cli::main(argc, argv, {sweep}); }

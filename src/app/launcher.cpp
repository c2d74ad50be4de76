// The `covcontact` command as the user starts it: a launcher that puts the OpenMP settings of a
// run and the BLAS kernels (app/openmp_environment.hpp, app/blas_environment.hpp) into the
// environment and then executes the program,
// covcontact-engine beside it, in its own place (same process, same arguments).
// Why a launcher: libgomp reads those settings only when it is loaded, so the program used to
// re-execute itself with them set. It links ~140 shared libraries (gmsh brings OpenCASCADE,
// FLTK, X11, image and network libraries), and their symbol relocation costs ~0.15 s CPU per
// start: every run started twice (a small deck: 0.40 s against 0.22 s). This launcher links
// only the C++ runtime. It does not validate the command line; the program does.
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include "app/blas_environment.hpp"
#include "app/openmp_environment.hpp"

namespace {

// `--threads N` or `--threads=N` of a `run` command line; 0 when absent or not a whole number
// from 1 (the program then reports it).
int requestedThreads(int argc, char** argv) {
  int threads = 0;
  for (int i = 2; i < argc; ++i) {
    const std::string_view argument = argv[i];
    const char* value = nullptr;
    if (argument == "--threads" && i + 1 < argc) value = argv[i + 1];
    if (argument.starts_with("--threads=")) value = argv[i] + std::strlen("--threads=");
    if (!value) continue;
    char* end = nullptr;
    const long parsed = std::strtol(value, &end, 10);
    threads = end != value && *end == '\0' && parsed >= 1 && parsed <= INT_MAX
                  ? static_cast<int>(parsed)
                  : 0;
  }
  return threads;
}

std::string enginePath(const char* argv0) {
  char self[PATH_MAX];
  const ssize_t length = readlink("/proc/self/exe", self, sizeof self - 1);
  std::string path = length > 0 ? std::string(self, static_cast<std::size_t>(length)) : argv0;
  const std::size_t slash = path.rfind('/');
  return (slash == std::string::npos ? std::string() : path.substr(0, slash + 1)) +
         "covcontact-engine";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string_view(argv[1]) == "run") {
    cc::app::setOpenMpEnvironment(cc::app::runThreads(requestedThreads(argc, argv)));
  }
  cc::app::setBlasEnvironment();  // every command: check and compare load OpenBLAS too
  const std::string engine = enginePath(argv[0]);
  execv(engine.c_str(), argv);
  std::fprintf(stderr, "covcontact: cannot start the program %s: %s\n", engine.c_str(),
               std::strerror(errno));
  return 70;  // internal error (an incomplete installation)
}

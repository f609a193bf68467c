// SPDX-License-Identifier: MIT
#include "frictopt/linalg/blas_threads.hpp"

#include <dirent.h>
#include <dlfcn.h>
#include <limits.h>
#include <sched.h>
#include <stdlib.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "frictopt/core/error.hpp"

namespace frictopt::linalg {

namespace {

// OpenBLAS' thread control, looked up at run time: the BLAS is chosen by the system's
// alternatives (libblas.so.3 may be OpenBLAS, the reference BLAS or ATLAS), so linking against
// openblas_set_num_threads would tie the binary to one of them.
using SetThreads = void (*)(int);
using GetThreads = int (*)();

struct BlasControl {
  SetThreads set = nullptr;
  GetThreads get = nullptr;
  int max_threads = 1;  // the BLAS' count before we change anything (OpenBLAS: the cores)
  BlasThreadMode mode = BlasThreadMode::kUnavailable;
  int fixed_threads = 0;
};

BlasThreadMode mode_from_environment(int& fixed) {
  if (const char* v = std::getenv("FRICTOPT_BLAS_THREADS")) {
    const std::string s(v);
    if (s == "auto") return BlasThreadMode::kAutomatic;
    char* end = nullptr;
    const long n = std::strtol(v, &end, 10);
    if (s.empty() || *end != '\0' || n < 1 || n > 4096)
      throw InvalidInput("environment variable FRICTOPT_BLAS_THREADS = '" + s +
                         "'; expected 'auto' or an integer number of threads >= 1");
    fixed = static_cast<int>(n);
    return BlasThreadMode::kFixed;
  }
  for (const char* name : {"OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS"})
    if (std::getenv(name) != nullptr) return BlasThreadMode::kUser;
  return BlasThreadMode::kAutomatic;
}

const BlasControl& control() {
  static const BlasControl c = [] {
    BlasControl b;
    b.set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    b.get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    int fixed = 0;
    const BlasThreadMode requested = mode_from_environment(fixed);  // validated even without OpenBLAS
    if (b.set == nullptr || b.get == nullptr) return b;
    b.max_threads = std::max(1, b.get());
    b.mode = requested;
    b.fixed_threads = fixed;
    return b;
  }();
  return c;
}

// procs_running of /proc/stat: runnable threads of the whole system, this one included.
int system_running_threads() {
  std::ifstream in("/proc/stat");
  std::string key;
  long value = 0;
  while (in >> key) {
    if (key == "procs_running" && in >> value) return static_cast<int>(value);
    in.ignore(1 << 20, '\n');
  }
  return -1;
}

// Running threads of this process (state R in /proc/self/task/*/stat): OpenBLAS workers still
// spinning after the previous call count here, not as another process' load.
int own_running_threads() {
  DIR* dir = opendir("/proc/self/task");
  if (dir == nullptr) return -1;
  int running = 0;
  while (const dirent* e = readdir(dir)) {
    if (e->d_name[0] == '.') continue;
    std::ifstream stat(std::string("/proc/self/task/") + e->d_name + "/stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    const auto close = line.rfind(')');  // the command name may contain spaces
    if (close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'R') ++running;
  }
  closedir(dir);
  return running;
}

}  // namespace

int choose_blas_threads(double flops, int max_threads, int idle_cores, BlasThreadMode mode, int fixed_threads) {
  max_threads = std::max(1, max_threads);
  switch (mode) {
    case BlasThreadMode::kFixed: return std::clamp(fixed_threads, 1, max_threads);
    case BlasThreadMode::kUser:
    case BlasThreadMode::kUnavailable: return max_threads;
    case BlasThreadMode::kAutomatic: break;
  }
  if (!(flops >= kMinFlopsForThreads)) return 1;
  // Unknown load (no /proc): stay on one thread, which costs at most the parallel speed-up;
  // a guess of "idle" could cost a multiple (the measurement in the header comment).
  if (idle_cores < 0) return 1;
  return std::clamp(idle_cores, 1, max_threads);
}

int idle_cores_now() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) != 0) return -1;
  const int usable = CPU_COUNT(&set);
  const int all = system_running_threads();
  const int own = own_running_threads();
  if (all < 0 || own < 0) return -1;
  // `own` includes the calling thread, which /proc/stat counts as well.
  return std::max(0, usable - std::max(0, all - own));
}

BlasThreadMode blas_thread_mode() { return control().mode; }

std::string describe_blas_threads() {
  const BlasControl& c = control();
  std::ostringstream s;
  s << "BLAS threads: ";
  switch (c.mode) {
    case BlasThreadMode::kAutomatic: s << "automatic (max " << c.max_threads << ")"; break;
    case BlasThreadMode::kFixed: s << "FRICTOPT_BLAS_THREADS = " << c.fixed_threads << " (max " << c.max_threads << ")"; break;
    case BlasThreadMode::kUser: s << "set by OPENBLAS_NUM_THREADS/OMP_NUM_THREADS (" << c.max_threads << ")"; break;
    case BlasThreadMode::kUnavailable: s << "not controllable (the BLAS is not OpenBLAS)"; break;
  }
  return s.str();
}

std::string library_of_symbol(const char* symbol) {
  // RTLD_DEFAULT searches the caller's lookup scope: the global scope of an executable, and for
  // a module loaded with dlopen(RTLD_LOCAL) (the Python module) also the module's own
  // dependencies, the scope its CHOLMOD is bound in.
  void* address = dlsym(RTLD_DEFAULT, symbol);
  if (address == nullptr) return {};
  Dl_info info{};
  if (dladdr(address, &info) == 0 || info.dli_fname == nullptr) return {};
  // The file itself, not the alternatives' link the loader opened (libblas.so.3 and
  // libopenblas.so.0 name different implementations on different machines).
  char resolved[PATH_MAX];
  if (realpath(info.dli_fname, resolved) != nullptr) return resolved;
  return info.dli_fname;
}

bool LoadedBlas::is_openblas() const {
  return implementation.rfind("OpenBLAS", 0) == 0 && dgemm_library.find("openblas") != std::string::npos;
}

LoadedBlas loaded_blas() {
  using GetConfig = const char* (*)();
  LoadedBlas b;
  const auto config = reinterpret_cast<GetConfig>(dlsym(RTLD_DEFAULT, "openblas_get_config"));
  const char* text = config != nullptr ? config() : nullptr;
  b.implementation = text != nullptr ? std::string(text) : std::string("unknown");
  // OpenBLAS' config string ends with a blank on some builds.
  while (!b.implementation.empty() && b.implementation.back() == ' ') b.implementation.pop_back();
  b.dgemm_library = library_of_symbol("dgemm_");
  return b;
}

std::string describe_loaded_blas() {
  const LoadedBlas b = loaded_blas();
  return b.implementation + " (dgemm_ from " + (b.dgemm_library.empty() ? "nowhere" : b.dgemm_library) + ")";
}

BlasThreadsForCall::BlasThreadsForCall(double flops) {
  const BlasControl& c = control();
  if (c.mode == BlasThreadMode::kUser || c.mode == BlasThreadMode::kUnavailable) return;
  const int idle = c.mode == BlasThreadMode::kAutomatic && flops >= kMinFlopsForThreads ? idle_cores_now() : 0;
  threads_ = choose_blas_threads(flops, c.max_threads, idle, c.mode, c.fixed_threads);
  // Set only on a change, and never restored afterwards: every openblas_set_num_threads call
  // wakes OpenBLAS' workers, which then spin (sched_yield) before sleeping again. Restoring the
  // previous count after each call did that twice per call: 104k sched_yield calls in one demo
  // solve against 8.9k with a constant count (strace -c -f, docs/benchmarks.md §2b).
  if (threads_ != c.get()) c.set(threads_);
}

}  // namespace frictopt::linalg

#include "pss/backend/backend.hpp"

#include <omp.h>

#include "pss/core/error.hpp"

namespace pss {

Backend select_backend(std::string_view choice) {
  if (choice == "cpu") return Backend::cpu;
  if (choice == "auto") return cuda::built() && cuda::device_count() > 0 ? Backend::cuda : Backend::cpu;
  if (choice == "cuda") {
    if (!cuda::built()) cuda_not_built("--backend cuda");
    if (cuda::device_count() == 0) throw Error("--backend cuda: no CUDA device found");
    return Backend::cuda;
  }
  throw Error("--backend: unknown backend " + quote(choice) + " (expected cpu, cuda or auto)");
}

const char* backend_name(Backend backend) { return backend == Backend::cuda ? "cuda" : "cpu"; }

void cuda_not_built(std::string_view what) {
  throw Error(std::string(what) + ": this pss was built without CUDA (nvcc was not found)");
}

#if !PSS_HAVE_CUDA
namespace cuda {
bool built() { return false; }
int device_count() { return 0; }
std::string device_name() { return "none"; }
void use_device(int) {}
}  // namespace cuda
#endif

void set_cpu_threads(int threads) {
  if (threads > 0) omp_set_num_threads(threads);
}

int cpu_threads() { return omp_get_max_threads(); }

}  // namespace pss

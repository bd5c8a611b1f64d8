// Which backend runs the kernels. The same host+device functions run on either.
#pragma once

#include <string>
#include <string_view>

namespace pss {

enum class Backend { cpu, cuda };

// "cpu", "cuda" or "auto" (CUDA when this build has it and a device is present). Asking for
// cuda where it cannot run is an Error naming why.
Backend select_backend(std::string_view choice);
const char* backend_name(Backend backend);

// Threads of the CPU backend; 0 keeps OpenMP's default (all cores).
void set_cpu_threads(int threads);
int cpu_threads();

namespace cuda {
bool built();          // this binary has the CUDA backend
int device_count();    // 0 without a driver or device
std::string device_name();
}  // namespace cuda

}  // namespace pss

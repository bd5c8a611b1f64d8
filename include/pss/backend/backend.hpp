// Which backend runs the kernels. The same host+device functions run on either.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace pss {

enum class Backend { cpu, cuda };

// "cpu", "cuda" or "auto" (CUDA when this build has it and a device is present). Asking for
// cuda where it cannot run is an Error naming why.
Backend select_backend(std::string_view choice);
const char* backend_name(Backend backend);

// The most threads set_cpu_threads takes. Each OpenMP thread is a system thread with its own
// stack: 100000 of them exhaust libgomp's stacks and crash. More threads than cores only add
// overhead, and 1024 is more than the cores of any one shared-memory machine pss runs on.
inline constexpr int kMaxCpuThreads = 1024;

// Threads of the CPU backend; 0 keeps OpenMP's default (all cores).
void set_cpu_threads(int threads);
int cpu_threads();

namespace cuda {
bool built();          // this binary has the CUDA backend
int device_count();    // 0 without a driver or device
std::string device_name();  // this thread's device's
// Makes the `index`-th device (modulo those found) this thread's for its CUDA work from now
// on: each rank on a machine its own GPU (apps/pss/ranks). Nothing without CUDA or a device.
void use_device(int index);

#if PSS_HAVE_CUDA
// Device memory for Mirror (mirror.hpp); each failure is an Error naming the call. A
// CPU-only build has none: it never selects the CUDA backend.
void* allocate(std::size_t bytes);  // zeroed
void release(void* device) noexcept;
void upload(void* device, const void* host, std::size_t bytes);
void download(void* host, const void* device, std::size_t bytes);
#endif
}  // namespace cuda

// The one place a CPU-only build says it cannot run `what` on the GPU.
[[noreturn]] void cuda_not_built(std::string_view what);

}  // namespace pss

// An array as the kernels of one backend see it. On the CPU a Mirror of host data is that
// data (no copy) and an output Mirror is a host vector; on the GPU both live in device
// memory, uploaded once and copied back by take(). Code around a kernel is written once
// against data().
#pragma once

#include <cstddef>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "pss/backend/backend.hpp"

namespace pss {

template <class T>
class Mirror {
  static_assert(std::is_trivially_copyable_v<T>, "kernels copy their arrays bytewise");

 public:
  // What the kernels read: `host` must outlive the Mirror on the CPU.
  Mirror(Backend backend, std::span<const T> host) : backend_(backend), size_(host.size()) {
    if (backend_ == Backend::cpu) {
      data_ = const_cast<T*>(host.data());  // read only: data() is const for inputs by convention
      return;
    }
    allocate_device();
#if PSS_HAVE_CUDA
    if (size_) cuda::upload(data_, host.data(), bytes());
#endif
  }
  // What the kernels write: n zeroed elements.
  Mirror(Backend backend, std::size_t n) : backend_(backend), size_(n) {
    if (backend_ == Backend::cpu) {
      owned_.resize(n);
      data_ = owned_.data();
      return;
    }
    allocate_device();
  }
  ~Mirror() {
#if PSS_HAVE_CUDA
    if (backend_ == Backend::cuda && data_) cuda::release(data_);
#endif
  }
  Mirror(Mirror&& other) noexcept
      : backend_(other.backend_), size_(other.size_), data_(std::exchange(other.data_, nullptr)),
        owned_(std::move(other.owned_)) {}
  Mirror& operator=(Mirror&&) = delete;
  Mirror(const Mirror&) = delete;
  Mirror& operator=(const Mirror&) = delete;

  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }

  // The contents on the host: the CPU's own vector (moved out, no copy), or a download.
  std::vector<T> take() {
    if (backend_ == Backend::cpu) {
      if (owned_.size() != size_) owned_.assign(data_, data_ + size_);  // a Mirror of input data
      data_ = nullptr;
      return std::move(owned_);
    }
    std::vector<T> host(size_);
#if PSS_HAVE_CUDA
    if (size_) cuda::download(host.data(), data_, bytes());
#endif
    return host;
  }

 private:
  std::size_t bytes() const { return size_ * sizeof(T); }
  void allocate_device() {
#if PSS_HAVE_CUDA
    if (size_) data_ = static_cast<T*>(cuda::allocate(bytes()));
#else
    cuda_not_built("device memory");
#endif
  }

  Backend backend_;
  std::size_t size_;
  T* data_ = nullptr;
  std::vector<T> owned_;  // the CPU's output
};

}  // namespace pss

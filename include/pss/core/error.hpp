// Host-side errors. Kernels never throw: they return a status, and the host turns the
// problems of input files and parameters into one-line messages at the edges.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace pss {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "FILE: problem", the shape of every message about an input or output file.
inline Error file_error(const std::filesystem::path& file, const std::string& problem) {
  return Error(file.string() + ": " + problem);
}

}  // namespace pss

// Host-side errors. Kernels never throw: they return a status, and the host turns the
// problems of input files and parameters into one-line messages at the edges.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "pss/core/text.hpp"

namespace pss {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The longest file name a message shows: a path is what the user typed, so it is shown
// (nearly always) whole, but a message stays one bounded line.
inline constexpr std::size_t kPathBytes = 512;

// "FILE: problem", the shape of every message about an input or output file. The name is
// printable() (a newline in it cannot split the line); the problem quotes what it echoes.
inline Error file_error(const std::filesystem::path& file, const std::string& problem) {
  return Error(printable(file.string(), kPathBytes) + ": " + problem);
}

}  // namespace pss

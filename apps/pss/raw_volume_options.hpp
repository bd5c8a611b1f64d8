// The flags that describe a headerless raw volume (--dims, --type, --spacing, --endian,
// --skip), shared by `pss volume`, `pss extract` and `pss info`.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "pss/io/volume_file.hpp"

namespace pss::app {

struct RawVolumeOptions {
  std::string dims, type, spacing, endian, skip;  // empty: not given
};

void add_raw_volume_options(CLI::App& command, RawVolumeOptions& options);

// The raw format of `input` when any raw flag was given (and then --dims is required, and
// `input` must have no header), else nullopt (the file must then be a format with a header).
std::optional<RawVolumeFormat> raw_volume_format(const RawVolumeOptions& options, const std::string& input);

}  // namespace pss::app

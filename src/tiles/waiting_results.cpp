#include "pss/tiles/waiting_results.hpp"

#include <string>
#include <utility>

#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"

namespace pss {

WaitingResults::WaitingResults(std::filesystem::path folder) : folder_(std::move(folder)) {}

WaitingResults::~WaitingResults() = default;

void WaitingResults::put(std::size_t place, int rank, std::span<const std::byte> result,
                         std::span<const std::byte> notes) {
  if (!file_) file_ = std::make_unique<ScratchFile>(folder_);
  const Where at{end_, result.size(), notes.size(), rank};
  file_->write_at(at.offset, result.data(), result.size());
  file_->write_at(at.offset + at.result_size, notes.data(), notes.size());
  end_ += at.result_size + at.notes_size;
  where_[place] = at;
}

WaitingResults::Taken WaitingResults::take(std::size_t place) {
  const auto it = where_.find(place);
  if (it == where_.end()) throw Error("no result waits for tile " + std::to_string(place));
  const Where at = it->second;
  where_.erase(it);
  Taken out;
  out.rank = at.rank;
  out.result.resize(std::size_t(at.result_size));
  out.notes.resize(std::size_t(at.notes_size));
  file_->read_at(at.offset, out.result.data(), out.result.size());
  file_->read_at(at.offset + at.result_size, out.notes.data(), out.notes.size());
  if (where_.empty()) end_ = 0;  // what is written next overwrites what was read
  return out;
}

}  // namespace pss

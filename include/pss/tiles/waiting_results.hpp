// The results of tiles that come back before their turn (tiles/farm.hpp: a farm takes them in
// the tiles' order), kept in a scratch file rather than in memory: under mpirun every rank
// may run ahead of the oldest tile not yet back, and rank 0 would otherwise hold a result of
// each, however many ranks there are, beyond what `--memory` counts (issue 28).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <vector>

namespace pss {

class ScratchFile;

class WaitingResults {
 public:
  // The scratch file goes in `folder`, made at the first put and removed with this.
  explicit WaitingResults(std::filesystem::path folder);
  ~WaitingResults();
  WaitingResults(const WaitingResults&) = delete;
  WaitingResults& operator=(const WaitingResults&) = delete;

  // The result of the tile at `place` (in the order results are taken), worked on by `rank`.
  void put(std::size_t place, int rank, std::span<const std::byte> result, std::span<const std::byte> notes);
  bool holds(std::size_t place) const { return where_.count(place) > 0; }
  std::size_t size() const { return where_.size(); }

  struct Taken {
    std::vector<std::byte> result, notes;
    int rank = 0;
  };
  // The result put at `place`, no longer held. Throws Error where none is.
  Taken take(std::size_t place);

 private:
  struct Where {
    std::uint64_t offset = 0, result_size = 0, notes_size = 0;
    int rank = 0;
  };
  std::filesystem::path folder_;
  std::unique_ptr<ScratchFile> file_;
  std::map<std::size_t, Where> where_;
  std::uint64_t end_ = 0;  // where the next put writes; back to 0 whenever none is held
};

}  // namespace pss

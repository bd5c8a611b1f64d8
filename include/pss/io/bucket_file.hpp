// Records of one size sorted into buckets on disk (issue 28): a cloud larger than memory is
// cut into tiles this way, each tile a bucket of its points' records. The records go to a
// ScratchFile (removed with the BucketFile, on errors and on signals) in blocks, each
// bucket's blocks in the order its records came; a bucket is read back whole or a block at
// a time. Memory: one block of buffer a bucket and a few words a block written.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <span>
#include <vector>

#include "pss/io/output_file.hpp"

namespace pss {

class BucketFile {
 public:
  // `buckets` buckets of records of `record_bytes` bytes, in a scratch file in `folder`,
  // buffering at most `buffer_bytes` in all (each bucket's block at least one record).
  BucketFile(const std::filesystem::path& folder, int buckets, std::size_t record_bytes, std::size_t buffer_bytes);

  int buckets() const { return int(buffers_.size()); }
  std::size_t record_bytes() const { return record_bytes_; }
  std::uint64_t records(int bucket) const { return counts_[std::size_t(bucket)]; }

  // Adds a record (record_bytes bytes) at the end of `bucket`.
  void append(int bucket, const void* record);
  // Writes what the buffers hold and frees them (the appending is over).
  void flush();
  // Calls `block` with each block of the bucket's records in the order they were appended
  // (a span of whole records' bytes, valid during the call).
  void read(int bucket, const std::function<void(std::span<const char>)>& block) const;

  // f(record) for each of the bucket's records, read into a T (record_bytes() == sizeof(T)).
  template <class T, class F>
  void for_each_record(int bucket, F&& f) const {
    read(bucket, [&](std::span<const char> block) {
      for (std::size_t k = 0; k + sizeof(T) <= block.size(); k += sizeof(T)) {
        T record;
        std::memcpy(&record, block.data() + k, sizeof record);
        f(record);
      }
    });
  }

  const std::filesystem::path& path() const { return file_.path(); }

 private:
  void write_block(int bucket);

  struct Block {
    std::uint64_t offset, bytes;
  };
  ScratchFile file_;
  std::size_t record_bytes_, block_bytes_;
  std::vector<std::vector<char>> buffers_;
  std::vector<std::vector<Block>> blocks_;
  std::vector<std::uint64_t> counts_;
  std::uint64_t end_ = 0;  // the file's size
};

}  // namespace pss

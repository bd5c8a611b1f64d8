#include "pss/io/bucket_file.hpp"

#include <algorithm>
#include <cstring>

#include "pss/core/error.hpp"

namespace pss {

BucketFile::BucketFile(const std::filesystem::path& folder, int buckets, std::size_t record_bytes,
                       std::size_t buffer_bytes)
    : file_(folder),
      record_bytes_(record_bytes),
      block_bytes_(std::max<std::size_t>(1, buffer_bytes / std::max(1, buckets) / record_bytes) * record_bytes),
      buffers_(std::size_t(std::max(buckets, 0))),
      blocks_(buffers_.size()),
      counts_(buffers_.size(), 0) {
  if (buckets < 1 || record_bytes < 1) throw Error("a bucket file needs at least one bucket and a record size");
}

void BucketFile::append(int bucket, const void* record) {
  std::vector<char>& buffer = buffers_[std::size_t(bucket)];
  if (buffer.capacity() < block_bytes_) buffer.reserve(block_bytes_);
  const char* bytes = static_cast<const char*>(record);
  buffer.insert(buffer.end(), bytes, bytes + record_bytes_);
  ++counts_[std::size_t(bucket)];
  if (buffer.size() >= block_bytes_) write_block(bucket);
}

void BucketFile::write_block(int bucket) {
  std::vector<char>& buffer = buffers_[std::size_t(bucket)];
  if (buffer.empty()) return;
  file_.write_at(end_, buffer.data(), buffer.size());
  blocks_[std::size_t(bucket)].push_back({end_, buffer.size()});
  end_ += buffer.size();
  buffer.clear();
}

void BucketFile::flush() {
  for (int b = 0; b < buckets(); ++b) {
    write_block(b);
    std::vector<char>().swap(buffers_[std::size_t(b)]);  // a bucket read back needs no buffer
  }
}

void BucketFile::read(int bucket, const std::function<void(std::span<const char>)>& block) const {
  std::vector<char> bytes;
  for (const Block& b : blocks_[std::size_t(bucket)]) {
    bytes.resize(b.bytes);
    file_.read_at(b.offset, bytes.data(), bytes.size());
    block(bytes);
  }
  const std::vector<char>& buffered = buffers_[std::size_t(bucket)];
  if (!buffered.empty()) block(buffered);
}

}  // namespace pss

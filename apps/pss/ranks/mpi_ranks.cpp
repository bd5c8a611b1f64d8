// The ranks over Open MPI. Rank 0 reads and writes every file, and sends each tile's work
// (its points and its halo's) in a message, so that no rank needs a file system shared with
// it; the other ranks only compute (tile_work). Rank 0 works on tiles of its own beside the
// messages (MpiFarm).
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <future>
#include <new>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/core/error.hpp"
#include "pss/tiles/memory_plan.hpp"
#include "pss/tiles/waiting_results.hpp"
#include "ranks.hpp"

namespace pss::app {

namespace {

enum Tag : int { kWork = 1, kStop = 2, kResult = 3 };

struct Ranks {
  bool joined = false, released = false;  // released: the other ranks let go
  int rank = 0, size = 1;
  int share = 1, all = 1;  // this rank's share of its machine's cores, and all of them
  int local = 0;           // its place among the ranks on its machine: its GPU's
};
Ranks world;

// What Open MPI's mpirun (or a PMIx launcher, as srun --mpi=pmix) sets in each rank's
// environment. A process started otherwise stays out of MPI: an MPI_Init of its own would
// start a runtime for one.
bool started_by_mpirun() { return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK"); }

// Bytes in pieces of at most 1 GiB: an MPI count is an int.
constexpr std::uint64_t kPiece = std::uint64_t(1) << 30;

void send_bytes(std::span<const std::byte> bytes, int to, int tag) {
  const std::uint64_t size = bytes.size();
  MPI_Send(&size, 1, MPI_UINT64_T, to, tag, MPI_COMM_WORLD);
  for (std::uint64_t at = 0; at < size; at += kPiece)
    MPI_Send(bytes.data() + at, int(std::min(kPiece, size - at)), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

// Where a message cannot be taken whole, the ranks' messages no longer pair up: every rank
// ends (mpirun's SIGTERM makes rank 0 remove its outputs and scratch files).
[[noreturn]] void end_every_rank(const std::string& why) {
  std::fprintf(stderr, "pss: error: rank %d: %s\n", world.rank, why.c_str());
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::abort();
}

std::vector<std::byte> receive_bytes(int from, int tag) {
  std::uint64_t size = 0;
  MPI_Recv(&size, 1, MPI_UINT64_T, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  std::vector<std::byte> bytes;
  try {
    bytes.resize(static_cast<std::size_t>(size));
  } catch (const std::exception&) {
    end_every_rank("out of memory for a message of " + std::to_string(size) + " bytes from rank " + std::to_string(from));
  }
  for (std::uint64_t at = 0; at < size; at += kPiece)
    MPI_Recv(bytes.data() + at, int(std::min(kPiece, size - at)), MPI_BYTE, from, tag, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
  return bytes;
}

// A rank's result: its bytes, or the one line of what went wrong there; and the tile's
// notes it was sent with (farm.hpp), given back.
struct Result {
  bool done = false;
  std::vector<std::byte> bytes, notes;
};

void send_result(const Result& result) {
  const int done = result.done;
  MPI_Send(&done, 1, MPI_INT, 0, kResult, MPI_COMM_WORLD);
  send_bytes(result.bytes, 0, kResult);
  send_bytes(result.notes, 0, kResult);
}

Result receive_result(int from) {
  int done = 0;
  MPI_Recv(&done, 1, MPI_INT, from, kResult, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  std::vector<std::byte> bytes = receive_bytes(from, kResult);
  return {done != 0, std::move(bytes), receive_bytes(from, kResult)};
}

std::vector<std::byte> text_bytes(const std::string& text) {
  const auto* p = reinterpret_cast<const std::byte*>(text.data());
  return {p, p + text.size()};
}

// A tile a rank at a time, each rank given its next as soon as it gives back its last, so
// that no rank waits for a slower tile than its own; rank 0 works on tiles of its own on a
// thread beside the messages. Results are taken in the tiles' order: one that comes back
// before its turn waits in the scratch folder (tiles/waiting_results.hpp), so that rank 0
// holds none in memory; at most kAhead tiles a rank run ahead of the oldest not yet taken.
class MpiFarm final : public TileFarm {
 public:
  int ranks() const override { return world.size; }

  void run(TileStep step, std::span<const int> tiles, const Request& request, const Take& take) override {
    // Rank 0's --threads, where given, for every rank; else each its own share (0).
    const int threads = cpu_threads() == world.share ? 0 : cpu_threads();
    const int own_threads = cpu_threads();
    const std::size_t n = tiles.size(), ahead = kAhead * std::size_t(world.size);
    std::vector<std::ptrdiff_t> at_rank(std::size_t(world.size), -1);  // each rank's tile: its place in `tiles`
    WaitingResults waiting(scratch_folder());
    std::future<Result> own;
    std::size_t next = 0, taken = 0;
    auto may_give = [&] { return next < n && next < taken + ahead; };
    try {
      while (taken < n) {
        for (int k = 1; k < world.size; ++k)
          if (at_rank[std::size_t(k)] < 0 && may_give()) {
            const TileRequest asked = request(tiles[next]);
            const int header[2] = {int(step), threads};
            MPI_Send(header, 2, MPI_INT, k, kWork, MPI_COMM_WORLD);
            send_bytes(asked.work, k, kWork);
            send_bytes(asked.notes, k, kWork);
            at_rank[std::size_t(k)] = std::ptrdiff_t(next++);
          }
        if (!own.valid() && may_give()) {
          at_rank[0] = std::ptrdiff_t(next++);
          TileRequest asked = request(tiles[std::size_t(at_rank[0])]);
          own = std::async(std::launch::async, [step, own_threads, asked = std::move(asked)]() mutable {
            set_cpu_threads(own_threads);  // a new thread starts from OpenMP's and CUDA's defaults
            cuda::use_device(world.local);
            return Result{true, tile_work(step, asked.work), std::move(asked.notes)};
          });
        }
        const Arrived arrived = wait_for_a_result(own, at_rank);  // the tile `taken` is in flight
        if (arrived.place != taken) {
          waiting.put(arrived.place, arrived.rank, arrived.result.bytes, arrived.result.notes);
          continue;
        }
        take(tiles[taken++], arrived.result.bytes, arrived.result.notes, arrived.rank);
        for (; waiting.holds(taken); ++taken) {
          const WaitingResults::Taken w = waiting.take(taken);
          take(tiles[taken], w.result, w.notes, w.rank);
        }
      }
    } catch (...) {
      if (own.valid()) own.wait();
      for (int k = 1; k < world.size; ++k)  // each rank free for the stop
        if (at_rank[std::size_t(k)] >= 0) receive_result(k);
      throw;
    }
  }

 private:
  static constexpr std::size_t kAhead = 2;
  struct Arrived {
    std::size_t place;  // in `tiles`
    int rank;
    Result result;
  };

  // Until rank 0's own tile is done or another rank's result comes.
  static Arrived wait_for_a_result(std::future<Result>& own, std::vector<std::ptrdiff_t>& at_rank) {
    for (;;) {
      if (own.valid() && own.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        const auto place = std::size_t(std::exchange(at_rank[0], -1));
        return {place, 0, own.get()};
      }
      int arrived = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, kResult, MPI_COMM_WORLD, &arrived, &status);
      if (arrived) {
        const int k = status.MPI_SOURCE;
        const auto place = std::size_t(std::exchange(at_rank[std::size_t(k)], -1));
        Result result = receive_result(k);
        if (!result.done)
          throw Error("rank " + std::to_string(k) + ": " +
                      std::string(reinterpret_cast<const char*>(result.bytes.data()), result.bytes.size()));
        return {place, k, std::move(result)};
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
};

MpiFarm farm;

}  // namespace

RankSession::RankSession(int& argc, char**& argv) {
  if (!started_by_mpirun()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);  // MPI from the main thread only
  world.joined = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &world.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world.size);
  MPI_Comm here;  // the ranks on this machine share its cores
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &here);
  int local = 1;
  MPI_Comm_size(here, &local);
  MPI_Comm_rank(here, &world.local);
  MPI_Comm_free(&here);
  world.all = cpu_threads();
  world.share = std::max(1, world.all / local);
  set_cpu_threads(world.share);
  cuda::use_device(world.local);
}

RankSession::~RankSession() {
  if (!world.joined) return;
  run_alone();
  MPI_Finalize();
}

void run_alone() {
  if (!world.joined || world.rank != 0 || world.released) return;
  const int header[2] = {0, 0};
  for (int k = 1; k < world.size; ++k) MPI_Send(header, 2, MPI_INT, k, kStop, MPI_COMM_WORLD);
  world.released = true;
  if (cpu_threads() == world.share) set_cpu_threads(world.all);  // not a --threads given
}

bool RankSession::serves() const { return world.rank > 0; }

int RankSession::serve() {
  for (;;) {
    int header[2] = {0, 0};
    MPI_Status status;
    MPI_Recv(header, 2, MPI_INT, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    if (status.MPI_TAG == kStop) return 0;
    const std::vector<std::byte> work = receive_bytes(0, kWork);
    std::vector<std::byte> notes = receive_bytes(0, kWork);
    set_cpu_threads(header[1] > 0 ? header[1] : world.share);
    Result result;
    try {
      result = {true, tile_work(TileStep(header[0]), work), {}};
    } catch (const std::bad_alloc&) {
      result = {false, text_bytes("out of memory"), {}};
    } catch (const std::exception& e) {
      result = {false, text_bytes(e.what()), {}};
    }
    result.notes = std::move(notes);
    send_result(result);
  }
}

int rank_count() { return world.size; }

TileFarm& rank_farm() { return world.size > 1 && !world.released ? static_cast<TileFarm&>(farm) : local_farm(); }

}  // namespace pss::app

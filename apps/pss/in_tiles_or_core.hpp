// `pss project` and `pss mesh` of a cloud: in core, or tile by tile where the cloud needs
// more than --memory or mpirun gives ranks to share it (issue 28, tiles/memory_plan.hpp).
#pragma once

#include <string>

#include "commands.hpp"
#include "pss/core/error.hpp"
#include "pss/core/stats.hpp"
#include "pss/core/text.hpp"
#include "pss/io/point_stream.hpp"
#include "pss/tiles/memory_plan.hpp"
#include "ranks/ranks.hpp"

namespace pss::app {

// Plans `input` within the budget `memory` (--memory) at `costs`: formats read whole (OBJ,
// STL, OFF, PCD) have no stream to tile and run in core; under mpirun a cloud that fits in
// core is tiled all the same, for the ranks to share. Runs `tiled(plan)` or `in_core()`.
// Where the tiles do not do what is asked (NotTiled), the cloud runs in core on rank 0
// alone, `stats` begun again, if the budget allows; else one line names the memory it needs
// in core. Returns the plan that ran.
template <class Tiled, class InCore>
MemoryPlan in_tiles_or_core(const std::string& input, const std::string& memory, const MemoryCosts& costs,
                            Stats& stats, const Tiled& tiled, const InCore& in_core) {
  MemoryPlan plan;
  plan.budget = memory_budget(memory);
  if (has_point_stream(input)) plan = plan_memory(input, plan.budget, costs);
  const MemoryPlan needed = plan;
  plan = spread_over_ranks(plan, rank_count());
  try {
    if (plan.tiled)
      tiled(plan);
    else
      in_core();
  } catch (const NotTiled& e) {
    if (needed.tiled)
      throw file_error(input, std::string(e.what()) + "; in core it needs about " +
                                  byte_size(double(plan.points * costs.in_core)) + " (--memory)");
    stats = Stats();
    plan = needed;
    run_alone();
    in_core();
  }
  return plan;
}

}  // namespace pss::app

// pss built without MPI: one process, whatever started it.
#include "ranks.hpp"

namespace pss::app {

RankSession::RankSession(int&, char**&) {}
RankSession::~RankSession() = default;
bool RankSession::serves() const { return false; }
int RankSession::serve() { return 0; }
void run_alone() {}
int rank_count() { return 1; }
TileFarm& rank_farm() { return local_farm(); }

}  // namespace pss::app

// The processes pss runs as (issue 28): this one alone, or the N that `mpirun -np N` started
// where pss is built with MPI. Rank 0 runs the command; the others work on its tiles
// (tiles/farm.hpp) until it lets them go.
#pragma once

#include "pss/tiles/farm.hpp"

namespace pss::app {

class RankSession {
 public:
  // Joins MPI where mpirun started pss (its environment says so), and gives each rank its
  // share of this machine's cores.
  RankSession(int& argc, char**& argv);
  ~RankSession();  // rank 0 lets the others go; every rank leaves MPI
  RankSession(const RankSession&) = delete;
  RankSession& operator=(const RankSession&) = delete;

  bool serves() const;  // a rank other than 0
  int serve();          // works on rank 0's tiles until it lets go; the exit status
};

int rank_count();       // 1 outside mpirun
TileFarm& rank_farm();  // every rank, from rank 0 (local_farm() when one, or once run_alone)
// On rank 0: lets the other ranks go, and takes all of this machine's cores unless --threads
// said otherwise; what follows is rank 0's alone (work that tiles do not do).
void run_alone();

}  // namespace pss::app

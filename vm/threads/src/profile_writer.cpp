// ThreadedMachine::writeProfile: the recorders' spans in the one profile format
// (support/profile_trace.hpp), one lane per worker thread.
#include <ostream>

#include "meldvm/threaded_machine.hpp"
#include "support/profile_trace.hpp"
#include "worker.hpp"

namespace meldvm {

void ThreadedMachine::writeProfile(std::ostream& out) const {
  std::vector<support::ProfileLane> lanes;
  for (unsigned t = 0; t < workers_.size(); ++t) {
    const threads::ProfileRecorder* r = workers_[t]->profile();
    lanes.push_back({"worker " + std::to_string(t), r ? &r->spans() : nullptr});
  }
  support::writeProfileTrace(out, "meld -j " + std::to_string(workers_.size()), lanes);
}

}  // namespace meldvm

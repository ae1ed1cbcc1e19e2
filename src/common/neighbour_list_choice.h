// Which of list_neighbours' two ways (neighbour_list.h) a CPU back end uses for the next step. Both give the same
// list, so the choice changes speed only, never a bit of the results: the back end times the way it
// uses, and every kProbeEvery steps tries the other for one step; it keeps whichever took less time per
// particle (an exponential average of each). A lattice at rest favours the branch, a splashing fluid the
// branch-free filter, and a run goes from one to the other.
#pragma once

#include <cstddef>

namespace sph {

class NeighbourListChoice {
 public:
  static constexpr long kProbeEvery = 32;

  // Whether the coming build should filter without a branch.
  bool branch_free() const {
    const bool probe = builds_ % kProbeEvery == kProbeEvery - 1 || seconds_[other()] < 0.0;
    return probe ? !best_branch_free() : best_branch_free();
  }
  // Records how long the build that branch_free() chose took for `particles` particles.
  void record(bool branch_free_used, double seconds, std::size_t particles) {
    ++builds_;
    if (particles == 0) return;
    const double per = seconds / double(particles);
    double& s = seconds_[branch_free_used ? 1 : 0];
    s = s < 0.0 ? per : 0.5 * s + 0.5 * per;
  }

 private:
  bool best_branch_free() const { return seconds_[1] >= 0.0 && (seconds_[0] < 0.0 || seconds_[1] < seconds_[0]); }
  int other() const { return best_branch_free() ? 0 : 1; }
  double seconds_[2] = {-1.0, -1.0};  // per particle: [0] with a branch, [1] branch-free; < 0 not yet timed
  long builds_ = 0;
};

}  // namespace sph

// Which of the two ways to filter the neighbour lists (neighbour_rows.h) a CPU back end uses for the next
// step. Both give the same list, so the choice changes speed only, never a bit of the results: the back
// end times the way it uses, and now and then tries the other for one step; it keeps whichever took less
// time per particle (an exponential average of each). A lattice at rest favours the branch, a splashing
// fluid the branch-free filter, and a run goes from one to the other.
//
// The other way is tried after kFirstProbe steps, then, each time it loses again, after twice as many (up
// to kLastProbe): a losing probe costs a step's lists at the slower way (about twice the time late in a
// dam break), which a probe every 32 steps paid in 3% of the run. When a probe wins, the choice flips and
// the interval starts again at kFirstProbe.
#pragma once

#include <cstddef>

namespace sph {

class NeighbourListChoice {
 public:
  static constexpr long kFirstProbe = 32;
  static constexpr long kLastProbe = 512;

  // Whether the coming build should filter without a branch.
  bool branch_free() const { return probing() ? !best_branch_free() : best_branch_free(); }

  // Records how long the build that branch_free() chose took for `particles` particles.
  void record(bool branch_free_used, double seconds, std::size_t particles) {
    const bool probe = probing();
    const bool best_before = best_branch_free();
    ++since_probe_;
    if (particles > 0) {
      const double per = seconds / double(particles);
      double& s = seconds_[branch_free_used ? 1 : 0];
      s = s < 0.0 ? per : 0.5 * s + 0.5 * per;
    }
    if (best_branch_free() != best_before) {  // the other way won a probe, or the way in use got slower
      interval_ = kFirstProbe;
      since_probe_ = 0;
    } else if (probe) {
      since_probe_ = 0;
      if (seconds_[0] >= 0.0 && seconds_[1] >= 0.0) interval_ = interval_ * 2 < kLastProbe ? interval_ * 2 : kLastProbe;
    }
  }

  long probe_interval() const { return interval_; }

 private:
  bool probing() const { return seconds_[other()] < 0.0 || since_probe_ + 1 >= interval_; }
  bool best_branch_free() const { return seconds_[1] >= 0.0 && (seconds_[0] < 0.0 || seconds_[1] < seconds_[0]); }
  int other() const { return best_branch_free() ? 0 : 1; }
  double seconds_[2] = {-1.0, -1.0};  // per particle: [0] with a branch, [1] branch-free; < 0 not yet timed
  long since_probe_ = 0;              // builds since the last probe
  long interval_ = kFirstProbe;       // builds from one probe to the next
};

}  // namespace sph

#include "dem/core/thread_governor.hpp"

#include <algorithm>

namespace dem {

void ThreadGovernor::start(int most) {
  most_ = base_ = current_ = most < 1 ? 1 : most;
  probing_ = held_ = false;
  hold_down_ = 2;  // the shares are balanced after 32 steps: their waits before that say little
  hold_up_ = 0;
  grow_down_ = grow_up_ = kStartHold;
  walls_.clear();
  walls_.reserve(kWindow);
}

void ThreadGovernor::hold_at(int threads) {
  base_ = current_ = std::clamp(threads, 1, most_);
  probing_ = false;
  held_ = true;
}

bool ThreadGovernor::add_step(double wall_seconds) {
  if (most_ == 1 || held_) return false;
  if (current_ < most_) ++steps_below_most_;
  walls_.push_back(wall_seconds);
  return static_cast<int>(walls_.size()) >= (probing_ ? kProbe : kWindow);
}

void ThreadGovernor::window_done(double wait_share) {
  std::nth_element(walls_.begin(), walls_.begin() + static_cast<std::ptrdiff_t>(walls_.size() / 2), walls_.end());
  const double median = walls_[walls_.size() / 2];
  walls_.clear();
  if (probing_) {  // keep the probe's threads if they made faster steps than the window before it
    probing_ = false;
    int& grow = probing_down_ ? grow_down_ : grow_up_;
    int& hold = probing_down_ ? hold_down_ : hold_up_;
    if (median < base_median_) {
      base_ = current_;
      base_median_ = median;
      grow_down_ = grow_up_ = kStartHold;
      hold_down_ = 0;
      hold_up_ = kStartHold;
    } else {
      current_ = base_;
      grow = std::min(kMaxHold, 4 * grow);
      hold = grow;
    }
    return;
  }
  base_median_ = median;
  hold_down_ = std::max(0, hold_down_ - 1);
  hold_up_ = std::max(0, hold_up_ - 1);
  if (base_ > 1 && hold_down_ == 0 && wait_share > kWaitShare) {
    probing_ = probing_down_ = true;
    current_ = std::max(1, base_ / 2);
  } else if (base_ < most_ && hold_up_ == 0) {
    probing_ = true;
    probing_down_ = false;
    current_ = std::min(most_, 2 * base_);
  }
  if (probing_) ++probes_;
}

}  // namespace dem

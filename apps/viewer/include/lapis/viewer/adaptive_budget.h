// Keeps an expensive display item (hair strands, glyphs) within a frame-time target by
// adapting how much of it is drawn: a software renderer's frame time grows with what is drawn,
// and a window that answers at one frame every two seconds is not usable. After a few slow
// frames the budget shrinks in proportion to the overshoot; after many fast ones it grows back
// towards full detail. A budget the user sets is pinned and left alone.
#pragma once

#include <algorithm>

namespace lapis::viewer {

struct AdaptiveBudgetOptions {
  double target_ms = 80;  // frame time aimed at (12 frames a second)
  long minimum = 20000;   // never below: the item must stay recognisable
  int slow_frames = 2;    // consecutive frames over 1.5× target before shrinking
  int fast_frames = 8;    // consecutive frames under 0.5× target before growing
  double growth = 1.5;
};

class AdaptiveBudget {
 public:
  explicit AdaptiveBudget(long initial, AdaptiveBudgetOptions options = {}) : value_(initial), options_(options) {}

  long value() const { return value_; }
  bool pinned() const { return pinned_; }
  void pin(long value) { value_ = value, pinned_ = true; }

  // One drawn frame's milliseconds; `full` is what drawing everything would take (the budget
  // never grows past it). Returns true when value() changed.
  bool observe(double frame_ms, long full) {
    if (pinned_) return false;
    slow_ = frame_ms > 1.5 * options_.target_ms ? slow_ + 1 : 0;
    fast_ = frame_ms < 0.5 * options_.target_ms ? fast_ + 1 : 0;
    const long before = value_;
    if (slow_ >= options_.slow_frames && value_ > options_.minimum) {
      value_ =
          std::max(options_.minimum, static_cast<long>(static_cast<double>(value_) * options_.target_ms / frame_ms));
      slow_ = 0;
    } else if (fast_ >= options_.fast_frames && value_ < full) {
      value_ = std::min(full, static_cast<long>(static_cast<double>(value_) * options_.growth));
      fast_ = 0;
    }
    return value_ != before;
  }

 private:
  long value_;
  AdaptiveBudgetOptions options_;
  bool pinned_ = false;
  int slow_ = 0, fast_ = 0;
};

}  // namespace lapis::viewer

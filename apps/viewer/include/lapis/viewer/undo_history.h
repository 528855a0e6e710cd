// Undo/redo by snapshots: the app pushes its whole editable state after each edit (a handle
// move, a brush stroke), undo() and redo() step through them. Snapshots are simple to get
// right and cheap when large parts are shared (keep big arrays behind shared_ptr<const>).
#pragma once

#include <cstddef>
#include <deque>
#include <string>
#include <utility>

namespace lapis::viewer {

template <class State>
class UndoHistory {
 public:
  // `initial` is the state before any edit; at most max_undo edits are kept.
  explicit UndoHistory(State initial, std::size_t max_undo = 200) : max_undo_(max_undo) {
    states_.push_back({std::move(initial), {}});
  }

  const State& current() const { return states_[index_].state; }

  // Records the state after an edit named `label`; forgets what could be redone.
  void push(State state, std::string label) {
    states_.erase(states_.begin() + static_cast<long>(index_) + 1, states_.end());
    states_.push_back({std::move(state), std::move(label)});
    ++index_;
    while (states_.size() > max_undo_ + 1) states_.pop_front(), --index_;
  }

  // Starts over from `state` (a new mesh was opened): nothing to undo or redo.
  void reset(State state) {
    states_.clear();
    states_.push_back({std::move(state), {}});
    index_ = 0;
  }

  bool can_undo() const { return index_ > 0; }
  bool can_redo() const { return index_ + 1 < states_.size(); }
  // Name of the edit undo() / redo() would revert / repeat ("" when none).
  const std::string& undo_label() const { return can_undo() ? states_[index_].label : empty_; }
  const std::string& redo_label() const { return can_redo() ? states_[index_ + 1].label : empty_; }

  // Steps back / forward and returns the state now current (unchanged when there is none).
  const State& undo() {
    if (can_undo()) --index_;
    return current();
  }
  const State& redo() {
    if (can_redo()) ++index_;
    return current();
  }

 private:
  struct Entry {
    State state;
    std::string label;  // the edit that produced this state
  };
  std::deque<Entry> states_;
  std::size_t index_ = 0;
  std::size_t max_undo_;
  std::string empty_;
};

}  // namespace lapis::viewer

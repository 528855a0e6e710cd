#include <doctest/doctest.h>

#include <string>

#include "lapis/viewer/undo_history.h"

using namespace lapis::viewer;

TEST_CASE("viewer: undo history steps back and forth and a new edit drops the redo branch") {
  UndoHistory<int> h(0);
  CHECK(!h.can_undo());
  CHECK(!h.can_redo());
  h.push(1, "one");
  h.push(2, "two");
  CHECK(h.undo_label() == "two");
  CHECK(h.undo() == 1);
  CHECK(h.redo_label() == "two");
  CHECK(h.undo() == 0);
  CHECK(h.undo() == 0);  // nothing more: stays
  CHECK(h.redo() == 1);
  h.push(5, "five");  // drops "two"
  CHECK(!h.can_redo());
  CHECK(h.current() == 5);
  CHECK(h.undo() == 1);
  CHECK(h.redo() == 5);
  h.reset(9);
  CHECK(h.current() == 9);
  CHECK(!h.can_undo());
}

TEST_CASE("viewer: undo history keeps at most max_undo edits") {
  UndoHistory<int> h(0, 3);
  for (int k = 1; k <= 10; ++k) h.push(k, std::to_string(k));
  int steps = 0;
  while (h.can_undo()) h.undo(), ++steps;
  CHECK(steps == 3);
  CHECK(h.current() == 7);
}

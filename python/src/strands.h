// Strands as NumPy arrays: a flat (n, 3) float32 points array plus per-strand offsets, the
// layout of .hair files.
#pragma once

#include <memory>
#include <vector>

#include "arrays.h"
#include "lapis/hair_sketch/growth.h"

namespace lapis::python {

// The storage of strands whose arrays Python has dropped, kept for the next regrowth to write
// into: a fresh allocation pays a page fault per 4 KB on first touch, which costs as much as
// the growth itself (hair_sketch::StrandGrower). Used with the GIL held.
class StrandPool {
 public:
  hair_sketch::Strands take();
  void give_back(hair_sketch::Strands strands);

 private:
  static constexpr size_t kKept = 2;  // the strands on screen and the ones being replaced
  std::vector<hair_sketch::Strands> free_;
};

// (points (n, 3) float32, offsets (strands + 1,) int32) viewing the moved strands: no copy.
// With a pool, the storage goes back to it once both arrays are gone.
py::tuple strands_to_numpy(hair_sketch::Strands&& strands, std::shared_ptr<StrandPool> pool = nullptr);

// points (n, 3) float32 and offsets (strands + 1,) int32/int64 from 0 to n, non-decreasing;
// copied.
hair_sketch::Strands strands_from_numpy(const py::handle& points, const py::handle& offsets);

}  // namespace lapis::python

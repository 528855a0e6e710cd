// The helper that faults a fresh array's pages in on another thread (solver/src/page_populate.h),
// and the factorization that uses it.
#include <doctest/doctest.h>

#include <sys/mman.h>
#include <unistd.h>

#include <cstring>
#include <vector>

#include "grid_matrices.h"
#include "lapis/solver/cholesky.h"
#include "page_populate.h"

using namespace lapis::solver;
using lapis::solver::detail::PagePopulator;

namespace {

// Fresh anonymous memory, unmapped on destruction: its pages are not resident until touched.
struct FreshMapping {
  std::size_t bytes;
  char* data;
  explicit FreshMapping(std::size_t b)
      : bytes(b),
        data(static_cast<char*>(::mmap(nullptr, b, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0))) {
    REQUIRE(data != MAP_FAILED);
    // Small pages: mincore() then reports each page on its own.
    ::madvise(data, bytes, MADV_NOHUGEPAGE);
  }
  ~FreshMapping() { ::munmap(data, bytes); }
  // Resident pages in [first, last) page indices.
  std::size_t resident_pages(std::size_t first, std::size_t last) const {
    const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    std::vector<unsigned char> in(bytes / page);
    REQUIRE(::mincore(data, bytes, in.data()) == 0);
    std::size_t count = 0;
    for (std::size_t p = first; p < last; ++p) count += in[p] & 1u;
    return count;
  }
};

// MADV_POPULATE_WRITE (Linux 5.14) on a fresh page: without it the populator does nothing,
// and the case that checks what it faulted in is reported as skipped.
bool kernel_populates() {
  const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  void* p = ::mmap(nullptr, page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) return false;
#ifdef MADV_POPULATE_WRITE
  const bool ok = ::madvise(p, page, MADV_POPULATE_WRITE) == 0;
#else
  const bool ok = ::madvise(p, page, 23 /* MADV_POPULATE_WRITE */) == 0;
#endif
  ::munmap(p, page);
  return ok;
}

}  // namespace

TEST_CASE("solver: the page populator faults in a whole fresh range and leaves its contents alone" *
          doctest::skip(!kernel_populates())) {
  const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  const std::size_t pages = 3000;  // ~12 MB: several of the helper's 2 MB chunks
  FreshMapping m(pages * page);
  // The owner has written the first pages already (as a factorization would from the front).
  std::memset(m.data, 0x5a, 10 * page);
  CHECK(m.resident_pages(10, pages) == 0);
  {
    // From mid-page to mid-page: only whole pages inside the range are the helper's.
    PagePopulator populate(m.data + page / 2, (pages - 1) * page, /*min_bytes=*/0);
    populate.wait();
    CHECK(populate.populated_bytes() == (pages - 2) * page);
  }
  CHECK(m.resident_pages(1, pages - 1) == pages - 2);
  CHECK(m.resident_pages(pages - 1, pages) == 0);  // the partial last page is left to the owner
  std::size_t kept = 0, zero = 0;
  for (std::size_t k = 0; k < 10 * page; ++k) kept += static_cast<unsigned char>(m.data[k]) == 0x5a;
  for (std::size_t k = 10 * page; k < (pages - 1) * page; ++k) zero += m.data[k] == 0;
  CHECK(kept == 10 * page);
  CHECK(zero == (pages - 11) * page);
}

TEST_CASE("solver: the page populator does nothing below its threshold or when stopped at once") {
  const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  FreshMapping m(64 * page);
  {
    const PagePopulator populate(m.data, m.bytes);  // far below kMinBytes
    CHECK(populate.populated_bytes() == 0);
  }
  CHECK(m.resident_pages(0, 64) == 0);
  { const PagePopulator nothing(nullptr, std::size_t{1} << 30, 0); }  // no range: no thread, no crash
}

TEST_CASE("solver: a supernodal factor whose pages are populated meanwhile solves like the Eigen backend") {
  // The 3D grid's Laplacian shifted to be definite: N = 30 gives a factor of ~30 MB, above
  // the populator's threshold, so its values are faulted in on the helper while CHOLMOD
  // writes them from the front.
  const SparseMatrix D = testing::grid_laplacian_3d(30);
  SparseMatrix A = -D;
  for (int i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += 0.1;
  A.makeCompressed();
  const DenseMatrix B = DenseMatrix::Random(A.rows(), 3);
  Cholesky cholmod({Backend::Cholmod, FactorKind::Supernodal});
  cholmod.compute(A);
  REQUIRE(cholmod.report().nnz_L * 8 >= static_cast<std::int64_t>(PagePopulator::kMinBytes));
  const DenseMatrix Xc = cholmod.solve(B);
  Cholesky eigen({Backend::Eigen, FactorKind::Simplicial});
  eigen.compute(A);
  const DenseMatrix Xe = eigen.solve(B);
  CHECK((A * Xc - B).norm() / B.norm() <= 1e-12);
  CHECK((Xc - Xe).norm() / Xe.norm() <= 1e-10);
  // Refactorized with new values into the same (now resident) factor: no populator, same answer.
  A = A * 2.0;
  cholmod.factorize(A);
  CHECK((cholmod.solve(B) - Xe / 2.0).norm() / Xe.norm() <= 1e-10);
}

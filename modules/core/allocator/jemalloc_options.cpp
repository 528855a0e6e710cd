// jemalloc's compiled-in options, read by jemalloc when the process starts. Linked into every
// Lapis executable with the allocator (cmake/LapisAllocator.cmake); a library user links
// lapis::allocator into their own executable to get the same.
//
// thp:always backs jemalloc's extents with transparent huge pages (MADV_HUGEPAGE), which the
// system grants on request when /sys/kernel/mm/transparent_hugepage/enabled is "madvise", as
// on Debian. Why: a one-off 50K-vertex merge touches about 1 GB of fresh memory (the normal
// matrices, the Cholesky factor, CHOLMOD's workspace). In 4 KB pages that was ~190K page
// faults, a third of the merge's time on this virtual machine; in 2 MB pages it is a few
// thousand. Freed memory stays with the process for jemalloc's default 10 s (dirty_decay_ms),
// so the next factorization reuses it without faulting it in again.
extern "C" {
// NOLINTNEXTLINE: the name and linkage are jemalloc's interface.
const char* malloc_conf = "thp:always,metadata_thp:auto";
}

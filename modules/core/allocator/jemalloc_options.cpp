// jemalloc's compiled-in options, read by jemalloc when the process starts (the MALLOC_CONF
// environment variable still overrides them). Linked into every Lapis executable with the
// allocator (cmake/LapisAllocator.cmake); a library user links lapis::allocator into their own
// executable to get the same.
//
// Why: a one-off 50K-vertex merge touches about 700 MB of fresh memory (the normal matrices,
// the Cholesky factors, CHOLMOD's workspace). With glibc's malloc, in 4 KB pages returned to the
// system on free, that was ~250K page faults, over a third of the merge's time on a virtual
// machine, where a fault costs microseconds.
//
// thp:always backs jemalloc's extents with transparent huge pages (MADV_HUGEPAGE), which the
// system grants on request when /sys/kernel/mm/transparent_hugepage/enabled is "madvise", as on
// Debian: 2 MB per fault instead of 4 KB.
//
// dirty_decay_ms:-1 keeps freed pages in the process for reuse instead of purging them: each
// purged page must be zeroed by the kernel again when reused, and that zeroing was a fifth of
// a 50K merge's main thread. The purging that matters is of blocks over 8 MiB (the factors,
// the normal matrices): jemalloc serves them from its "huge" arena and purges that one at once
// on free unless the default decay is -1. Neither oversize_threshold:0 nor keeping pages only
// during mesh_deform's set-up (per-arena mallctl) recovered the gain. The cost is that the
// process's resident memory stays at its peak (a 50K merge: 840 MB instead of 670–700 MB).
//
// Together the two options make a one-off 50K merge about twice as fast as with glibc's malloc;
// the measurements are in docs/decisions.md.
extern "C" {
// NOLINTNEXTLINE: the name and linkage are jemalloc's interface.
const char* malloc_conf = "thp:always,metadata_thp:auto,dirty_decay_ms:-1";
}

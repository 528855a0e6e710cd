# lapis::allocator — jemalloc with transparent huge pages, for executables.
#   lapis_use_allocator(<target>) links it into an executable (a no-op when it is off).
#
# Why an allocator at all: Lapis' one-off set-ups (a merge, a deformation's factorizations)
# touch hundreds of MB of fresh memory. glibc's malloc maps it in 4 KB pages and returns large
# blocks to the system on free, so each stage faults its memory in again; on a virtual machine
# a page fault costs microseconds, and faults were a third of a 50K-vertex merge. The options live in modules/core/allocator/jemalloc_options.cpp.
option(LAPIS_JEMALLOC "Link executables against jemalloc with transparent huge pages" ON)

if(LAPIS_JEMALLOC AND LAPIS_SANITIZE)
  message(STATUS "lapis: LAPIS_SANITIZE is on; executables keep the system allocator (ASan replaces it)")
  set(LAPIS_JEMALLOC OFF)
endif()

# The target itself, lapis_allocator, is defined by modules/core beside its options file.
if(LAPIS_JEMALLOC)
  find_library(LAPIS_JEMALLOC_LIBRARY NAMES jemalloc)
  if(LAPIS_JEMALLOC_LIBRARY)
    message(STATUS "lapis: executables allocate through ${LAPIS_JEMALLOC_LIBRARY} (thp:always, dirty_decay_ms:-1)")
  else()
    message(WARNING "lapis: jemalloc not found (Debian: libjemalloc-dev, installed by scripts/setup); "
                    "executables keep the system allocator and one-off set-ups run slower")
  endif()
endif()

function(lapis_use_allocator target)
  if(TARGET lapis_allocator)
    target_link_libraries(${target} PRIVATE lapis_allocator)
  endif()
endfunction()

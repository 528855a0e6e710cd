# Warning and sanitizer flags shared by every Lapis target (applied through lapis_target_defaults).
add_library(lapis_build_flags INTERFACE)
target_compile_options(lapis_build_flags INTERFACE -Wall -Wextra -Wpedantic)
# UBSan's null, alignment, vptr and object-size checks would double the compile time of the
# Eigen-heavy units; AddressSanitizer reports what the first and the last find, and the second
# and third guard what Lapis does not do (misaligned casts, polymorphic downcasts).
if(LAPIS_SANITIZE)
  set(lapis_sanitizers -fsanitize=address,undefined -fno-sanitize=null,alignment,vptr,object-size)
  target_compile_options(lapis_build_flags INTERFACE ${lapis_sanitizers} -fno-omit-frame-pointer)
  target_link_options(lapis_build_flags INTERFACE ${lapis_sanitizers})
endif()

# Executables also get the allocator (cmake/LapisAllocator.cmake). The flags are the build's
# own: an installed static library must not ask its consumers for lapis_build_flags.
function(lapis_target_defaults target)
  target_link_libraries(${target} PRIVATE $<BUILD_INTERFACE:lapis_build_flags>)
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "EXECUTABLE")
    lapis_use_allocator(${target})
  endif()
endfunction()

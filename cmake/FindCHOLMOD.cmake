# Finds CHOLMOD (SuiteSparse) and defines the imported target CHOLMOD::CHOLMOD.
# Debian's libsuitesparse-dev puts the headers in /usr/include/suitesparse and ships no
# CMake config, so look for the header and the libraries directly (pkg-config as a hint).
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(PC_CHOLMOD QUIET cholmod)
endif()

find_path(CHOLMOD_INCLUDE_DIR cholmod.h
  HINTS ${PC_CHOLMOD_INCLUDE_DIRS}
  PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY NAMES cholmod HINTS ${PC_CHOLMOD_LIBRARY_DIRS})
find_library(SUITESPARSECONFIG_LIBRARY NAMES suitesparseconfig HINTS ${PC_CHOLMOD_LIBRARY_DIRS})

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD
  REQUIRED_VARS CHOLMOD_LIBRARY SUITESPARSECONFIG_LIBRARY CHOLMOD_INCLUDE_DIR)

if(CHOLMOD_FOUND AND NOT TARGET CHOLMOD::CHOLMOD)
  add_library(CHOLMOD::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(CHOLMOD::CHOLMOD PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${SUITESPARSECONFIG_LIBRARY}")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY SUITESPARSECONFIG_LIBRARY)

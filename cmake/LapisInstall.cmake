# Installation: `cmake --install build --prefix P` puts the static libraries in P/lib, the
# public headers in P/include, the executables in P/bin, the runtime assets in P/share/lapis
# (found by lapis::asset_path) and, in P/lib/cmake/Lapis, the package LapisConfig.cmake that
# exports every module as lapis::<module>; P/lib/pkgconfig/lapis.pc serves the non-CMake world.
#
# lapis_add_module registers each library here (lapis_install_module); lapis_install_package,
# called once at the end of the top-level CMakeLists, writes the package from what was
# registered, so a new module needs no change to this file.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(LAPIS_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Lapis)
set(LAPIS_INSTALL_ASSETDIR ${CMAKE_INSTALL_DATADIR}/lapis)

# Installs a library and its include/ tree, and records it in the export set `set`
# (LapisTargets: the modules; LapisViewerTargets: the GL viewer shell of the apps).
function(lapis_install_module target set)
  install(TARGETS ${target} EXPORT ${set}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  set_property(GLOBAL APPEND PROPERTY LAPIS_EXPORT_${set} ${target})
endfunction()

# Installs executables into bin/.
function(lapis_install_programs)
  install(TARGETS ${ARGN} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# Depth-first visit of `t` for lapis_link_order: `t` is appended to `order` after every
# library of `targets` it links; `order` and `visited` live in the caller's scope.
function(_lapis_visit t)
  if(t IN_LIST visited)
    return()
  endif()
  list(APPEND visited ${t})
  get_target_property(deps ${t} LINK_LIBRARIES)
  get_target_property(interface_deps ${t} INTERFACE_LINK_LIBRARIES)
  foreach(dep IN LISTS deps interface_deps)
    if(TARGET "${dep}")
      get_target_property(aliased "${dep}" ALIASED_TARGET)
      if(aliased)
        set(dep ${aliased})
      endif()
      if(dep IN_LIST targets)
        _lapis_visit(${dep})
      endif()
    endif()
  endforeach()
  list(APPEND order ${t})
  set(visited ${visited} PARENT_SCOPE)
  set(order ${order} PARENT_SCOPE)
endfunction()

# The libraries of `set` in link order: every library before those it links, as a linker
# reading static archives left to right needs.
function(lapis_link_order set out_var)
  get_property(targets GLOBAL PROPERTY LAPIS_EXPORT_${set})
  set(order "")
  set(visited "")
  foreach(t IN LISTS targets)
    _lapis_visit(${t})
  endforeach()
  list(REVERSE order)
  set(${out_var} ${order} PARENT_SCOPE)
endfunction()

# `-l` flags of the static libraries of `set` that have an archive, in link order.
function(lapis_pkgconfig_libs set out_var)
  lapis_link_order(${set} order)
  set(flags "")
  foreach(t IN LISTS order)
    get_target_property(type ${t} TYPE)
    if(type STREQUAL "STATIC_LIBRARY")
      string(APPEND flags " -l${t}")
    endif()
  endforeach()
  set(${out_var} "${flags}" PARENT_SCOPE)
endfunction()

function(lapis_install_package)
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/package)
  get_property(viewer GLOBAL PROPERTY LAPIS_EXPORT_LapisViewerTargets)
  install(EXPORT LapisTargets NAMESPACE lapis:: DESTINATION ${LAPIS_INSTALL_CMAKEDIR})
  if(viewer)
    install(EXPORT LapisViewerTargets NAMESPACE lapis:: DESTINATION ${LAPIS_INSTALL_CMAKEDIR})
  endif()

  # The components a consumer may ask for: one per module (and viewer when installed).
  get_property(modules GLOBAL PROPERTY LAPIS_EXPORT_LapisTargets)
  list(TRANSFORM modules REPLACE "^lapis_" "")
  set(LAPIS_CONFIG_MODULES ${modules})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/LapisConfig.cmake.in ${dir}/LapisConfig.cmake
    INSTALL_DESTINATION ${LAPIS_INSTALL_CMAKEDIR})
  write_basic_package_version_file(${dir}/LapisConfigVersion.cmake COMPATIBILITY SameMajorVersion)
  install(FILES ${dir}/LapisConfig.cmake ${dir}/LapisConfigVersion.cmake ${PROJECT_SOURCE_DIR}/cmake/FindCHOLMOD.cmake
    DESTINATION ${LAPIS_INSTALL_CMAKEDIR})

  # pkg-config: the libraries in link order, then what they link privately (CHOLMOD, OpenMP, dl).
  # The prefix is found from the .pc file's own place, so the installed tree can move.
  file(RELATIVE_PATH LAPIS_PC_PREFIX_FROM_PCDIR /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
  string(REGEX REPLACE "/$" "" LAPIS_PC_PREFIX_FROM_PCDIR "${LAPIS_PC_PREFIX_FROM_PCDIR}")
  lapis_pkgconfig_libs(LapisTargets LAPIS_PC_LIBS)
  string(REPLACE ";" " " LAPIS_PC_OPENMP "${OpenMP_CXX_FLAGS}")
  set(LAPIS_PC_PRIVATE "${CHOLMOD_LIBRARY} ${SUITESPARSECONFIG_LIBRARY} ${LAPIS_PC_OPENMP}")
  foreach(lib IN LISTS CMAKE_DL_LIBS)
    string(APPEND LAPIS_PC_PRIVATE " -l${lib}")
  endforeach()
  configure_file(${PROJECT_SOURCE_DIR}/cmake/lapis.pc.in ${dir}/lapis.pc @ONLY)
  set(pc_files ${dir}/lapis.pc)
  if(viewer)
    lapis_pkgconfig_libs(LapisViewerTargets LAPIS_PC_VIEWER_LIBS)
    configure_file(${PROJECT_SOURCE_DIR}/cmake/lapis-viewer.pc.in ${dir}/lapis-viewer.pc @ONLY)
    list(APPEND pc_files ${dir}/lapis-viewer.pc)
  endif()
  install(FILES ${pc_files} DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()

# lapis_add_module(NAME <name> [SOURCES <files...>] [PUBLIC_DEPS <targets...>] [PRIVATE_DEPS <targets...>]
#                  [EXPORT <set>])
#   Builds the directory as the static library lapis_<name> with alias lapis::<name>; without
#   SOURCES, as a header-only INTERFACE library. Public headers live in include/lapis/<name>/,
#   private code in src/. The library and its headers are installed and exported as
#   lapis::<name> in the export set <set> (default LapisTargets, see cmake/LapisInstall.cmake),
#   so a new module needs nothing but this call.
function(lapis_add_module)
  cmake_parse_arguments(ARG "" "NAME;EXPORT" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  if(NOT ARG_EXPORT)
    set(ARG_EXPORT LapisTargets)
  endif()
  set(target lapis_${ARG_NAME})
  if(ARG_SOURCES)
    add_library(${target} STATIC ${ARG_SOURCES})
    set(scope PUBLIC)
  elseif(ARG_PRIVATE_DEPS)
    message(FATAL_ERROR "lapis_add_module(${ARG_NAME}): a header-only module has no PRIVATE_DEPS")
  else()
    add_library(${target} INTERFACE)
    set(scope INTERFACE)
  endif()
  target_include_directories(${target}
    ${scope} $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} ${scope} ${ARG_PUBLIC_DEPS})
  target_compile_features(${target} ${scope} cxx_std_20)
  if(ARG_SOURCES)
    target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
    target_link_libraries(${target} PRIVATE ${ARG_PRIVATE_DEPS})
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    lapis_target_defaults(${target})
  endif()
  add_library(lapis::${ARG_NAME} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${ARG_NAME})
  lapis_install_module(${target} ${ARG_EXPORT})
endfunction()

# lapis_add_test(NAME <module> SOURCES <files...> DEPS <targets...> [LABELS <labels>])
#   One doctest executable per module (test_<module>), registered with CTest.
#   Tests run from the source tree so they find assets/.
function(lapis_add_test)
  cmake_parse_arguments(ARG "" "NAME;TIMEOUT" "SOURCES;DEPS" ${ARGN})
  set(target test_${ARG_NAME})
  add_executable(${target} ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ${ARG_DEPS} lapis_doctest_main)
  target_compile_definitions(${target} PRIVATE LAPIS_SOURCE_DIR="${LAPIS_SOURCE_DIR}")
  lapis_target_defaults(${target})
  # Under the sanitizers the cases of the doctest suite "slow" (the real-mesh cross-checks at
  # size) are left out: they run the code of the smaller cases, and instrumented they would take
  # most of the budget. The plain build runs them.
  set(filter)
  if(LAPIS_SANITIZE)
    set(filter --test-suite-exclude=slow)
  endif()
  add_test(NAME ${ARG_NAME} COMMAND ${target} --force-colors=false ${filter}
           WORKING_DIRECTORY ${LAPIS_SOURCE_DIR})
  set(timeout 300)
  if(ARG_TIMEOUT)
    set(timeout ${ARG_TIMEOUT})
  endif()
  if(LAPIS_SANITIZE)  # the instrumented suites run 5 to 15 times slower
    math(EXPR timeout "${timeout} * 4")
  endif()
  set_tests_properties(${ARG_NAME} PROPERTIES TIMEOUT ${timeout})
endfunction()

# lapis_add_module(NAME <name> SOURCES <files...> [PUBLIC_DEPS <targets...>] [PRIVATE_DEPS <targets...>])
#   Builds modules/<name> as the static library lapis_<name> with alias lapis::<name>.
#   Public headers live in modules/<name>/include/lapis/<name>/, private code in src/.
function(lapis_add_module)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(target lapis_${ARG_NAME})
  add_library(${target} STATIC ${ARG_SOURCES})
  add_library(lapis::${ARG_NAME} ALIAS ${target})
  target_include_directories(${target}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  lapis_target_defaults(${target})
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
  add_test(NAME ${ARG_NAME} COMMAND ${target} --force-colors=false
           WORKING_DIRECTORY ${LAPIS_SOURCE_DIR})
  if(ARG_TIMEOUT)
    set_tests_properties(${ARG_NAME} PROPERTIES TIMEOUT ${ARG_TIMEOUT})
  else()
    set_tests_properties(${ARG_NAME} PROPERTIES TIMEOUT 300)
  endif()
endfunction()

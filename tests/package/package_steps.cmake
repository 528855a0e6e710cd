# Shared by the package tests' scripts (cmake -P): run a step, fail with its output.

# lapis_step(<description> [WORKING_DIRECTORY <dir>] COMMAND <command...>)
#   Runs the command; a non-zero exit ends the test with the command's output. The output is
#   left in LAPIS_STEP_OUTPUT.
function(lapis_step description)
  cmake_parse_arguments(ARG "" "WORKING_DIRECTORY" "COMMAND" ${ARGN})
  if(NOT ARG_WORKING_DIRECTORY)
    set(ARG_WORKING_DIRECTORY ${WORK})
  endif()
  message(STATUS "package: ${description}")
  execute_process(COMMAND ${ARG_COMMAND} WORKING_DIRECTORY ${ARG_WORKING_DIRECTORY}
    RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT status EQUAL 0)
    string(REPLACE ";" " " shown "${ARG_COMMAND}")
    message(FATAL_ERROR "package: ${description} failed (${status}) in ${ARG_WORKING_DIRECTORY}:\n  ${shown}\n${out}")
  endif()
  set(LAPIS_STEP_OUTPUT "${out}" PARENT_SCOPE)
endfunction()

# Fails unless every path exists.
function(lapis_expect_files)
  foreach(path IN LISTS ARGN)
    if(NOT EXISTS ${path})
      message(FATAL_ERROR "package: the install lacks ${path}")
    endif()
  endforeach()
endfunction()

# The installed executables run on the installed assets, not on a variable of the caller's.
unset(ENV{LAPIS_ASSET_DIR})

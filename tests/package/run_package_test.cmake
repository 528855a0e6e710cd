# cmake -DSTAGE=... -DWORK=... -DBUILD_DIR=... -DCONSUMER_SOURCE=... -DGENERATOR=... -DCXX=...
#       [-DCXX_LAUNCHER=...] [-DBUILD_TYPE=...] [-DVIEWER=ON] -P run_package_test.cmake
# Installs the build into STAGE and uses it as a user would (see CMakeLists.txt).
include(${CMAKE_CURRENT_LIST_DIR}/package_steps.cmake)
file(REMOVE_RECURSE ${STAGE} ${WORK}/consumer-build ${WORK}/run)
file(MAKE_DIRECTORY ${WORK}/run)

lapis_step("install into ${STAGE}" COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${STAGE})
lapis_expect_files(
  ${STAGE}/bin/lapis
  ${STAGE}/include/lapis/core/asset_path.h
  ${STAGE}/include/lapis/mesh_deform/deformer.h
  ${STAGE}/lib/liblapis_core.a
  ${STAGE}/lib/liblapis_mesh_deform.a
  ${STAGE}/lib/liblapis_hair_sketch.a
  ${STAGE}/lib/cmake/Lapis/LapisConfig.cmake
  ${STAGE}/lib/cmake/Lapis/LapisConfigVersion.cmake
  ${STAGE}/lib/cmake/Lapis/FindCHOLMOD.cmake
  ${STAGE}/lib/pkgconfig/lapis.pc
  ${STAGE}/share/lapis/head.obj
  ${STAGE}/share/lapis/head_scalp.txt
  ${STAGE}/share/lapis/sessions/smooth.json
  ${STAGE}/share/lapis/merge/dome.obj)

# A consumer project: find_package(Lapis), link lapis::mesh_deform and lapis::hair_sketch.
set(launcher "")
if(CXX_LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_LAUNCHER})
endif()
lapis_step("configure the consumer against the stage"
  COMMAND ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${WORK}/consumer-build -G ${GENERATOR}
          -DCMAKE_CXX_COMPILER=${CXX} ${launcher} -DCMAKE_BUILD_TYPE=${BUILD_TYPE}
          -DCMAKE_PREFIX_PATH=${STAGE} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
lapis_step("build the consumer" COMMAND ${CMAKE_COMMAND} --build ${WORK}/consumer-build)
set(ENV{LAPIS_ASSET_DIR} ${STAGE}/share/lapis)
lapis_step("run the consumer" COMMAND ${WORK}/consumer-build/lapis_consumer)
unset(ENV{LAPIS_ASSET_DIR})
message("${LAPIS_STEP_OUTPUT}")
if(VIEWER)  # built with the apps: lapis::viewer is installed too
  lapis_step("run the viewer consumer" COMMAND ${WORK}/consumer-build/lapis_viewer_consumer)
  message("${LAPIS_STEP_OUTPUT}")
endif()

# pkg-config: lapis.pc names every installed module library, each before those it links.
set(ENV{PKG_CONFIG_PATH} ${STAGE}/lib/pkgconfig)
lapis_step("pkg-config --cflags --libs lapis" COMMAND pkg-config --cflags --libs lapis)
string(STRIP "${LAPIS_STEP_OUTPUT}" pc_flags)
message("lapis.pc: ${pc_flags}")
file(GLOB archives RELATIVE ${STAGE}/lib ${STAGE}/lib/liblapis_*.a)
list(REMOVE_ITEM archives liblapis_viewer.a)  # lapis-viewer.pc's
foreach(archive IN LISTS archives)
  string(REGEX REPLACE "^lib(.*)\\.a$" "-l\\1" flag ${archive})
  string(FIND " ${pc_flags} " " ${flag} " at_${flag})
  if(at_${flag} LESS 0)
    message(FATAL_ERROR "package: lapis.pc lacks ${flag}")
  endif()
endforeach()
foreach(pair mesh_merge:mesh_deform mesh_deform:geometry mesh_deform:solver hair_sketch:geometry
             hair_sketch:solver geometry:core solver:core)
  string(REPLACE ":" ";" pair ${pair})
  list(GET pair 0 user)
  list(GET pair 1 used)
  if(NOT at_-llapis_${user} LESS at_-llapis_${used})
    message(FATAL_ERROR "package: lapis.pc links lapis_${used} before lapis_${user}, which needs it")
  endif()
endforeach()
separate_arguments(pc_args UNIX_COMMAND "${pc_flags}")
lapis_step("build the consumer from lapis.pc's flags"
  COMMAND ${CXX_LAUNCHER} ${CXX} -std=c++20 -O1 ${CONSUMER_SOURCE}/main.cpp ${pc_args} -o ${WORK}/run/consumer_pc)
set(ENV{LAPIS_ASSET_DIR} ${STAGE}/share/lapis)
lapis_step("run the pkg-config build" COMMAND ${WORK}/run/consumer_pc)
unset(ENV{LAPIS_ASSET_DIR})

# The installed CLI from /: a bundled session whose head is the installed one.
lapis_step("installed lapis hair, run from /" WORKING_DIRECTORY /
  COMMAND ${STAGE}/bin/lapis hair --session ${STAGE}/share/lapis/sessions/smooth.json --grid-unknowns 4000
          --roots 300 --out-hair ${WORK}/run/smooth.hair --report ${WORK}/run/smooth.report.json)
lapis_expect_files(${WORK}/run/smooth.hair ${WORK}/run/smooth.report.json)

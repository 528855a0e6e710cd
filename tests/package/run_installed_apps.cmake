# cmake -DSTAGE=... -DWORK=... -P run_installed_apps.cmake
# The installed GL apps (staged by the `package` test) from /, on the installed assets: each
# opens its default input and writes a headless screenshot. Exit 77 (skipped) without xvfb-run.
include(${CMAKE_CURRENT_LIST_DIR}/package_steps.cmake)
find_program(XVFB_RUN xvfb-run)
if(NOT XVFB_RUN)
  message("package_apps: skipped, xvfb-run not found")
  cmake_language(EXIT 77)
endif()
file(REMOVE_RECURSE ${WORK}/apps-run)
file(MAKE_DIRECTORY ${WORK}/apps-run)
set(out ${WORK}/apps-run)
set(xvfb ${XVFB_RUN} -a -s "-screen 0 1280x1024x24")

# The bundled head (no --session): share/lapis/head.obj. --save-session keeps the autosave
# on exit out of /.
lapis_step("installed lapis-hair-sketch, run from /" WORKING_DIRECTORY /
  COMMAND ${xvfb} ${STAGE}/bin/lapis-hair-sketch --headless --size 320x240 --roots 200
          --screenshot ${out}/hair.png --save-session ${out}/hairstyle.json)
# The default preset: share/lapis/merge/dome.obj onto neck.obj.
lapis_step("installed lapis-merge, run from /" WORKING_DIRECTORY /
  COMMAND ${xvfb} ${STAGE}/bin/lapis-merge --headless --size 320x240 --screenshot ${out}/merge.png)
lapis_expect_files(${out}/hair.png ${out}/merge.png ${out}/hairstyle.json.autosave.json)

# The session the hair app saved on exit names the head it opened: the installed one, though
# the source tree's assets/ exists too, by a path relative to the session (no absolute path of
# this machine in a file a user shares).
file(READ ${out}/hairstyle.json.autosave.json session)
string(JSON head_mesh GET "${session}" settings head_mesh)
string(JSON scalp_mask GET "${session}" settings scalp_mask)
if(IS_ABSOLUTE "${head_mesh}" OR IS_ABSOLUTE "${scalp_mask}")
  message(FATAL_ERROR "package: the saved session names its head by absolute paths: ${head_mesh}, ${scalp_mask}")
endif()
get_filename_component(head_mesh "${head_mesh}" ABSOLUTE BASE_DIR ${out})
get_filename_component(scalp_mask "${scalp_mask}" ABSOLUTE BASE_DIR ${out})
get_filename_component(installed_head "${STAGE}/share/lapis/head.obj" ABSOLUTE)
get_filename_component(installed_mask "${STAGE}/share/lapis/head_scalp.txt" ABSOLUTE)
if(NOT head_mesh STREQUAL installed_head OR NOT scalp_mask STREQUAL installed_mask)
  message(FATAL_ERROR "package: the installed lapis-hair-sketch opened ${head_mesh} and ${scalp_mask}, "
                      "not the installed ${installed_head} and ${installed_mask}")
endif()

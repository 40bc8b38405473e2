# Installed-package check, run as `cmake -P` by ctest (package_consumer):
#   1. install the svo build SVO_BUILD_DIR into WORK_DIR/prefix;
#   2. voxelize MESH with the installed svo into WORK_DIR/cli.vdb (a MaskGrid);
#   3. configure and build CONSUMER_DIR (this folder) against that prefix;
#   4. run `consumer MESH WORK_DIR/cli.vdb`, which voxelizes through the
#      package and exits 0 only when its voxels equal the CLI's;
#   5. check the installed targets' links: svo::vdb_io (the converter) reaches
#      no GL library, directly or through the svo:: targets it links.
# Also takes GENERATOR, MAKE_PROGRAM, CXX_COMPILER, LAUNCHER, BINDIR and INCLUDEDIR
# (relative install folders) from the calling build.
set(prefix "${WORK_DIR}/prefix")
set(consumer_build "${WORK_DIR}/build")
file(REMOVE_RECURSE "${WORK_DIR}")

# run(<step> <command...>): runs the command, stops the test when it fails.
function(run step)
  message(STATUS "package_consumer: ${step}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${step} failed (${rc}): ${ARGN}")
  endif()
endfunction()

run("install" ${CMAKE_COMMAND} --install ${SVO_BUILD_DIR} --prefix ${prefix})
# overlap.h includes the shader source overlap.glsl: it has to be installed too.
foreach(f ${INCLUDEDIR}/svo/core/overlap.glsl ${INCLUDEDIR}/svo/gl/raster_voxelizer.h
          ${INCLUDEDIR}/svo/vdb_io/vdb_file.h ${BINDIR}/svo)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "the install lacks ${f}")
  endif()
endforeach()

run("svo voxelize" ${prefix}/${BINDIR}/svo voxelize ${MESH} -r 64 --topology mask -o ${WORK_DIR}/cli.vdb)

run("configure consumer" ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${consumer_build} -G ${GENERATOR}
    -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER} -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${prefix})
# The package must come from the prefix, not from the build tree or the system.
file(STRINGS "${consumer_build}/CMakeCache.txt" svo_dir REGEX "^svo_DIR:")
if(NOT svo_dir MATCHES "=${prefix}/")
  message(FATAL_ERROR "the consumer found svo elsewhere: ${svo_dir}")
endif()
run("build consumer" ${CMAKE_COMMAND} --build ${consumer_build})

run("consumer" ${consumer_build}/consumer ${MESH} ${WORK_DIR}/cli.vdb)

# Each installed svo:: target's INTERFACE_LINK_LIBRARIES, as svoTargets.cmake declares them.
file(GLOB_RECURSE targets_file "${prefix}/*/svoTargets.cmake")
file(READ "${targets_file}" targets_text)
# links_of(<name> <var>): svo::<name>'s links, "" when it declares none.
function(links_of name var)
  string(REGEX MATCH "set_target_properties\\(svo::${name} PROPERTIES[^)]*INTERFACE_LINK_LIBRARIES \"([^\"]*)\""
         found "${targets_text}")
  set(${var} "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()
links_of(vdb_io vdb_io_links)
links_of(svo svo_links)
links_of(gl_device device_links)
# The reading itself: the converter links core, and the front door and device do link GL
# (libepoxy, which loads GL at run time).
if(NOT vdb_io_links MATCHES "svo::core" OR NOT svo_links MATCHES "svo::gl_voxelize"
   OR NOT device_links MATCHES "PkgConfig::epoxy")
  message(FATAL_ERROR "svoTargets.cmake read wrongly: svo::vdb_io links '${vdb_io_links}', svo::svo links "
                      "'${svo_links}', svo::gl_device links '${device_links}'")
endif()
set(pending vdb_io)
set(seen)
while(pending)
  list(POP_FRONT pending name)
  list(APPEND seen svo::${name})
  links_of(${name} links)
  if(links MATCHES "OpenGL|EGL|epoxy|svo::gl")
    message(FATAL_ERROR "svo::vdb_io reaches GL through svo::${name}: ${links}")
  endif()
  string(REGEX MATCHALL "svo::[a-z_]+" next "${links}")
  string(REPLACE "svo::" "" next "${next}")
  foreach(n ${next})
    list(FIND seen svo::${n} at)
    if(at EQUAL -1)
      list(APPEND pending ${n})
    endif()
  endforeach()
endwhile()
message(STATUS "package_consumer: svo::vdb_io links no GL (through ${seen})")

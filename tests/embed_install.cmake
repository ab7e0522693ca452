# ctest embed.InstallAndBuildExamples: installs the build into a fresh prefix,
# then configures, builds and runs examples/embed (C++) and examples/embed_c (C)
# against it as separate projects, the way an engine would consume the package.
# Usage: cmake -DBUILD_DIR=.. -DSOURCE_DIR=.. -DWORK_DIR=.. -DGENERATOR=.. -P embed_install.cmake
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR GENERATOR)
  if(NOT ${var})
    message(FATAL_ERROR "embed_install.cmake: pass -D${var}=...")
  endif()
endforeach()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    list(JOIN ARGN " " command)
    message(FATAL_ERROR "failed (${rc}): ${command}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(file include/facial/character.h include/facial/c_api.h lib/cmake/facial/facialConfig.cmake
             share/facial/data/graphs/tour.json)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "the install has no ${file}")
  endif()
endforeach()
# Implementation headers (detail/: the graph JSON readers, which throw inside the
# library) stay out of the install, and no installed header may need one.
file(GLOB_RECURSE installed_headers ${prefix}/include/*.h)
foreach(header ${installed_headers})
  if(header MATCHES "/detail/")
    message(FATAL_ERROR "the install has an implementation header: ${header}")
  endif()
  file(STRINGS ${header} detail_includes REGEX "#[ \t]*include[ \t]*[\"<][^\">]*/detail/")
  if(detail_includes)
    message(FATAL_ERROR "${header} includes a header that is not installed: ${detail_includes}")
  endif()
endforeach()

foreach(example embed embed_c)
  set(build ${WORK_DIR}/${example})
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/${example} -B ${build} -G ${GENERATOR}
      -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
  run(${CMAKE_COMMAND} --build ${build})
  run(${build}/${example})
  # 200 frames, and the last emotion the example triggers reaches the face (surprise opens
  # the jaw, sadness pulls the lip corners down: AU15).
  string(REGEX MATCHALL "\nframe +[0-9]+ " frames "\n${run_output}")
  list(LENGTH frames count)
  if(NOT count EQUAL 200)
    message(FATAL_ERROR "${example} printed ${count} frames, not 200:\n${run_output}")
  endif()
  if(example STREQUAL "embed")
    set(expect "frame 199 [^\n]* jawOpen=")
  else()
    set(expect "frame 199 [^\n]* AU15=")
  endif()
  if(NOT run_output MATCHES "${expect}")
    message(FATAL_ERROR "${example}: the last frame does not show the triggered emotion (${expect}):\n${run_output}")
  endif()
  message(STATUS "${example}: 200 frames")
endforeach()

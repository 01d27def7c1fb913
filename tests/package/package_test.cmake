# cmake -D ... -P package_test.cmake (arguments: tests/package/CMakeLists.txt)
#
# 1. cmake --install the build tree into WORK_DIR/prefix: no internal/ headers, and no path into
#    the source or build tree in the package files;
# 2. configure and build the consumer project against that prefix alone (find_package(inkline));
# 3. run it on FRAME of SCENE, and `inkline render SCENE --frames FRAME:FRAME --json ...
#    --visibility raycast` beside it;
# 4. compare the two JSON files byte for byte, the stage timings (stats.ms) aside;
# 5. with the Python module built, import it from the prefix alone and compare its frame too;
# and `inkline --version` says project()'s VERSION.

foreach(var INKLINE_SOURCE_DIR INKLINE_BUILD_DIR INKLINE_EXE VERSION CONSUMER_SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER SCENE FRAME)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "package_test.cmake: -D ${var}=... missing")
  endif()
endforeach()

# Runs a command; on failure stops with its output.
function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${step} failed (${rc}):\n${ARGN}\n${out}")
  endif()
  message(STATUS "${step}: done")
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

# 1. Install.
set(config_args)
if(CONFIG)
  set(config_args --config ${CONFIG})
endif()
run("install" ${CMAKE_COMMAND} --install ${INKLINE_BUILD_DIR} --prefix ${prefix} ${config_args})
if(NOT EXISTS ${prefix}/include/inkline/core/version.h)
  message(FATAL_ERROR "no include/inkline/core/version.h in the installation")
endif()
file(GLOB_RECURSE internal_headers ${prefix}/include/*)
list(FILTER internal_headers INCLUDE REGEX "/internal/")
if(internal_headers)
  message(FATAL_ERROR "internal headers installed: ${internal_headers}")
endif()
file(GLOB_RECURSE package_files ${prefix}/*.cmake)
if(NOT package_files)
  message(FATAL_ERROR "no package files (*.cmake) in the installation")
endif()
foreach(file IN LISTS package_files)
  file(READ ${file} text)
  foreach(tree ${INKLINE_SOURCE_DIR} ${INKLINE_BUILD_DIR})
    string(FIND "${text}" "${tree}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${file} names '${tree}': the installed package must stand on its own")
    endif()
  endforeach()
endforeach()

# 2. The consumer, which sees nothing of inkline but the prefix.
set(build_type Release)
if(CONFIG)
  set(build_type ${CONFIG})
endif()
set(consumer_build ${WORK_DIR}/consumer-build)
run("consumer configure" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${consumer_build} -G ${GENERATOR}
    -D CMAKE_BUILD_TYPE=${build_type}
    -D CMAKE_PREFIX_PATH=${prefix}
    -D CMAKE_CXX_COMPILER=${CXX_COMPILER}
    -D CMAKE_CXX_COMPILER_LAUNCHER=${CXX_COMPILER_LAUNCHER}
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${CXX_FLAGS}")
# The package found must be the one just installed, not another inkline on the machine.
file(STRINGS ${consumer_build}/CMakeCache.txt found_dir REGEX "^inkline_DIR:")
string(REGEX REPLACE "^[^=]*=" "" found_dir "${found_dir}")
file(REAL_PATH "${found_dir}" found_dir)
file(REAL_PATH "${prefix}" real_prefix)
string(FIND "${found_dir}" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "the consumer found inkline in '${found_dir}', not under '${real_prefix}'")
endif()
run("consumer build" ${CMAKE_COMMAND} --build ${consumer_build} ${config_args})
find_program(consumer inkline_consumer PATHS ${consumer_build} ${consumer_build}/${CONFIG} NO_DEFAULT_PATH REQUIRED)

# 3. The same frame from the library and from the program.
set(library_json ${WORK_DIR}/library.json)
set(cli_json ${WORK_DIR}/cli.json)
run("consumer run" ${consumer} ${SCENE} ${FRAME} ${library_json})
run("inkline render" ${INKLINE_EXE} render ${SCENE} --frames ${FRAME}:${FRAME} --json ${cli_json}
    --visibility raycast -q)

# 4. Byte for byte, with the one "ms" object of each emptied.
function(read_without_timings path out_var)
  if(NOT EXISTS ${path})
    message(FATAL_ERROR "${path} was not written")
  endif()
  file(READ ${path} text)
  string(REGEX MATCHALL "\"ms\":{[^}]*}" timings "${text}")
  list(LENGTH timings count)
  if(NOT count EQUAL 1)
    message(FATAL_ERROR "${path}: expected one \"ms\" object in stats, found ${count}")
  endif()
  string(REGEX REPLACE "\"ms\":{[^}]*}" "\"ms\":{}" text "${text}")
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()
read_without_timings(${library_json} library)
read_without_timings(${cli_json} cli)
if(NOT library STREQUAL cli)
  # The longest common prefix, by bisection, to show where they part.
  string(LENGTH "${library}" library_length)
  string(LENGTH "${cli}" cli_length)
  set(lo 0)
  if(library_length LESS cli_length)
    set(hi ${library_length})
  else()
    set(hi ${cli_length})
  endif()
  while(lo LESS hi)
    math(EXPR mid "(${lo} + ${hi} + 1) / 2")
    string(SUBSTRING "${library}" 0 ${mid} a)
    string(SUBSTRING "${cli}" 0 ${mid} b)
    if(a STREQUAL b)
      set(lo ${mid})
    else()
      math(EXPR hi "${mid} - 1")
    endif()
  endwhile()
  math(EXPR from "${lo} - 60")
  if(from LESS 0)
    set(from 0)
  endif()
  string(SUBSTRING "${library}" ${from} 160 library_here)
  string(SUBSTRING "${cli}" ${from} 160 cli_here)
  message(FATAL_ERROR "the library's frame differs from the program's at byte ${lo} "
                      "(${library_length} and ${cli_length} bytes):\n"
                      "  library: ...${library_here}...\n  inkline: ...${cli_here}...")
endif()
string(LENGTH "${cli}" length)
message(STATUS "frame ${FRAME}: the library's polylines JSON equals the program's (${length} bytes, stats.ms aside)")

# 5. With the Python module built: the installed package imports from the prefix alone and draws
#    the same frame.
if(PYTHON)
  set(site ${prefix}/${PYTHON_SITE})
  if(NOT EXISTS ${site}/inkline/__init__.py)
    message(FATAL_ERROR "the Python package is not in ${site}")
  endif()
  set(python_json ${WORK_DIR}/python.json)
  run("python module" ${CMAKE_COMMAND} -E env PYTHONPATH=${site} PYTHONDONTWRITEBYTECODE=1
      ${PYTHON} ${CMAKE_CURRENT_LIST_DIR}/python_consumer.py ${site} ${SCENE} ${FRAME} ${python_json})
  read_without_timings(${python_json} python)
  if(NOT python STREQUAL cli)
    message(FATAL_ERROR "the installed Python module's frame differs from the program's")
  endif()
  message(STATUS "frame ${FRAME}: the installed Python module's polylines JSON equals the program's")
endif()

execute_process(COMMAND ${INKLINE_EXE} --version RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE said)
if(NOT rc EQUAL 0 OR NOT said STREQUAL "inkline ${VERSION}\n")
  message(FATAL_ERROR "inkline --version said '${said}' (exit ${rc}), expected 'inkline ${VERSION}'")
endif()
message(STATUS "inkline --version: inkline ${VERSION}")

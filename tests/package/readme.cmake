# The README's C++ snippets compile and run exactly as printed against an installed package: each
# fenced ```cpp block of README.md becomes one program (nothing added around it), built with
# find_package(massspring COMPONENTS io) from a temporary prefix by the README's own consumer
# commands (its "cmake -S . -B build ... -DCMAKE_PREFIX_PATH=/your/prefix" block, which must
# build optimised), and run in an empty folder: with no argument, on its own saved state, and on
# the project's scenes without pins (drape.json) and with an XML scene's force terms (orbit.xml),
# each of which it saves and reads back.
# Usage: cmake -DSOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=... -DCXX_COMPILER=... [-DCCACHE=...] -P readme.cmake
foreach(var SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "readme.cmake: ${var} is not set")
  endif()
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/ccache.cmake)

function(run)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${WORK_DIR}/run
    RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "failed (${result}): ${command}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/run)
set(prefix ${WORK_DIR}/prefix)
set(common -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_BUILD_TYPE=Release)

# The snippets: every line between "```cpp" and the next "```", verbatim.
file(STRINGS ${SOURCE_DIR}/README.md lines)
set(snippets 0)
set(inside OFF)
foreach(line IN LISTS lines)
  if(inside)
    if(line STREQUAL "```")
      set(inside OFF)
    else()
      file(APPEND ${WORK_DIR}/consumer/snippet_${snippets}.cpp "${line}\n")
    endif()
  elseif(line STREQUAL "```cpp")
    math(EXPR snippets "${snippets} + 1")
    set(inside ON)
    file(WRITE ${WORK_DIR}/consumer/snippet_${snippets}.cpp "")
  endif()
endforeach()
if(snippets LESS 2)
  message(FATAL_ERROR "README.md has ${snippets} C++ snippets, expected the two of the quick start")
endif()

set(cmakelists "cmake_minimum_required(VERSION 3.21)\nproject(readme LANGUAGES CXX)\n"
  "find_package(massspring 0.1 CONFIG REQUIRED COMPONENTS io)\n")
foreach(k RANGE 1 ${snippets})
  string(APPEND cmakelists "add_executable(snippet_${k} snippet_${k}.cpp)\n"
    "target_link_libraries(snippet_${k} PRIVATE massspring::massspring massspring::io)\n")
endforeach()
file(WRITE ${WORK_DIR}/consumer/CMakeLists.txt ${cmakelists})

run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/library ${common}
    -DMASSSPRING_BUILD_TESTS=OFF -DMASSSPRING_BUILD_EXAMPLES=OFF -DMASSSPRING_BUILD_BENCHMARKS=OFF
    -DMASSSPRING_BUILD_PYTHON=OFF)
run(${CMAKE_COMMAND} --install ${WORK_DIR}/library --prefix ${prefix})
# The consumer is built by the README's commands: every line of the ```sh block that names
# /your/prefix, the prefix put in its place, run in the consumer's folder with the compiler of
# this build.
set(commands "")
set(inside OFF)
set(block "")
foreach(line IN LISTS lines)
  if(inside)
    if(line STREQUAL "```")
      set(inside OFF)
      if(block MATCHES "/your/prefix")
        set(commands "${block}")
      endif()
    else()
      list(APPEND block "${line}")
    endif()
  elseif(line STREQUAL "```sh")
    set(inside ON)
    set(block "")
  endif()
endforeach()
if(NOT commands)
  message(FATAL_ERROR "README.md shows no commands that build a consumer (a ```sh block naming "
    "/your/prefix)")
endif()
set(ENV{CXX} ${CXX_COMPILER})
foreach(command IN LISTS commands)
  string(REGEX REPLACE "#.*" "" command "${command}")
  string(REPLACE "/your/prefix" "${prefix}" command "${command}")
  separate_arguments(argv UNIX_COMMAND "${command}")
  if(argv)
    execute_process(COMMAND ${argv} WORKING_DIRECTORY ${WORK_DIR}/consumer
      RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT result EQUAL 0)
      message(FATAL_ERROR "the README's command failed (${result}): ${command}\n${out}\n${err}")
    endif()
  endif()
endforeach()
# Built as the README says, the consumer is optimised (no build type: no optimisation at all).
set(consumer ${WORK_DIR}/consumer/build)
if(NOT EXISTS ${consumer}/CMakeCache.txt)
  message(FATAL_ERROR "the README's commands did not configure ${consumer}")
endif()
file(STRINGS ${consumer}/CMakeCache.txt build_type REGEX "^CMAKE_BUILD_TYPE:")
if(NOT build_type MATCHES "=(Release|RelWithDebInfo|MinSizeRel)$")
  message(FATAL_ERROR "the README's consumer commands build without optimisation: "
    "${build_type}")
endif()

foreach(k RANGE 1 ${snippets})
  run(${consumer}/snippet_${k})
endforeach()
# The first snippet saved its state; the state loads back.
if(NOT EXISTS ${WORK_DIR}/run/cloth-state.json)
  message(FATAL_ERROR "snippet 1 did not write cloth-state.json")
endif()
run(${consumer}/snippet_1 ${WORK_DIR}/run/cloth-state.json)
# The project's own scenes: one without pins, one with an XML scene's force terms; each state it
# saves reads back.
foreach(scene examples/scenes/drape.json examples/scenes_xml/orbit.xml)
  file(REMOVE ${WORK_DIR}/run/cloth-state.json)
  run(${consumer}/snippet_1 ${SOURCE_DIR}/${scene})
  if(NOT EXISTS ${WORK_DIR}/run/cloth-state.json)
    message(FATAL_ERROR "snippet 1 on ${scene} did not write cloth-state.json")
  endif()
  run(${consumer}/snippet_1 ${WORK_DIR}/run/cloth-state.json)
endforeach()

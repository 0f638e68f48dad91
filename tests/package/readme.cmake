# The README's C++ snippets compile and run exactly as printed against an installed package: each
# fenced ```cpp block of README.md becomes one program (nothing added around it), built with
# find_package(massspring COMPONENTS io) from a temporary prefix, and run in an empty folder.
# Usage: cmake -DSOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=... -DCXX_COMPILER=... -P readme.cmake
foreach(var SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "readme.cmake: ${var} is not set")
  endif()
endforeach()

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
run(${CMAKE_COMMAND} -S ${WORK_DIR}/consumer -B ${WORK_DIR}/build ${common}
    -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
foreach(k RANGE 1 ${snippets})
  run(${WORK_DIR}/build/snippet_${k})
endforeach()
# The first snippet saved its state; the state loads back.
if(NOT EXISTS ${WORK_DIR}/run/cloth-state.json)
  message(FATAL_ERROR "snippet 1 did not write cloth-state.json")
endif()
run(${WORK_DIR}/build/snippet_1 ${WORK_DIR}/run/cloth-state.json)

# Installs massspring into a temporary prefix and builds two consumers: one with find_package from
# that prefix, one with add_subdirectory of the source tree; runs both.
# Usage: cmake -DSOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=... -DCXX_COMPILER=... [-DCCACHE=...] -P run.cmake
foreach(var SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run.cmake: ${var} is not set")
  endif()
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/ccache.cmake)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "failed (${result}): ${command}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(common -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_BUILD_TYPE=Release)

# 1. Install (header-only: configuring is all the building there is).
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/library ${common}
    -DMASSSPRING_BUILD_TESTS=OFF -DMASSSPRING_BUILD_EXAMPLES=OFF -DMASSSPRING_BUILD_BENCHMARKS=OFF
    -DMASSSPRING_BUILD_PYTHON=OFF)
run(${CMAKE_COMMAND} --install ${WORK_DIR}/library --prefix ${prefix})
foreach(file include/massspring/massspring.hpp include/massspring/io.hpp
             share/cmake/massspring/massspringConfig.cmake
             share/cmake/massspring/massspringConfigVersion.cmake
             bin/massspring-render share/doc/massspring/README.md)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "the install is missing ${file}")
  endif()
endforeach()
# massspring-render (scripts/render.py) is a program; every relative link of the installed README
# (docs/*.md, pictures, LICENSE) leads to an installed file.
file(STRINGS ${prefix}/bin/massspring-render shebang LIMIT_COUNT 1)
if(NOT shebang MATCHES "^#!.*python3")
  message(FATAL_ERROR "bin/massspring-render does not start with a python3 #! line: ${shebang}")
endif()
file(READ ${prefix}/share/doc/massspring/README.md readme)
# (brackets and semicolons would confuse CMake's lists: a link "](target)" becomes "@(target)")
string(REPLACE ";" "," readme "${readme}")
string(REPLACE "[" "<" readme "${readme}")
string(REPLACE "]" "@" readme "${readme}")
string(REGEX MATCHALL "@\\([^)#]+[)#]" links "${readme}")
set(checked 0)
foreach(link IN LISTS links)
  string(REGEX REPLACE "^@\\(([^)#]+)[)#]$" "\\1" target "${link}")
  if(target MATCHES "^[a-z]+:")
    continue()
  endif()
  if(NOT EXISTS ${prefix}/share/doc/massspring/${target})
    message(FATAL_ERROR "the installed README links ${target}, which is not installed")
  endif()
  math(EXPR checked "${checked} + 1")
endforeach()
if(checked LESS 10)
  message(FATAL_ERROR "found ${checked} relative links in the installed README, expected its docs")
endif()
message(STATUS "the installed README's ${checked} relative links lead to installed files")

# 2. find_package from the prefix (with the cholmod component where it was installed: the library's
# configure found CHOLMOD).
set(expect_cholmod OFF)
if(EXISTS ${prefix}/share/cmake/massspring/massspringCholmodTargets.cmake)
  set(expect_cholmod ON)
  if(NOT EXISTS ${prefix}/share/cmake/massspring/FindCHOLMOD.cmake)
    message(FATAL_ERROR "the install has massspring::cholmod but not FindCHOLMOD.cmake")
  endif()
endif()
message(STATUS "massspring::cholmod installed: ${expect_cholmod}")
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/find_package -B ${WORK_DIR}/find_package
    ${common} -DCMAKE_PREFIX_PATH=${prefix} -DEXPECT_CHOLMOD=${expect_cholmod})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/find_package)
run(${WORK_DIR}/find_package/consumer ${WORK_DIR}/find_package)

# 3. A version the package does not satisfy is refused.
file(WRITE ${WORK_DIR}/too_new/CMakeLists.txt
  "cmake_minimum_required(VERSION 3.21)\nproject(too_new LANGUAGES CXX)\n"
  "find_package(massspring 99 CONFIG)\n"
  "if(massspring_FOUND)\n  message(FATAL_ERROR \"version 99 accepted\")\nendif()\n")
run(${CMAKE_COMMAND} -S ${WORK_DIR}/too_new -B ${WORK_DIR}/too_new/build ${common}
    -DCMAKE_PREFIX_PATH=${prefix})

# 4. add_subdirectory of the source tree.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/add_subdirectory -B ${WORK_DIR}/add_subdirectory
    ${common} -DMASSSPRING_SOURCE_DIR=${SOURCE_DIR})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/add_subdirectory)
run(${WORK_DIR}/add_subdirectory/consumer ${WORK_DIR}/add_subdirectory)

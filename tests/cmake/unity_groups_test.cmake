# tests.unity_group_clash: the unity-group check (unity_groups.cmake, run as a script) on the
# fixtures in unity_fixtures/. first.cpp with second.cpp passes: repeats C++ allows (the same
# alias, an overload, the same macro), names in other namespaces, and decoys in a raw string, in
# comments and in a test's body. first.cpp with third.cpp, fourth.cpp or fifth.cpp (a variable
# named as first.cpp's struct, another body for its macro, its function again) fails at once,
# naming the group, the name and both files with the lines of the two declarations.
#   cmake -DCHECK=.../unity_groups.cmake -DFIXTURES=.../unity_fixtures -P unity_groups_test.cmake

function(check_group second result_var output_var)
  execute_process(
    COMMAND ${CMAKE_COMMAND} -DGROUP=fixtures "-DFILES=${FIXTURES}/first.cpp;${FIXTURES}/${second}"
      -P ${CHECK}
    RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  string(REGEX REPLACE "[ \n]+" " " output "${output}")  # CMake wraps long messages
  set(${result_var} "${result}" PARENT_SCOPE)
  set(${output_var} "${output}" PARENT_SCOPE)
endfunction()

set(failures 0)
check_group(second.cpp result output)
if(NOT result EQUAL 0)
  message(SEND_ERROR "first.cpp with second.cpp should pass; it failed:\n${output}")
  math(EXPR failures "${failures} + 1")
endif()

foreach(case "third.cpp|Fixture|12|4" "fourth.cpp|TOLERANCE|6|2" "fifth.cpp|helper|17|3")
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 file)
  list(GET case 1 name)
  list(GET case 2 first_line)
  list(GET case 3 second_line)
  check_group(${file} result output)
  set(expected "unity group 'fixtures'" "the file-scope name '${name}'"
    "${FIXTURES}/first.cpp:${first_line}:" "${FIXTURES}/${file}:${second_line}:")
  if(result EQUAL 0)
    message(SEND_ERROR "first.cpp with ${file} should fail; it passed:\n${output}")
    math(EXPR failures "${failures} + 1")
    continue()
  endif()
  foreach(text IN LISTS expected)
    string(FIND "${output}" "${text}" at)
    if(at LESS 0)
      message(SEND_ERROR "first.cpp with ${file}: the message lacks \"${text}\":\n${output}")
      math(EXPR failures "${failures} + 1")
    endif()
  endforeach()
endforeach()
if(failures EQUAL 0)
  message(STATUS "the unity-group check passes the allowed repeats and names each clash")
endif()

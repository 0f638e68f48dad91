# With MASSSPRING_EXTERN_TEMPLATES, a unit that steps FastMassSpring<MassSpringSystem<double,
# Sparse>> leaves precompute() and step() undefined (nm: U) for instances.hpp's unit to define, and
# defines no copy of its own (nm: T or W). Reads the object file of
# benchmarks/compile_time/consumer.cpp compiled with the macro (tests/CMakeLists.txt).
# Usage: cmake -DNM=... -DOBJECT=... -P extern_templates.cmake
foreach(var NM OBJECT)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "extern_templates.cmake: ${var} is not set")
  endif()
endforeach()
execute_process(COMMAND ${NM} -C ${OBJECT} RESULT_VARIABLE result OUTPUT_VARIABLE symbols
  ERROR_VARIABLE err)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${NM} -C ${OBJECT} failed (${result}): ${err}")
endif()
string(REPLACE "\n" ";" lines "${symbols}")
foreach(member precompute step)
  set(undefined 0)
  set(defined 0)
  foreach(line IN LISTS lines)
    if(line MATCHES "massspring::FastMassSpring<massspring::MassSpringSystem<double, massspring::Sparse>.*>::${member}\\(")
      if(line MATCHES "^ +U ")
        math(EXPR undefined "${undefined} + 1")
      else()
        math(EXPR defined "${defined} + 1")
        message(STATUS "defined here: ${line}")
      endif()
    endif()
  endforeach()
  if(NOT undefined EQUAL 1 OR NOT defined EQUAL 0)
    message(FATAL_ERROR "FastMassSpring::${member}: ${undefined} undefined reference(s) (expected "
      "1) and ${defined} definition(s) (expected 0) in ${OBJECT}")
  endif()
  message(STATUS "FastMassSpring::${member}: referenced, not instantiated")
endforeach()

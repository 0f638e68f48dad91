# The system and the integrators do not include the geometry of boxes and meshes nor the surface
# contact pipeline: those come with the headers that make a box or a mesh collider
# (contact/colliders/box_shape.hpp, mesh_shape.hpp) or set a surface
# (contact/response/surface_contact.hpp). Lists each header's includes with the compiler's -M and
# fails when one of the heavy headers is among them (tests/CMakeLists.txt).
# Usage: cmake -DCXX=... -DINCLUDE=<repo>/include -DEIGEN=<dir>[|<dir>...] -P light_includes.cmake
foreach(var CXX INCLUDE EIGEN)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "light_includes.cmake: ${var} is not set")
  endif()
endforeach()
string(REPLACE "|" ";" eigen_dirs "${EIGEN}")
set(flags -std=c++17 -M "-I${INCLUDE}")
foreach(dir IN LISTS eigen_dirs)
  list(APPEND flags "-I${dir}")
endforeach()
set(light
  massspring/system/mass_spring_system.hpp
  massspring/integrators/fast_mass_spring.hpp
  massspring/integrators/backward_euler.hpp
  massspring/integrators/symplectic_euler.hpp
  massspring/integrators/forward_euler.hpp
  massspring/integrators/rk4.hpp)
set(heavy
  contact/colliders/triangle_mesh.hpp contact/colliders/mesh_shape.hpp
  contact/colliders/box_shape.hpp contact/distance/point_box.hpp
  contact/response/surface_contact.hpp contact/response/surface_candidates.hpp
  contact/response/surface_elements.hpp contact/response/impact_zones.hpp
  contact/broad_phase/box_hash.hpp contact/ccd/additive_ccd.hpp)
set(source ${CMAKE_CURRENT_BINARY_DIR}/light_includes.cpp)
set(failed "")
foreach(header IN LISTS light)
  file(WRITE ${source} "#include <${header}>\n")
  execute_process(COMMAND ${CXX} ${flags} ${source} RESULT_VARIABLE result
    OUTPUT_VARIABLE dependencies ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${CXX} -M on ${header} failed (${result}): ${err}")
  endif()
  string(REPLACE "\\" "/" dependencies "${dependencies}")
  foreach(h IN LISTS heavy)
    string(FIND "${dependencies}" "/massspring/${h}" at)
    if(NOT at EQUAL -1)
      list(APPEND failed "${header} includes massspring/${h}")
    endif()
  endforeach()
  message(STATUS "${header}: checked")
endforeach()
if(failed)
  string(REPLACE ";" "\n  " failed "${failed}")
  message(FATAL_ERROR "heavy headers pulled in:\n  ${failed}")
endif()

# Included by the package tests (run.cmake, readme.cmake). When CCACHE names the compiler cache the
# project's own build found, every consumer these tests configure compiles through it, with paths
# taken relative to the checkout (CCACHE_BASEDIR) and the working directory left out of the hash:
# a rerun, or a checkout in another folder, hits the objects an earlier run stored. What is
# compiled, and with which flags, is unchanged.
if(CCACHE)
  set(ENV{CMAKE_CXX_COMPILER_LAUNCHER} ${CCACHE})
  set(ENV{CCACHE_BASEDIR} ${SOURCE_DIR})
  set(ENV{CCACHE_NOHASHDIR} true)
endif()

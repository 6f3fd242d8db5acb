# The libraries verifybench links, all Debian packages, found the same way when the project is
# built and when an installed verifybench is found by a consumer (verifybenchConfig.cmake includes
# this file with the VERIFYBENCH_WITH_* values of the build). Libraries without a CMake config of
# their own become imported targets verifybench_dep::NAME, so that exported targets name no
# absolute path.
include(CMakeFindDependencyMacro)
macro(_verifybench_find)
  if(VERIFYBENCH_FINDING_INSTALLED)
    find_dependency(${ARGN})
  else()
    find_package(${ARGN} REQUIRED)
  endif()
endmacro()

function(_verifybench_import name)  # name, include file, library names...
  if(TARGET verifybench_dep::${name})
    return()
  endif()
  cmake_parse_arguments(ARG "" "HEADER" "SUFFIXES;LIBRARIES" ${ARGN})
  find_path(VERIFYBENCH_${name}_INCLUDE_DIR ${ARG_HEADER} PATH_SUFFIXES ${ARG_SUFFIXES})
  if(NOT VERIFYBENCH_${name}_INCLUDE_DIR)
    message(FATAL_ERROR "verifybench: ${ARG_HEADER} not found (VERIFYBENCH_WITH_* of ${name})")
  endif()
  add_library(verifybench_dep::${name} INTERFACE IMPORTED GLOBAL)
  target_include_directories(verifybench_dep::${name} SYSTEM INTERFACE
                             ${VERIFYBENCH_${name}_INCLUDE_DIR})
  foreach(lib ${ARG_LIBRARIES})
    find_library(VERIFYBENCH_${lib}_LIBRARY ${lib})
    if(NOT VERIFYBENCH_${lib}_LIBRARY)
      message(FATAL_ERROR "verifybench: library ${lib} not found (for ${name})")
    endif()
    target_link_libraries(verifybench_dep::${name} INTERFACE ${VERIFYBENCH_${lib}_LIBRARY})
  endforeach()
endfunction()

_verifybench_find(Eigen3 3.3 NO_MODULE)
_verifybench_find(nlohmann_json 3.9)
_verifybench_find(Threads)
_verifybench_find(Boost 1.71 CONFIG)  # header-only parts: Boost.Math (chi-square)
if(VERIFYBENCH_WITH_OPEN3D)
  _verifybench_find(OpenMP)  # the Open3D peer pins Open3D's OpenMP team to one thread
  _verifybench_find(Open3D)
endif()
if(VERIFYBENCH_WITH_OPENCV)
  _verifybench_find(OpenCV COMPONENTS core features2d)
  if(NOT TARGET verifybench_dep::opencv)
    add_library(verifybench_dep::opencv INTERFACE IMPORTED GLOBAL)
    target_include_directories(verifybench_dep::opencv SYSTEM INTERFACE ${OpenCV_INCLUDE_DIRS})
    target_link_libraries(verifybench_dep::opencv INTERFACE ${OpenCV_LIBS})
  endif()
endif()
if(VERIFYBENCH_WITH_PCL)
  # PCL's CMake config drags in VTK, whose Debian config needs MPI targets that nothing installs;
  # PCL's headers and libraries are found directly.
  _verifybench_import(pcl HEADER pcl/point_types.h SUFFIXES pcl-1.13 pcl-1.12 pcl-1.11
    LIBRARIES pcl_common pcl_registration pcl_sample_consensus pcl_kdtree pcl_search pcl_features
              pcl_filters pcl_io pcl_keypoints pcl_octree)
endif()
if(VERIFYBENCH_WITH_CLIQUER)
  _verifybench_import(cliquer HEADER cliquer/cliquer.h LIBRARIES cliquer)
endif()
if(VERIFYBENCH_WITH_IGRAPH)
  # Debian's igraph CMake config lists the static link closure (ARPACK, GLPK, ...) whose -dev
  # packages libigraph-dev does not pull in; the shared library carries its own dependencies.
  _verifybench_import(igraph HEADER igraph/igraph.h LIBRARIES igraph)
endif()
if(VERIFYBENCH_WITH_EMBREE)
  _verifybench_import(embree HEADER embree3/rtcore.h LIBRARIES embree3)
endif()
if(VERIFYBENCH_WITH_LOOP OR (NOT VERIFYBENCH_FINDING_INSTALLED AND VERIFYBENCH_WITH_CERES))
  _verifybench_find(Ceres 2.0)
endif()

# One place for per-target settings (as KISS-ICP's cmake/CompilerOptions.cmake does).
function(verifybench_set_options target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic
      -fno-math-errno)  # lets sqrt vectorise; we never read errno after maths
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
    endif()
  endif()
endfunction()

# verifybench_stage(NAME SOURCES... [DEPENDS targets...]): the static library of one stage,
# exported as verifybench::NAME. Headers are found as "STAGE/x.hpp" in the tree and as
# <verifybench/STAGE/x.hpp> (or "STAGE/x.hpp" below include/verifybench) once installed.
function(verifybench_stage name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(verifybench_${name} STATIC ${ARG_SOURCES})
  add_library(verifybench::${name} ALIAS verifybench_${name})
  set_target_properties(verifybench_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(verifybench_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<BUILD_INTERFACE:${VERIFYBENCH_BUILD_INCLUDE}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/verifybench>)
  target_link_libraries(verifybench_${name} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
  verifybench_set_options(verifybench_${name})
  set_property(GLOBAL APPEND PROPERTY VERIFYBENCH_STAGE_TARGETS verifybench_${name})
endfunction()

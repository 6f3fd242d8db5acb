# One place for per-target warnings (as KISS-ICP's cmake/CompilerOptions.cmake does).
function(verifybench_set_options target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-maybe-uninitialized
      -fno-math-errno)  # lets sqrt vectorise; we never read errno after maths
  endif()
endfunction()

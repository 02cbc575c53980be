# Helpers shared by every target of the build.

# A program built with LOOM_PROGRAM_SOURCES exports its GOMP_parallel, so that the libraries' calls bind to it (the
# linker would export it anyway while a library on the link line imports it; this says so).
function(loom_program target)
  target_link_options(${target} PRIVATE "LINKER:--export-dynamic-symbol=GOMP_parallel")
endfunction()

function(loom_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local -Wnon-virtual-dtor)
  if(LOOM_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# Linked into every program (the loom command, each test and benchmark), not from a library: the process's
# allocator policy (engine/core/allocator.hpp) and the OpenMP regions of one (engine/linalg/openmp_regions_of_one.cpp),
# which must be the executable's own to take effect. Compiled once, as object files that every program's link names
# (an object on the link line is always linked, unlike a static library's member nobody refers to).
add_library(loom_program_objects OBJECT
  ${PROJECT_SOURCE_DIR}/engine/core/allocator_at_start.cpp
  ${PROJECT_SOURCE_DIR}/engine/linalg/openmp_regions_of_one.cpp)
target_include_directories(loom_program_objects PRIVATE ${PROJECT_SOURCE_DIR})
loom_set_warnings(loom_program_objects)
set(LOOM_PROGRAM_SOURCES $<TARGET_OBJECTS:loom_program_objects>)

# loom_add_test(NAME name SOURCES a.cpp ... [LABELS unit verification scene stress] [LIBS ...])
function(loom_add_test)
  cmake_parse_arguments(T "" "NAME" "SOURCES;LABELS;LIBS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES} ${LOOM_PROGRAM_SOURCES})
  loom_program(${T_NAME})
  target_link_libraries(${T_NAME} PRIVATE loom_testing GTest::gtest_main ${T_LIBS})
  loom_set_warnings(${T_NAME})
  # The solver thread pins of the loom program (engine/cli/main.cpp) for tests that run systems in-process.
  gtest_discover_tests(${T_NAME}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES LABELS "${T_LABELS}" ENVIRONMENT "OMP_THREAD_LIMIT=1;OPENBLAS_NUM_THREADS=1"
    DISCOVERY_TIMEOUT 60)
endfunction()

# loom_add_benchmark(NAME bench_x SOURCES bench_x.cpp [LIBS ...]): also a ctest smoke run (label perf).
function(loom_add_benchmark)
  cmake_parse_arguments(B "" "NAME;SMOKE" "SOURCES;LIBS" ${ARGN})
  if(NOT B_SMOKE)
    set(B_SMOKE "/1024/|/1000/|/16/")  # the smallest size of most benchmarks
  endif()
  add_executable(${B_NAME} ${B_SOURCES} ${LOOM_PROGRAM_SOURCES})
  loom_program(${B_NAME})
  target_link_libraries(${B_NAME} PRIVATE benchmark::benchmark ${B_LIBS})
  loom_set_warnings(${B_NAME})
  if(LOOM_BUILD_TESTS)
    add_test(NAME ${B_NAME}_smoke COMMAND ${B_NAME} --benchmark_min_time=0.01 --benchmark_filter=${B_SMOKE})
    set_tests_properties(${B_NAME}_smoke PROPERTIES LABELS "perf_smoke" WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  endif()
endfunction()

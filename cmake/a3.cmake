# Helpers shared by every folder's CMakeLists.txt.

# Precompiled headers (A3_PCH, on by default): the heavy headers every test includes, parsed once
# for all of them, and the same for the `a3rig` program's commands (CLI11 as well), the heaviest
# part of the program's own build. Not for the libraries: GCC 12 at -O3 then reports its own
# std::string internals (false positives the system-header silence hides without one).
option(A3_PCH "Precompile the heaviest headers the test programs and the a3rig program share" ON)
set(A3_PCH_HEADERS <nlohmann/json.hpp> <string> <vector> <map> <memory> <functional> <chrono>
    <optional> <filesystem>)

# a3_library(NAME SOURCES ... DEPS ...): a static library whose headers are included
# from the repository root. Its code is compiled as the compiler's default for programs
# (position-independent executable, -fPIE on Debian), not as for a shared library (-fPIC): the
# libraries only ever go into programs, and -fPIC would have GCC assume every public function
# may be replaced at load time, so none is inlined into another and calls go through the PLT.
function(a3_library name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${A_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_SOURCE_DIR} ${A3_GENERATED_DIR})
  target_link_libraries(${name} PUBLIC ${A_DEPS})
endfunction()

# Test programs are compiled at -O1 (the libraries they test keep the build type's -O3): a test's
# own code is assertions and set-up, and -O3 made it a third slower to compile for nothing. They
# share one precompiled header (GoogleTest, nlohmann-json, the standard library), parsed once.
# -pthread on every one (most get it from a library anyway): it defines _REENTRANT, which a
# precompiled header must agree on.
set(A3_TEST_COMPILE_OPTIONS -O1 -pthread)
# GCC 12 loses the system-header silence of a precompiled <string> and <new>, so its known false
# positives in std::string copies (bugs 105329, 105651) and in a test's own operator new/delete
# pair surface as errors: off for the tests only (the libraries are compiled without a PCH).
if(A3_PCH AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  list(APPEND A3_TEST_COMPILE_OPTIONS -Wno-array-bounds -Wno-stringop-overflow -Wno-mismatched-new-delete)
endif()
if(A3_PCH AND A3_BUILD_TESTS)
  find_package(GTest REQUIRED)
  add_library(a3_test_pch OBJECT ${CMAKE_SOURCE_DIR}/cmake/pch_anchor.cpp)
  target_include_directories(a3_test_pch PRIVATE ${CMAKE_SOURCE_DIR} ${A3_GENERATED_DIR})
  target_compile_definitions(a3_test_pch PRIVATE
    A3_SOURCE_DIR="${CMAKE_SOURCE_DIR}" A3_BINARY_DIR="${CMAKE_BINARY_DIR}"
    A3_SHARED_DIR_DEFAULT="${A3_SHARED_DIR_DEFAULT}")
  target_compile_options(a3_test_pch PRIVATE ${A3_TEST_COMPILE_OPTIONS})
  target_link_libraries(a3_test_pch PRIVATE GTest::gtest nlohmann_json::nlohmann_json Threads::Threads)
  target_precompile_headers(a3_test_pch PRIVATE <gtest/gtest.h> ${A3_PCH_HEADERS})
endif()

# a3_gtest(NAME SOURCES ... DEPS ... [LABELS label] [TIMEOUT s] [SERIAL]): a GoogleTest program,
# each test discovered by CTest. Tests find ../shared through A3_SHARED_DIR. SERIAL: tests that
# judge wall-clock timing with bounds (not lockstep behaviour) run with nothing beside them
# under `ctest -j`, so that the suite's deliberately loaded tests cannot starve them.
function(a3_gtest name)
  cmake_parse_arguments(A "SERIAL" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
  if(NOT A_TIMEOUT)
    set(A_TIMEOUT 300)
  endif()
  add_executable(${name} ${A_SOURCES})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  target_compile_options(${name} PRIVATE ${A3_TEST_COMPILE_OPTIONS})
  if(TARGET a3_test_pch)
    target_precompile_headers(${name} REUSE_FROM a3_test_pch)
  endif()
  target_include_directories(${name} PRIVATE ${CMAKE_SOURCE_DIR} ${A3_GENERATED_DIR})
  target_compile_definitions(${name} PRIVATE
    A3_SOURCE_DIR="${CMAKE_SOURCE_DIR}" A3_BINARY_DIR="${CMAKE_BINARY_DIR}"
    A3_SHARED_DIR_DEFAULT="${A3_SHARED_DIR_DEFAULT}")
  target_link_libraries(${name} PRIVATE ${A_DEPS} GTest::gtest GTest::gtest_main Threads::Threads)
  set(_a3_serial "")
  if(A_SERIAL)
    set(_a3_serial RUN_SERIAL TRUE)
  endif()
  gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60
    PROPERTIES TIMEOUT ${A_TIMEOUT} ${_a3_serial})
  a3_label_discovered_tests(${name} "${A_LABELS}")
endfunction()

# Labels for the tests gtest_discover_tests finds in program NAME. Its PROPERTIES keep only the
# first element of a list (LABELS "x;faults" arrived as LABELS x), so every label is set by a
# file CTest reads after the discovery, over the list the discovery leaves in NAME_TESTS.
function(a3_label_discovered_tests name labels)
  if(NOT labels)
    return()
  endif()
  set(file "${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake")
  file(WRITE "${file}"
    "if(${name}_TESTS)\n  set_tests_properties(\${${name}_TESTS} PROPERTIES LABELS \"${labels}\")\nendif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${file}")
endfunction()

# a3_bench(NAME SOURCES ... DEPS ...): a Google Benchmark (or plain) benchmark program.
function(a3_bench name)
  cmake_parse_arguments(A "PLAIN" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bench)
  target_include_directories(${name} PRIVATE ${CMAKE_SOURCE_DIR} ${A3_GENERATED_DIR})
  target_compile_definitions(${name} PRIVATE
    A3_SOURCE_DIR="${CMAKE_SOURCE_DIR}" A3_SHARED_DIR_DEFAULT="${A3_SHARED_DIR_DEFAULT}")
  target_link_libraries(${name} PRIVATE ${A_DEPS} Threads::Threads)
  if(NOT A_PLAIN)
    target_link_libraries(${name} PRIVATE benchmark::benchmark)
  endif()
endfunction()

# a3_add_existing_subdirectories(): add every direct subfolder holding a CMakeLists.txt.
macro(a3_add_existing_subdirectories)
  file(GLOB _a3_children LIST_DIRECTORIES true ${CMAKE_CURRENT_SOURCE_DIR}/*)
  foreach(_a3_child ${_a3_children})
    if(IS_DIRECTORY ${_a3_child} AND EXISTS ${_a3_child}/CMakeLists.txt)
      add_subdirectory(${_a3_child})
    endif()
  endforeach()
endmacro()

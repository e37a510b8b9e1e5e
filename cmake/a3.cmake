# Helpers shared by every folder's CMakeLists.txt.

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

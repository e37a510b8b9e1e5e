# Sanitizer and fuzzing builds, chosen at configure time (both off by default):
#   A3_SANITIZE  AddressSanitizer + UndefinedBehaviorSanitizer for every target (gcc or clang);
#                undefined behaviour aborts instead of printing and going on
#                (pointer-overflow: see below).
#   A3_FUZZ      the libFuzzer targets in fuzz/ (clang only): every library is compiled with
#                -fsanitize=fuzzer-no-link,address,undefined, each fuzz_<name> program links
#                -fsanitize=fuzzer. See fuzz/README.md and scripts/fuzz.sh.
option(A3_SANITIZE "Build everything with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(A3_FUZZ "Build the libFuzzer targets in fuzz/ (clang; implies the sanitizers)" OFF)

# pointer-overflow stays recoverable so that fuzz/ubsan.supp can silence it in RapidJSON 1.1.0
# code (offsets added to null pointers; Debian rapidjson-dev, fixed upstream after 1.1.0): run with
# UBSAN_OPTIONS=halt_on_error=1:suppressions=<repo>/fuzz/ubsan.supp, as scripts/fuzz.sh does.
set(A3_SANITIZER_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=undefined
    -fsanitize-recover=pointer-overflow -fno-omit-frame-pointer)

if(A3_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "A3_FUZZ needs clang (libFuzzer), not ${CMAKE_CXX_COMPILER_ID}: "
                        "configure with -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link ${A3_SANITIZER_FLAGS})
  add_link_options(-fsanitize=address,undefined)
elseif(A3_SANITIZE)
  add_compile_options(${A3_SANITIZER_FLAGS})
  add_link_options(-fsanitize=address,undefined)
  # GCC 12's -Wmaybe-uninitialized misfires on std::function inside std::regex once ASan
  # instruments it (GCC bug 105562): a false positive under -Werror, off in this build only.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options(-Wno-maybe-uninitialized)
  endif()
endif()

# Flags of a fuzzing build (FEEDPLAN_BUILD_FUZZERS): clang's libFuzzer coverage instrumentation and
# AddressSanitizer + UndefinedBehaviorSanitizer on every feedplan library, so that a reader's bug is
# found where it happens. Undefined behaviour aborts (no recovery), so libFuzzer records it as a crash.
# The harnesses themselves link -fsanitize=fuzzer (tests/fuzz/CMakeLists.txt).
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "FEEDPLAN_BUILD_FUZZERS needs clang (libFuzzer); configure with -DCMAKE_CXX_COMPILER=clang++ "
                      "in a build directory of its own (tests/fuzz/run-fuzzers.sh does)")
endif()
set(FEEDPLAN_SANITIZERS address,undefined)
add_compile_options(-fsanitize=fuzzer-no-link,${FEEDPLAN_SANITIZERS} -fno-sanitize-recover=all
                    -fno-omit-frame-pointer -g)
add_link_options(-fsanitize=${FEEDPLAN_SANITIZERS})

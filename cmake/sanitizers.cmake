# FINFLEX_SANITIZE: sanitizers every target of the build is compiled and linked with,
# as -fsanitize takes them (gcc or clang): "address,undefined" or "thread", for
# example; empty (the default) for none. A finding stops the program (no recovery),
# so a test fails on the first one. The suppressions and run-time options CI uses are
# in tests/sanitizers/ (README.md there).
set(FINFLEX_SANITIZE "" CACHE STRING
    "Sanitizers to build with, e.g. address,undefined or thread (empty: none)")
if(FINFLEX_SANITIZE)
  # -O1 (after the build type's -O3, so it wins): what the sanitizers' documentation
  # recommends, and half the build time; -g1: line numbers in reports.
  set(FINFLEX_SANITIZE_COMPILE_FLAGS
      -fsanitize=${FINFLEX_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer -O1 -g1)
  set(FINFLEX_SANITIZE_LINK_FLAGS -fsanitize=${FINFLEX_SANITIZE})
  add_compile_options(${FINFLEX_SANITIZE_COMPILE_FLAGS})
  add_link_options(${FINFLEX_SANITIZE_LINK_FLAGS})
  message(STATUS "FinFlex: built with -fsanitize=${FINFLEX_SANITIZE}")
endif()

# FINFLEX_FUZZ: libFuzzer harnesses (clang only; tests/fuzz_*/): every target gets
# libFuzzer's coverage instrumentation, the harnesses its driver. Usually with
# FINFLEX_SANITIZE=address,undefined.
if(NOT DEFINED FINFLEX_FUZZ)
  option(FINFLEX_FUZZ "Build the libFuzzer harnesses (clang)" OFF)
endif()
if(FINFLEX_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "FINFLEX_FUZZ needs clang (libFuzzer): configure with CXX=clang++")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

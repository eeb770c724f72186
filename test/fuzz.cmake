# libFuzzer targets (test/fuzz/) and the smoke test that runs each one for a few seconds.
# Included from test/CMakeLists.txt. The fuzzers need clang++ with libFuzzer and are built with
# the package when it is there; fuzz_smoke_test fails, naming what to install, when it is not.
include(ExternalProject)

find_program(PDA_FUZZ_CLANGXX NAMES clang++-14 clang++)
set(PDA_FUZZERS_AVAILABLE 0)
if(PDA_FUZZ_CLANGXX)
  # A one-line probe: clang++ alone is not enough, libFuzzer's runtime (libclang-rt-*-dev) too.
  set(probe_dir ${CMAKE_CURRENT_BINARY_DIR}/fuzz_probe)
  file(WRITE ${probe_dir}/probe.cpp
       "#include <cstddef>\n#include <cstdint>\n"
       "extern \"C\" int LLVMFuzzerTestOneInput(const uint8_t*, size_t) { return 0; }\n")
  execute_process(
    COMMAND ${PDA_FUZZ_CLANGXX} -fsanitize=fuzzer,address,undefined ${probe_dir}/probe.cpp
            -o ${probe_dir}/probe
    RESULT_VARIABLE probe_result OUTPUT_QUIET ERROR_QUIET)
  if(probe_result EQUAL 0)
    set(PDA_FUZZERS_AVAILABLE 1)
  endif()
endif()

set(PDA_FUZZ_BINARY_DIR ${CMAKE_CURRENT_BINARY_DIR}/fuzz)
if(PDA_FUZZERS_AVAILABLE)
  ExternalProject_Add(pda_fuzzers
    SOURCE_DIR ${PDA_REPO_DIR}/test/fuzz
    BINARY_DIR ${PDA_FUZZ_BINARY_DIR}
    CMAKE_CACHE_ARGS
      -DCMAKE_CXX_COMPILER:FILEPATH=${PDA_FUZZ_CLANGXX}
      -DCMAKE_BUILD_TYPE:STRING=RelWithDebInfo
      -DPDA_SOURCE_DIR:PATH=${PDA_REPO_DIR}
      -DPDA_FUZZ_INCLUDE_DIRS:STRING=${catkin_INCLUDE_DIRS};${EIGEN3_INCLUDE_DIR}
      -DPDA_FUZZ_LIBRARY_DIRS:STRING=${catkin_LIBRARY_DIRS}
    INSTALL_COMMAND ""
    # The sub-build tracks its own dependencies; always let it look.
    BUILD_ALWAYS 1)
else()
  message(WARNING "clang++ with libFuzzer not found: the fuzzers are not built and "
                  "fuzz_smoke_test will fail (install clang and libclang-rt-14-dev)")
endif()

catkin_add_gtest(fuzz_smoke_test fuzz_smoke_test.cpp)
target_compile_options(fuzz_smoke_test PRIVATE ${PDA_WARNINGS})
target_link_libraries(fuzz_smoke_test pda_test_support gtest_main)
target_compile_definitions(fuzz_smoke_test PRIVATE
  PDA_FUZZERS_AVAILABLE=${PDA_FUZZERS_AVAILABLE}
  PDA_FUZZ_BINARY_DIR="${PDA_FUZZ_BINARY_DIR}"
  PDA_FUZZ_SOURCE_DIR="${PDA_REPO_DIR}/test/fuzz")
if(PDA_FUZZERS_AVAILABLE)
  add_dependencies(fuzz_smoke_test pda_fuzzers)
endif()

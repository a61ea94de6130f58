# DRAPE_FUZZ=ON builds every library with libFuzzer's coverage instrumentation plus
# AddressSanitizer and UndefinedBehaviorSanitizer, and the harnesses of fuzz/ (docs/hardening.md).
# Clang only, in a build folder of its own: scripts/fuzz.sh configures it.
if(DRAPE_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "DRAPE_FUZZ=ON needs clang (CC=clang CXX=clang++); got ${CMAKE_CXX_COMPILER_ID}")
  endif()
  if(DRAPE_SANITIZE)
    message(FATAL_ERROR "DRAPE_FUZZ=ON already enables ASan + UBSan; leave DRAPE_SANITIZE OFF")
  endif()
  # -fno-sanitize-recover: a UBSan finding stops the run like a crash, so libFuzzer keeps
  # the input. vptr needs RTTI everywhere, which the system libraries' headers do not promise.
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=vptr
                      -fno-sanitize-recover=undefined -fno-omit-frame-pointer -gline-tables-only)
  add_link_options(-fsanitize=address,undefined)
endif()

# drape_add_fuzzer(<name> SOURCES <files...> LIBRARIES <targets...>): with DRAPE_FUZZ, the
# harness fuzz_<name> (LLVMFuzzerTestOneInput in its sources), linked with libFuzzer's main.
# Its seed corpus is fuzz/corpus/<name>/ and its kept crashes fuzz/regressions/<name>/.
# Without DRAPE_FUZZ (a build with tests): replay_<name>, the same sources with
# fuzz/replay_main.cpp, and the ctest test "fuzz: replay <name>", which runs every kept crash
# and every seed once (in the Release suite, and under ASan + UBSan in scripts/test.sh).
function(drape_add_fuzzer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES" ${ARGN})
  if(DRAPE_FUZZ)
    set(target fuzz_${name})
    add_executable(${target} ${ARG_SOURCES})
    target_link_options(${target} PRIVATE -fsanitize=fuzzer)
  else()
    set(target replay_${name})
    add_executable(${target} ${ARG_SOURCES} ${PROJECT_SOURCE_DIR}/fuzz/replay_main.cpp)
    set(inputs ${PROJECT_SOURCE_DIR}/fuzz/corpus/${name})
    if(EXISTS ${PROJECT_SOURCE_DIR}/fuzz/regressions/${name})
      list(PREPEND inputs ${PROJECT_SOURCE_DIR}/fuzz/regressions/${name})
    endif()
    add_test(NAME "fuzz: replay ${name}" COMMAND ${target} ${inputs})
    set_tests_properties("fuzz: replay ${name}" PROPERTIES TIMEOUT 600)
  endif()
  target_link_libraries(${target} PRIVATE drape_fuzz_common ${ARG_LIBRARIES})
  set(DRAPE_FUZZ_TARGET ${target} PARENT_SCOPE)
  set_property(GLOBAL APPEND PROPERTY DRAPE_FUZZERS ${name})
endfunction()

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

# drape_add_fuzzer(<name> SOURCES <files...> LIBRARIES <targets...>): the harness
# fuzz_<name> (LLVMFuzzerTestOneInput in its sources), linked with libFuzzer's main. Its
# seed corpus is fuzz/corpus/<name>/ and its kept crashes fuzz/regressions/<name>/.
function(drape_add_fuzzer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES" ${ARGN})
  add_executable(fuzz_${name} ${ARG_SOURCES})
  target_link_libraries(fuzz_${name} PRIVATE drape_fuzz_common ${ARG_LIBRARIES})
  target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
  set_property(GLOBAL APPEND PROPERTY DRAPE_FUZZERS ${name})
endfunction()

# drape_set_warnings(<target>): the project's warning set, as errors unless
# DRAPE_WARNINGS_AS_ERRORS is OFF. Third-party headers are included as SYSTEM.
function(drape_set_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wnon-virtual-dtor>
    $<$<AND:$<COMPILE_LANGUAGE:CXX>,$<CXX_COMPILER_ID:GNU>>:-Wshadow=local>  # GCC's spelling
    $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -Wpedantic>)
  if(DRAPE_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  # Under the sanitizers GCC 12 reports maybe-uninitialized inside libstdc++'s std::regex
  # (std::function moves in regex_automaton.h, seen in librecover's report.cpp): a known
  # false positive of instrumented code that -Werror would make a build failure.
  if(DRAPE_SANITIZE AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE $<$<COMPILE_LANGUAGE:CXX>:-Wno-maybe-uninitialized>)
  endif()
endfunction()

// Runs the drape CLI as a user would and captures its exit code and output.
#pragma once

#include <string>

namespace drape::test {

struct CliResult {
    int exit_code = -1;
    std::string out;  ///< stdout and stderr, interleaved
};

/// Runs `drape <args>` (args are passed to the shell as written; quote paths).
CliResult run_drape(const std::string& args);

}  // namespace drape::test

// Runs a shell command from a test and captures its exit code and output.
#pragma once

#include <string>

namespace drape::test {

struct CommandResult {
    int exit_code = -1;  ///< -1 when the command could not be run or did not exit normally
    std::string out;     ///< stdout and stderr, interleaved
};

/// Runs `command` through the shell (`sh -c`), with stderr merged into stdout.
CommandResult run_command(const std::string& command);

}  // namespace drape::test

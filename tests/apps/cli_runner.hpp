// Runs the drape CLI as a user would and captures its exit code and output.
#pragma once

#include "run_command.hpp"

#include <string>

namespace drape::test {

using CliResult = CommandResult;

/// Runs `drape <args>` (args are passed to the shell as written; quote paths).
CliResult run_drape(const std::string& args);

}  // namespace drape::test

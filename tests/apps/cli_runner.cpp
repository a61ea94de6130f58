#include "cli_runner.hpp"

namespace drape::test {

CliResult run_drape(const std::string& args) {
    return run_command(std::string("\"") + DRAPE_CLI + "\" " + args);
}

}  // namespace drape::test

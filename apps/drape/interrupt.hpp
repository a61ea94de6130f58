// Ctrl-C and SIGTERM for long commands (app layer): the handler only sets a flag; the
// command's progress callback reads it and asks the library to stop, which then returns
// normally (nothing half-written).
#pragma once

#include <string>

namespace drape::app {

/// Installs SIGINT and SIGTERM handlers that set the flag (once per process; idempotent).
void install_interrupt_handlers();
/// True once SIGINT or SIGTERM arrived.
bool interrupted();

/// Thrown by a command to end with a given exit status and message (main prints it).
struct CommandExit {
    int code = 1;
    std::string message;
};

}  // namespace drape::app

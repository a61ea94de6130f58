// Runs a parser of untrusted input in a child process, so that a crash or a hang inside a
// third-party library it calls (libhdf5 on a damaged file: docs/hardening.md) is reported as
// an error instead of taking the host process down. POSIX (fork, pipe, poll, waitpid).
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace drape::core {

struct IsolatedOutcome {
    enum class Kind {
        finished,      ///< `work` returned
        invalid_input, ///< `work` threw drape::InvalidInput (message in `message`)
        io_error,      ///< `work` threw drape::IoError or another exception (message in `message`)
        crashed,       ///< the child died: a signal (`signal`), or an exit it did not choose (`exit_code`)
        timed_out,     ///< still running after the time limit: killed
        not_started,   ///< fork or pipe failed (`message`); nothing ran
    } kind = Kind::not_started;
    std::string message;
    std::string output;  ///< what `work` returned (finished only)
    int signal = 0;
    int exit_code = 0;
    double seconds = 0;
};

/// Runs `work` in a forked child of the calling process, which only the calling thread
/// continues (so `work` must not need other threads or locks another thread may hold:
/// parse bytes already in memory), and returns the bytes it returned (at most
/// `max_output_bytes`; more is a crash). Nothing `work` touched reaches this process but those
/// bytes: the caller decodes and checks them as untrusted input. The child's crash handlers
/// are reset to the default, and a sanitizer's death callback (libFuzzer's) is cleared, so
/// that the child's crash is only reported here. Waits at most `timeout_s` seconds, then
/// kills the child. Never throws; the caller turns the outcome into its own error.
IsolatedOutcome run_isolated(const std::function<std::string()>& work, double timeout_s,
                             std::size_t max_output_bytes);

/// Turns an outcome other than `finished` into the caller's error: the child's InvalidInput
/// or IoError as thrown there, else an IoError "<subject>: <library> crashed parsing it
/// (signal N, in the isolated reader: this process is unharmed)" (or did not finish within
/// `timeout_s` s, or the reader could not start). `subject` names the file, e.g. "cannot
/// read 'x.h5'"; `library` the parser, e.g. "the HDF5 library". Returns on `finished`.
void throw_unless_finished(const IsolatedOutcome& outcome, const std::string& subject, const std::string& library,
                           double timeout_s);

}  // namespace drape::core

#include <drape/core/isolated.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

// A sanitizer runtime's hook (libFuzzer sets one to save the crashing input): weak, absent
// in normal builds.
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));
extern "C" void __sanitizer_set_report_fd(void* fd) __attribute__((weak));

namespace drape::core {

namespace {

constexpr int kExitInvalidInput = 3;
constexpr int kExitIoError = 4;
constexpr std::size_t kMaxMessageBytes = 64 * 1024;

void write_all(int fd, const std::string& text) {
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;
        done += static_cast<std::size_t>(n);
    }
}

[[noreturn]] void child(int fd, const std::function<std::string()>& work) {
    for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP}) std::signal(s, SIG_DFL);
    if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(nullptr);
    // A sanitizer's report of the child's crash would read as the host's: the outcome
    // (crashed, exit code) is the report.
    if (__sanitizer_set_report_fd) {
        const int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (null_fd >= 0) __sanitizer_set_report_fd(reinterpret_cast<void*>(static_cast<std::intptr_t>(null_fd)));
    }
    int code = 0;
    std::string message;
    try {
        write_all(fd, work());
        ::_exit(0);  // no atexit handlers, no stdio flush: they belong to the parent
    } catch (const InvalidInput& e) {
        code = kExitInvalidInput;
        message = e.what();
    } catch (const std::exception& e) {
        code = kExitIoError;
        message = e.what();
    } catch (...) {
        code = kExitIoError;
        message = "an unknown exception";
    }
    if (message.size() > kMaxMessageBytes) message.resize(kMaxMessageBytes);
    write_all(fd, message);
    ::_exit(code);  // no atexit handlers, no stdio flush: they belong to the parent
}

}  // namespace

IsolatedOutcome run_isolated(const std::function<std::string()>& work, double timeout_s,
                             std::size_t max_output_bytes) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    IsolatedOutcome out;
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
        out.message = std::string("pipe failed: ") + std::strerror(errno);
        return out;
    }
    const pid_t pid = ::fork();
    if (pid < 0) {
        out.message = std::string("fork failed: ") + std::strerror(errno);
        ::close(fds[0]);
        ::close(fds[1]);
        return out;
    }
    if (pid == 0) {
        ::close(fds[0]);
        child(fds[1], work);
    }
    ::close(fds[1]);
    ::fcntl(fds[0], F_SETFL, ::fcntl(fds[0], F_GETFL) | O_NONBLOCK);
    std::string message;
    const std::size_t max_bytes = std::max(max_output_bytes, kMaxMessageBytes);
    bool too_much = false;
    int status = 0;
    bool exited = false;
    const auto drain = [&] {
        char buffer[4096];
        for (;;) {
            const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
            if (n > 0) {
                if (message.size() + static_cast<std::size_t>(n) <= max_bytes)
                    message.append(buffer, static_cast<std::size_t>(n));
                else
                    too_much = true;
                continue;
            }
            if (n < 0 && errno == EINTR) continue;
            return;  // EOF or nothing more now
        }
    };
    // Poll in short slices and check the child each time: the pipe's write end may also be
    // held by a process another thread forked meanwhile, so EOF alone is not the signal.
    while (!exited) {
        pollfd p{fds[0], POLLIN, 0};
        ::poll(&p, 1, 50);
        drain();
        const pid_t w = ::waitpid(pid, &status, WNOHANG);
        if (w == pid) {
            exited = true;
            drain();
        } else if (w < 0 && errno != EINTR) {
            break;
        } else if (std::chrono::duration<double>(Clock::now() - t0).count() > timeout_s) {
            ::kill(pid, SIGKILL);
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            ::close(fds[0]);
            out.kind = IsolatedOutcome::Kind::timed_out;
            out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
            return out;
        }
    }
    ::close(fds[0]);
    out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    out.message = message;
    if (!exited) {
        out.kind = IsolatedOutcome::Kind::not_started;
        out.message = "waiting for the child process failed";
    } else if (WIFSIGNALED(status)) {
        out.kind = IsolatedOutcome::Kind::crashed;
        out.signal = WTERMSIG(status);
    } else if (WIFEXITED(status)) {
        out.exit_code = WEXITSTATUS(status);
        if (out.exit_code == 0) {
            out.kind = too_much ? IsolatedOutcome::Kind::crashed : IsolatedOutcome::Kind::finished;
            if (!too_much) out.output = std::move(out.message);
            out.message = too_much ? "more output than " + std::to_string(max_output_bytes) + " bytes" : "";
        }
        else if (out.exit_code == kExitInvalidInput) out.kind = IsolatedOutcome::Kind::invalid_input;
        else if (out.exit_code == kExitIoError) out.kind = IsolatedOutcome::Kind::io_error;
        else out.kind = IsolatedOutcome::Kind::crashed;  // e.g. a sanitizer's exit after its report
    }
    return out;
}

void throw_unless_finished(const IsolatedOutcome& o, const std::string& subject, const std::string& library,
                           double timeout_s) {
    using K = IsolatedOutcome::Kind;
    switch (o.kind) {
        case K::finished: return;
        case K::invalid_input: throw InvalidInput(o.message);
        case K::io_error: throw IoError(o.message);
        case K::crashed: {
            const std::string how = o.signal ? "signal " + std::to_string(o.signal) + ", " + ::strsignal(o.signal)
                                    : o.message.empty() ? "exit code " + std::to_string(o.exit_code)
                                                        : o.message;
            throw IoError(subject + ": " + library + " crashed parsing it (" + how +
                          ", in the isolated reader: this process is unharmed); the file is damaged "
                          "(docs/hardening.md)");
        }
        case K::timed_out:
            throw IoError(subject + ": " + library + " did not finish parsing it within " + std::to_string(timeout_s) +
                          " s (killed; docs/hardening.md)");
        case K::not_started: throw IoError(subject + ": the isolated reader could not start: " + o.message);
    }
}

}  // namespace drape::core

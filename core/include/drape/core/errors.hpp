// Drape's small exception tree, shared by every library (drape::core).
//
// Broken preconditions throw InvalidInput with a message naming the argument and the
// value; failed reads and writes throw IoError naming the file. Expected numerical
// outcomes (no convergence, a failed step) are never exceptions: they go into the
// Summary struct of the algorithm that produced them.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace drape {

/// A precondition of a public function was broken (bad argument, shape, range, file content).
class InvalidInput : public std::invalid_argument {
public:
    explicit InvalidInput(const std::string& what) : std::invalid_argument(what) {}
};

/// A file could not be read or written.
class IoError : public std::runtime_error {
public:
    explicit IoError(const std::string& what) : std::runtime_error(what) {}
};

/// An operation was cancelled by the caller's progress callback.
class Cancelled : public std::runtime_error {
public:
    explicit Cancelled(const std::string& what) : std::runtime_error(what) {}
};

namespace detail {
template <class... Args>
std::string concat(const Args&... args) {
    std::ostringstream os;
    (os << ... << args);
    return os.str();
}
}  // namespace detail

/// Throws InvalidInput built from the streamed arguments when `condition` is false.
template <class... Args>
void require(bool condition, const Args&... message) {
    if (!condition) throw InvalidInput(detail::concat(message...));
}

}  // namespace drape

// Shared helpers of the libFuzzer harnesses (docs/hardening.md).
//
// A harness feeds its input to one public reader. The contract checked, besides what
// ASan and UBSan catch: a reader either returns or throws drape::InvalidInput /
// drape::IoError. Any other exception escaping (nlohmann::json's, cv::Exception,
// std::out_of_range, std::bad_alloc, ...) is a finding: fail() prints it and aborts, so
// libFuzzer keeps the input.
#pragma once

#include <drape/core/errors.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <typeinfo>

namespace drape::fuzz {

/// A per-process scratch folder (under $TMPDIR or /tmp), created on first use.
const std::filesystem::path& scratch_dir();

/// Writes `size` bytes to scratch_dir()/name and returns the path.
std::filesystem::path write_input(const std::string& name, const std::uint8_t* data, std::size_t size);

/// Reports an escaped exception and aborts (the input is a finding).
[[noreturn]] void fail(const char* what);

/// Runs `f`; InvalidInput and IoError are the documented outcomes of bad input and pass
/// (their message must not be empty); anything else is a finding.
template <class F>
void expect_clean(F&& f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        if (!*e.what()) fail("InvalidInput with an empty message");
    } catch (const IoError& e) {
        if (!*e.what()) fail("IoError with an empty message");
    } catch (const std::exception& e) {
        fail((std::string(typeid(e).name()) + ": " + e.what()).c_str());
    } catch (...) {
        fail("a non-std exception");
    }
}

}  // namespace drape::fuzz

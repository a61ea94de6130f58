#include "test_paths.hpp"

#include <cstdlib>
#include <system_error>

namespace drape::test {

std::filesystem::path shared_dir() {
    if (const char* env = std::getenv("DRAPE_SHARED_DIR"); env && *env) return env;
    return DRAPE_SHARED_DIR_DEFAULT;
}

std::filesystem::path shared_path(const std::string& relative) {
    std::error_code ec;
    const auto p = shared_dir() / relative;
    return std::filesystem::exists(p, ec) ? p : std::filesystem::path();
}

std::filesystem::path scratch_dir(const std::string& name) {
    std::error_code ec;
    auto p = std::filesystem::temp_directory_path() / ("drape_test_" + name);
    std::filesystem::remove_all(p, ec);
    std::filesystem::create_directories(p);
    return p;
}

std::filesystem::path source_dir() { return DRAPE_SOURCE_DIR; }

}  // namespace drape::test

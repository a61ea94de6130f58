#include "fuzz_common.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <typeinfo>
#include <unistd.h>

namespace drape::fuzz {

const std::filesystem::path& scratch_dir() {
    static const std::filesystem::path dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::filesystem::path d = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") /
                                  ("drape-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

std::filesystem::path write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
    const auto path = scratch_dir() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) {
        std::fprintf(stderr, "fuzz harness: cannot write %s\n", path.c_str());
        std::abort();
    }
    return path;
}

void fail(const char* what) {
    std::fprintf(stderr, "fuzz harness: an exception other than drape::InvalidInput/IoError escaped: %s\n", what);
    std::abort();
}

}  // namespace drape::fuzz

#include <drape/core/limits.hpp>

#include <drape/core/errors.hpp>

#include <fstream>
#include <system_error>

namespace drape::limits {

std::string read_file_capped(const std::filesystem::path& path, std::int64_t max_bytes, const std::string& what) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw IoError("cannot read " + what + " '" + path.string() + "': file missing or not a regular file");
    const auto bytes = std::filesystem::file_size(path, ec);
    if (ec) throw IoError("cannot read " + what + " '" + path.string() + "': " + ec.message());
    if (static_cast<std::int64_t>(bytes) > max_bytes)
        throw InvalidInput(what + " '" + path.string() + "' is too large: " + std::to_string(bytes) +
                           " bytes (limit " + std::to_string(max_bytes) + ", docs/hardening.md)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot read " + what + " '" + path.string() + "': cannot open the file");
    std::string text(static_cast<size_t>(bytes), '\0');
    in.read(text.data(), static_cast<std::streamsize>(bytes));
    if (in.bad() || in.gcount() != static_cast<std::streamsize>(bytes))
        throw IoError("cannot read " + what + " '" + path.string() + "': read error (file changed while read?)");
    return text;
}

void check_json_text(std::string_view text, const std::string& where) {
    if (static_cast<std::int64_t>(text.size()) > kMaxJsonFileBytes)
        throw InvalidInput(where + ": JSON text too large: " + std::to_string(text.size()) + " bytes (limit " +
                           std::to_string(kMaxJsonFileBytes) + ", docs/hardening.md)");
    int depth = 0;
    bool in_string = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (c == '\\') ++i;
            else if (c == '"') in_string = false;
            continue;
        }
        if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                throw InvalidInput(where + ": JSON nested deeper than " + std::to_string(kMaxJsonDepth) +
                                   " levels (at byte " + std::to_string(i) + "; docs/hardening.md)");
        } else if (c == ']' || c == '}') {
            if (depth > 0) --depth;
        }
    }
}

}  // namespace drape::limits

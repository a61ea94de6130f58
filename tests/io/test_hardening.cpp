// Resource limits and the regressions of the fuzzers (docs/hardening.md): each bad input
// is refused with drape::InvalidInput / drape::IoError naming the file, before any work.
#include <catch2/catch.hpp>

#include <drape/body/model_io.hpp>
#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/limits.hpp>
#include <drape/garment/pattern_json.hpp>
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>
#include <drape/vision/image_io.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

void write_bytes(const fs::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary) << bytes;
}

std::uint32_t crc32(const std::string& s) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : s) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    }
    return c ^ 0xFFFFFFFFu;
}

std::string be32(std::uint32_t v) {
    return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

std::string chunk(const std::string& type, const std::string& data) {
    return be32(std::uint32_t(data.size())) + type + data + be32(crc32(type + data));
}

/// A structurally complete PNG declaring width x height, with a tiny (wrong) IDAT: the
/// decoder would allocate width x height pixels before noticing.
std::string png_header_only(std::uint32_t width, std::uint32_t height) {
    const std::string ihdr = be32(width) + be32(height) + std::string("\x08\x02\x00\x00\x00", 5);
    const std::string idat("\x78\x9c\x63\x00\x00\x00\x01\x00\x01", 9);
    return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", idat) + chunk("IEND", "");
}

}  // namespace

TEST_CASE("an image whose header exceeds the pixel limit is refused before decoding", "[io][hardening]") {
    const fs::path dir = drape::test::scratch_dir("hardening_images");
    const fs::path huge = dir / "huge.png";
    write_bytes(huge, png_header_only(100000, 100000));
    // Every reader refuses it from the header (a decode would need 30 GB).
    CHECK_THROWS_WITH(drape::io::read_photo(huge), Contains("100000 x 100000") && Contains("header"));
    CHECK_THROWS_AS(drape::io::read_photo(huge), drape::InvalidInput);
    CHECK_THROWS_AS(drape::io::read_mask(huge, "silhouette"), drape::InvalidInput);
    CHECK_THROWS_AS(drape::io::read_label_masks(huge), drape::InvalidInput);
    CHECK_THROWS_AS(drape::vision::load_image_unchanged(huge, "strokes"), drape::InvalidInput);
    // Just over the pixel count, each side within its limit.
    write_bytes(huge, png_header_only(10000, 5001));
    CHECK_THROWS_WITH(drape::io::read_photo(huge), Contains("50000000 pixels"));
    // A format other than PNG or JPEG is refused by name (its header is not read).
    write_bytes(dir / "image.bmp", "BM" + std::string(60, '\0'));
    CHECK_THROWS_WITH(drape::io::read_photo(dir / "image.bmp"), Contains("not a PNG or JPEG"));
}

TEST_CASE("JSON nested or sized beyond the limits is refused before parsing", "[io][hardening]") {
    const fs::path dir = drape::test::scratch_dir("hardening_json");
    const int deep = drape::limits::kMaxJsonDepth + 1;
    write_bytes(dir / "deep.json", std::string(deep, '[') + std::string(deep, ']'));
    CHECK_THROWS_WITH(drape::io::read_json_file(dir / "deep.json"), Contains("nested deeper than 64"));
    CHECK_THROWS_AS(drape::cloth::load_material(dir / "deep.json"), drape::InvalidInput);
    CHECK_THROWS_AS(drape::garment::read_pattern_json(dir / "deep.json"), drape::InvalidInput);
    // At the limit it parses; brackets inside strings do not count.
    const int ok = drape::limits::kMaxJsonDepth;
    write_bytes(dir / "ok.json", std::string(ok, '[') + "\"[[[[{{{{\\\"[[\"" + std::string(ok, ']'));
    CHECK_NOTHROW(drape::io::read_json_file(dir / "ok.json"));
    // The size cap is checked on the file size before reading.
    write_bytes(dir / "small.json", "[1, 2, 3]");
    CHECK_THROWS_WITH(drape::limits::read_file_capped(dir / "small.json", 4, "JSON file"),
                      Contains("small.json") && Contains("9 bytes") && Contains("limit 4"));
    CHECK_THROWS_AS(drape::limits::read_file_capped(dir / "missing.json", 4, "JSON file"), drape::IoError);
}

TEST_CASE("a damaged body model file is an IoError naming it", "[io][hardening]") {
    const fs::path dir = drape::test::scratch_dir("hardening_model");
    write_bytes(dir / "model.h5", std::string("\x89HDF\r\n\x1a\n", 8) + std::string(100, '\0'));
    CHECK_THROWS_AS(drape::body::load_model(dir / "model.h5"), drape::IoError);
    CHECK_THROWS_WITH(drape::body::load_model(dir / "model.h5"), Contains("model.h5"));
}

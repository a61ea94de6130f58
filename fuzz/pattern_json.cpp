// GarmentCode pattern JSON: the text parser and the file reader.
#include "fuzz_common.hpp"

#include <drape/garment/pattern_json.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    drape::fuzz::expect_clean([&] { (void)drape::garment::pattern_from_garmentcode_json(text); });
    const auto path = drape::fuzz::write_input("pattern.json", data, size);
    drape::fuzz::expect_clean([&] { (void)drape::garment::read_pattern_json(path); });
    return 0;
}

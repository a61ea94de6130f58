// Sizing G.json of each template, then the pattern made from it (where G's ranges are
// checked). The first byte picks the template; the rest is the file.
#include "fuzz_common.hpp"

#include <drape/garment/garment_sizing.hpp>
#include <drape/io/garment_json.hpp>
#include <drape/io/json_io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    const auto type = static_cast<drape::garment::GarmentType>(data[0] % 4);
    const auto path = drape::fuzz::write_input("sizing.json", data + 1, size - 1);
    drape::fuzz::expect_clean([&] {
        const auto sizing = drape::io::sizing_from_json(type, drape::io::read_json_file(path), "sizing.json");
        (void)drape::garment::make_pattern(sizing);
    });
    return 0;
}

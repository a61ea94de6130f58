// User strokes: a stroke image (class ids or colour-coded) decoded with the default
// palette, and a stroke palette file. The first byte picks which.
#include "fuzz_common.hpp"

#include <drape/io/vision_json.hpp>
#include <drape/vision/label_table.hpp>
#include <drape/vision/strokes.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    if (data[0] & 1) {
        const auto path = drape::fuzz::write_input("palette.json", data + 1, size - 1);
        drape::fuzz::expect_clean([&] {
            const auto palette = drape::io::read_stroke_palette(path, drape::vision::LabelTable::fashionista());
            std::string why;
            if (!palette.is_valid(&why)) drape::fuzz::fail(("read_stroke_palette returned an invalid palette: " + why).c_str());
        });
    } else {
        const auto path = drape::fuzz::write_input("strokes.png", data + 1, size - 1);
        drape::fuzz::expect_clean([&] {
            drape::vision::StrokeDecoding report;
            (void)drape::vision::load_strokes(path, drape::vision::StrokePalette::fashionista_default(), &report);
        });
    }
    return 0;
}

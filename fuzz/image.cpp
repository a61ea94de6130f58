// Image files (PNG, JPEG, anything OpenCV decodes) through every reader of photos, masks
// and label maps: huge dimensions in a header, truncated or damaged files.
#include "fuzz_common.hpp"

#include <drape/io/image_io.hpp>
#include <drape/vision/image_io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = drape::fuzz::write_input("image.img", data, size);
    drape::fuzz::expect_clean([&] { (void)drape::io::read_photo(path); });
    drape::fuzz::expect_clean([&] { (void)drape::io::read_mask(path, "silhouette"); });
    drape::fuzz::expect_clean([&] { (void)drape::io::read_label_masks(path); });
    drape::fuzz::expect_clean([&] { (void)drape::vision::load_image_unchanged(path, "strokes"); });
    return 0;
}

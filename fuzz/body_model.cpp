// HDF5 body model files through body::load_model.
#include "fuzz_common.hpp"

#include <drape/body/model_io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = drape::fuzz::write_input("model.h5", data, size);
    drape::fuzz::expect_clean([&] { (void)drape::body::load_model(path); });
    return 0;
}

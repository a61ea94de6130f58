// Any JSON file through drape::io::read_json_file: the size cap, the nesting-depth check
// and nlohmann-json's parser (docs/hardening.md, "Resource limits").
#include "fuzz_common.hpp"

#include <drape/io/json_io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = drape::fuzz::write_input("input.json", data, size);
    drape::fuzz::expect_clean([&] {
        const nlohmann::json j = drape::io::read_json_file(path);
        (void)drape::io::optional_number(j.is_object() ? j : nlohmann::json::object(), "x", "input.json");
    });
    return 0;
}

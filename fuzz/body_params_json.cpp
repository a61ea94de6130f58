// Body parameters P.json (semantic shape request) as `drape body --params` reads them.
#include "fuzz_common.hpp"

#include <drape/io/body_json.hpp>
#include <drape/io/json_io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = drape::fuzz::write_input("params.json", data, size);
    drape::fuzz::expect_clean([&] {
        (void)drape::io::semantic_request_from_json(drape::io::read_json_file(path), "params.json");
    });
    return 0;
}

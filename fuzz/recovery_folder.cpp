// Result folders for try-on and animation: the input is result.json in a folder, read by
// io::read_recovery_folder as "DIR" and as "DIR:0".
#include "fuzz_common.hpp"

#include <drape/io/recovery_files.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = drape::fuzz::write_input("result.json", data, size);
    const std::string dir = path.parent_path().string();
    drape::fuzz::expect_clean([&] { (void)drape::io::read_recovery_folder(dir); });
    drape::fuzz::expect_clean([&] { (void)drape::io::read_recovery_folder(dir + ":0"); });
    return 0;
}

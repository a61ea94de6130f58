// Small helpers of the C++ C API tests.
#pragma once

#include <drape/drape.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace drape::test {

/// This thread's last error message.
inline std::string last_error() { return drape_last_error_message(); }

/// A JSON string from the library, parsed and freed.
inline nlohmann::json take_json(char* text) {
    REQUIRE(text != nullptr);
    const nlohmann::json j = nlohmann::json::parse(text);
    drape_free(text);
    return j;
}

}  // namespace drape::test

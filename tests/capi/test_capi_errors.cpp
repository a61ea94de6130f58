// C API contract: status codes, messages, size queries, thread-local errors, NULL handling.
#include <drape/drape.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "test_paths.hpp"

TEST_CASE("every status has a description", "[capi]") {
    for (int s = DRAPE_OK; s <= DRAPE_ERROR_INTERNAL; ++s)
        CHECK(std::string(drape_status_string(static_cast<drape_status>(s))).size() > 0);
    CHECK(std::string(drape_status_string(static_cast<drape_status>(99))) == "unknown status");
}

TEST_CASE("drape_version is the CMake project version", "[capi]") {
    CHECK(std::string(drape_version()) == DRAPE_PROJECT_VERSION);
}

namespace {
// What a caller compiled against an older drape.h would have: drape_shape_params and
// drape_measurements as if they had ended after height_m. The guards after each struct
// are in the caller's memory but outside the struct: the library must not touch them.
struct old_shape_params {
    uint32_t struct_size;
    int32_t gender;
    double height_m;
};
struct old_shape_params_with_guard {
    old_shape_params params;
    double guard[16];
};
struct old_measurements {
    uint32_t struct_size;
    double height_m;
};
struct old_measurements_with_guard {
    old_measurements m;
    double guard[16];
};
constexpr double kGuard = 12345.0;
}  // namespace

TEST_CASE("versioned structs: init and outputs respect the caller's struct_size", "[capi]") {
    SECTION("init keeps the caller's struct_size") {
        drape_shape_params p;
        p.struct_size = sizeof p + 8;  // a caller built against a newer header
        REQUIRE(drape_shape_params_init(&p) == DRAPE_OK);
        CHECK(p.struct_size == sizeof p + 8);
        CHECK(std::isnan(p.crotch_height_m));
        p.struct_size = 0;
        CHECK(drape_shape_params_init(&p) == DRAPE_ERROR_INVALID_ARGUMENT);
        drape_measurements m;
        m.struct_size = 0;
        CHECK(drape_measurements_init(&m) == DRAPE_ERROR_INVALID_ARGUMENT);
    }
    SECTION("an older, smaller struct is filled only as far as it reaches") {
        old_shape_params_with_guard old;
        for (double& g : old.guard) g = kGuard;
        old.params.struct_size = sizeof(old_shape_params);
        old.params.gender = 99;
        old.params.height_m = 0;
        auto* p = reinterpret_cast<drape_shape_params*>(&old.params);
        REQUIRE(drape_shape_params_init(p) == DRAPE_OK);
        CHECK(old.params.struct_size == sizeof(old_shape_params));
        CHECK(old.params.gender == DRAPE_GENDER_UNSPECIFIED);
        CHECK(std::isnan(old.params.height_m));
        for (double g : old.guard) CHECK(g == kGuard);

        // As input: fields the caller does not have are "not given".
        drape_body body = nullptr;
        REQUIRE(drape_body_create(nullptr, &body) == DRAPE_OK);
        old.params.gender = DRAPE_GENDER_MALE;
        old.params.height_m = 1.85;
        REQUIRE(drape_body_set_shape(body, p) == DRAPE_OK);

        // As output: only the fields that fit are written.
        old.params.height_m = 0;
        REQUIRE(drape_body_get_shape(body, p) == DRAPE_OK);
        CHECK(old.params.gender == DRAPE_GENDER_MALE);
        CHECK(old.params.height_m == Approx(1.85));
        CHECK(old.params.struct_size == sizeof(old_shape_params));
        for (double g : old.guard) CHECK(g == kGuard);

        old_measurements_with_guard om;
        for (double& g : om.guard) g = kGuard;
        om.m.struct_size = sizeof(old_measurements);
        auto* m = reinterpret_cast<drape_measurements*>(&om.m);
        REQUIRE(drape_measurements_init(m) == DRAPE_OK);
        CHECK(om.m.height_m == 0);
        REQUIRE(drape_body_measure(body, m) == DRAPE_OK);
        CHECK(om.m.height_m == Approx(1.85).margin(0.005));
        CHECK(om.m.struct_size == sizeof(old_measurements));
        for (double g : om.guard) CHECK(g == kGuard);
        drape_body_destroy(body);
    }
}

TEST_CASE("NULL handles and bad arguments give INVALID_ARGUMENT with a message", "[capi]") {
    drape_body_destroy(nullptr);
    drape_body_model_destroy(nullptr);
    CHECK(drape_body_set_shape(nullptr, nullptr) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(drape_last_error_message()).find("must not be NULL") != std::string::npos);
    drape_body_model model = nullptr;
    CHECK(drape_body_model_load("/nonexistent/model.h5", &model) == DRAPE_ERROR_IO);
    CHECK(model == nullptr);
    CHECK(std::string(drape_last_error_message()).find("/nonexistent/model.h5") != std::string::npos);
    CHECK(drape_joint_name(22) == nullptr);
}

TEST_CASE("shape parameters are validated", "[capi]") {
    drape_body body = nullptr;
    REQUIRE(drape_body_create(nullptr, &body) == DRAPE_OK);
    drape_shape_params p;
    p.struct_size = 4;
    CHECK(drape_body_set_shape(body, &p) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(drape_shape_params_init(&p) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(drape_last_error_message()).find("struct_size is 4") != std::string::npos);
    p.struct_size = sizeof p;
    drape_shape_params_init(&p);
    p.height_m = -1.7;
    CHECK(drape_body_set_shape(body, &p) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(drape_last_error_message()).find("height_m") != std::string::npos);
    drape_shape_params_init(&p);
    p.gender = 7;
    CHECK(drape_body_set_shape(body, &p) == DRAPE_ERROR_INVALID_ARGUMENT);
    // A failed call leaves the body usable and unchanged.
    drape_measurements m;
    m.struct_size = sizeof m;
    REQUIRE(drape_body_measure(body, &m) == DRAPE_OK);
    CHECK(m.height_m > 1.5);
    drape_body_destroy(body);
}

TEST_CASE("the last error message is per thread", "[capi]") {
    CHECK(drape_body_create(nullptr, nullptr) == DRAPE_ERROR_INVALID_ARGUMENT);
    std::string other;
    std::thread t([&] { other = drape_last_error_message(); });
    t.join();
    CHECK(other.empty());
    CHECK(!std::string(drape_last_error_message()).empty());
}

TEST_CASE("distinct bodies can be used from distinct threads", "[capi]") {
    std::vector<double> heights(2, 0);
    std::vector<std::thread> threads;
    for (int i = 0; i < 2; ++i)
        threads.emplace_back([&, i] {
            drape_body body = nullptr;
            if (drape_body_create(nullptr, &body) != DRAPE_OK) return;
            drape_shape_params p;
            p.struct_size = sizeof p;
            drape_shape_params_init(&p);
            p.height_m = i == 0 ? 1.60 : 1.90;
            p.gender = i == 0 ? DRAPE_GENDER_FEMALE : DRAPE_GENDER_MALE;
            if (drape_body_set_shape(body, &p) == DRAPE_OK) {
                drape_measurements m;
                m.struct_size = sizeof m;
                drape_body_measure(body, &m);
                heights[i] = m.height_m;
            }
            drape_body_destroy(body);
        });
    for (auto& t : threads) t.join();
    CHECK(heights[0] == Approx(1.60).margin(0.005));
    CHECK(heights[1] == Approx(1.90).margin(0.005));
}

TEST_CASE("a model round-trips through a file via the C API", "[capi][io]") {
    const auto dir = drape::test::scratch_dir("capi_model");
    const std::string path = (dir / "model.h5").string();
    drape_body_model model = nullptr;
    REQUIRE(drape_body_model_default(&model) == DRAPE_OK);
    REQUIRE(drape_body_model_save(model, path.c_str()) == DRAPE_OK);
    drape_body_model loaded = nullptr;
    REQUIRE(drape_body_model_load(path.c_str(), &loaded) == DRAPE_OK);
    drape_body a = nullptr, b = nullptr;
    REQUIRE(drape_body_create(model, &a) == DRAPE_OK);
    REQUIRE(drape_body_create(loaded, &b) == DRAPE_OK);
    drape_body_model_destroy(loaded);  // the body keeps the model alive
    size_t n = 0;
    drape_body_get_vertices(a, nullptr, 0, &n);
    std::vector<double> va(n), vb(n);
    REQUIRE(drape_body_get_vertices(a, va.data(), n, nullptr) == DRAPE_OK);
    REQUIRE(drape_body_get_vertices(b, vb.data(), n, nullptr) == DRAPE_OK);
    double max_diff = 0;
    for (size_t i = 0; i < n; ++i) max_diff = std::max(max_diff, std::abs(va[i] - vb[i]));
    CHECK(max_diff < 1e-12);
    drape_body_destroy(a);
    drape_body_destroy(b);
    drape_body_model_destroy(model);

    std::ofstream(dir / "garbage.h5") << "not an hdf5 file";
    CHECK(drape_body_model_load((dir / "garbage.h5").string().c_str(), &loaded) == DRAPE_ERROR_IO);
}

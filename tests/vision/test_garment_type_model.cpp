// The learned garment-type decisions of the automatic segmentation
// (libvision/src/garment_type_model.hpp): features on the drawn figure, the embedded
// models' provenance and the model arithmetic.
#include "garment_type_model.hpp"
#include "synthetic_figure.hpp"

#include <catch2/catch.hpp>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <string>

using namespace drape;
using namespace drape::vision;
using drape::test::Bottom;
using drape::test::make_figure;

TEST_CASE("dress features: colours, boundary and shares of a drawn figure", "[types]") {
    const auto f = make_figure(Bottom::skirt);
    const cv::Mat upper = f.labels == 51, lower = f.labels == 42;
    const auto two = detail::dress_features(f.photo, upper, lower, f.joints);
    // The drawn t-shirt and skirt have different flat colours: histograms barely overlap.
    CHECK(two[0] < 0.2);
    CHECK(two[3] > 20.0);
    // Upper share: the upper region's pixels over both.
    const double nu = cv::countNonZero(upper), nl = cv::countNonZero(lower);
    CHECK(two[7] == Approx(nu / (nu + nl)).epsilon(1e-9));
    // The shirt meets the skirt across the torso, between the shoulders and the hips.
    CHECK(two[9] > 0.8);
    CHECK(two[5] > 0.3);
    CHECK(two[5] < 1.3);
    // The same figure with the skirt painted in the shirt's colour: one fabric.
    cv::Mat photo = f.photo.clone();
    cv::Scalar shirt = cv::mean(f.photo, upper);
    photo.setTo(shirt, lower);
    photo.setTo(shirt, upper);
    const auto one = detail::dress_features(photo, upper, lower, f.joints);
    CHECK(one[0] > 0.95);
    CHECK(one[2] < 2.0);
    CHECK(one[3] < 2.0);
    CHECK(one[4] < two[4]);  // no colour step at the waist
}

TEST_CASE("lower features: skirt and pants of the drawn figure", "[types]") {
    const auto skirt = make_figure(Bottom::skirt), pants = make_figure(Bottom::pants);
    const cv::Mat none;
    const auto fs = detail::lower_features(skirt.photo, skirt.labels == 42, skirt.joints, none);
    const auto fp = detail::lower_features(pants.photo, pants.labels == 31, pants.joints, none);
    CHECK(fp[0] > 0.75);  // hem near the ankles
    CHECK(fp[1] > fs[1]);  // the pants run further down the legs
    CHECK(fp[8] > 1.5);    // two legs: two pieces per row below the crotch
    CHECK(fs[8] < 1.2);
}

TEST_CASE("the embedded garment-type models are trained on the tuning photos", "[types]") {
    REQUIRE(detail::kDressModel.trained());
    // The lower types stay with the rules (--keep-rule lower, docs/vision.md): the learned
    // lower model's CV gain was 2 of 64 garments.
    CHECK_FALSE(detail::kLowerModel.trained());
    CHECK(std::string(detail::kTypeModelProvenance).find("photos-dev (tune") != std::string::npos);
    for (const auto* m : {&detail::kDressModel}) {
        REQUIRE(m->weight.size() == m->classes.size());
        REQUIRE(m->bias.size() == m->classes.size());
        REQUIRE(m->mean.size() == m->features.size());
        REQUIRE(m->scale.size() == m->features.size());
        for (double s : m->scale) CHECK(s > 0);
    }
    CHECK(detail::kDressModel.classes.front() == GarmentType::dress);
    // The dress model uses the colour similarity, and more similar colours make a dress
    // more likely (all other features at their training means).
    double x[detail::kDressFeatureCount] = {};
    int sim = -1;
    for (size_t k = 0; k < detail::kDressModel.features.size(); ++k) {
        x[detail::kDressModel.features[k]] = detail::kDressModel.mean[k];
        if (detail::kDressModel.features[k] == 0) sim = int(k);
    }
    REQUIRE(sim >= 0);
    x[0] = 0.1;
    const double p_low = detail::kDressModel.probabilities(x)[0];
    x[0] = 0.95;
    const double p_high = detail::kDressModel.probabilities(x)[0];
    CHECK(p_high > p_low + 0.3);
    CHECK(p_low < detail::kDressDecision);
}

TEST_CASE("a linear type model's probabilities are its softmax", "[types]") {
    detail::LinearTypeModel m;
    m.classes = {GarmentType::skirt, GarmentType::pants, GarmentType::shorts};
    m.features = {1, 3};
    m.mean = {0.5, 1.0};
    m.scale = {0.25, 2.0};
    m.weight = {{1.0, 0.0}, {0.0, 1.0}, {-1.0, -1.0}};
    m.bias = {0.0, 0.5, 0.0};
    const double x[4] = {9.0, 1.0, 9.0, 3.0};  // z = (2, 1)
    const auto p = m.probabilities(x);
    const double s[3] = {2.0, 1.5, -3.0};
    const double z = std::exp(s[0]) + std::exp(s[1]) + std::exp(s[2]);
    for (int c = 0; c < 3; ++c) CHECK(p[size_t(c)] == Approx(std::exp(s[c]) / z).epsilon(1e-12));
}

#include <drape/core/errors.hpp>
#include <drape/vision/bare_arms.hpp>
#include <drape/vision/garment_result.hpp>

#include "synthetic_figure.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <tuple>

using namespace drape;
using namespace drape::vision;

TEST_CASE("garment results carry polygons with holes, features and occlusion", "[vision][garments]") {
    test::SyntheticFigure f = test::make_figure();
    // A bag (class 2) in front of the skirt: a hole in its silhouette.
    cv::rectangle(f.labels, cv::Rect(190, 360, 20, 20), cv::Scalar(2), cv::FILLED);
    Segmentation seg;
    seg.labels = f.labels;
    seg.occlusion = occlusion_mask(f.labels, LabelTable::fashionista());
    const auto garments = describe_garments(f.photo, seg, f.joints, LabelTable::fashionista(), {});
    REQUIRE(garments.size() == 2);
    const GarmentResult* skirt = nullptr;
    const GarmentResult* shirt = nullptr;
    for (const auto& g : garments) (g.label_id == 42 ? skirt : shirt) = &g;
    REQUIRE(skirt);
    REQUIRE(shirt);
    CHECK(skirt->type == GarmentType::skirt);
    CHECK(shirt->type == GarmentType::t_shirt);
    REQUIRE(skirt->silhouette.size() == 1);
    REQUIRE(skirt->silhouette[0].holes.size() == 1);
    CHECK(skirt->occlusion_fraction == Approx(400.0 / (skirt->area_px + 400)).epsilon(0.05));
    // The skirt trapezoid (y 290..420, 64 -> 124 px wide) shows below the t-shirt's hem
    // (y 300): 121 rows.
    const GarmentFeatures& sf = skirt->features;
    CHECK(sf.length_px == Approx(121).margin(3));
    CHECK(sf.hem_width_px == Approx(121).margin(6));
    CHECK(sf.top_width_px == Approx(67).margin(6));
    CHECK(std::isnan(sf.inseam_px));
    CHECK(std::isnan(sf.sleeve_length_px));
    for (const auto& [name, v] : sf.list()) CHECK(v.second == Approx(v.first / f.joints.body_height_px()));
    // The t-shirt's sleeve covers about 37 % of the arm from the shoulder.
    CHECK(shirt->cues.sleeve_fraction > 0.2);
    CHECK(shirt->cues.sleeve_fraction < 0.5);
    CHECK(shirt->features.sleeve_length_px > 40);
    CHECK(shirt->features.neckline_depth_px >= 0);
    CHECK(shirt->features.neckline_depth_px < 20);
}

TEST_CASE("garment cues separate skirts, shorts, pants and sleeve lengths", "[vision][garments][classify]") {
    const test::SyntheticFigure skirt = test::make_figure(test::Bottom::skirt);
    const test::SyntheticFigure pants = test::make_figure(test::Bottom::pants);
    CHECK(classify_lower(measure_shape_cues(skirt.labels == 42, skirt.joints)) == GarmentType::skirt);
    const GarmentShapeCues pc = measure_shape_cues(pants.labels == 31, pants.joints);
    CHECK(pc.hem_fraction > 0.9);
    CHECK(classify_lower(pc) == GarmentType::pants);
    // Shorts: the pants cut above the knee.
    cv::Mat shorts = (pants.labels == 31);
    shorts.rowRange(380, shorts.rows).setTo(0);
    const GarmentShapeCues sc = measure_shape_cues(shorts, pants.joints);
    CHECK(sc.between_legs_fraction < 0.5);
    CHECK(classify_lower(sc) == GarmentType::shorts);
    const GarmentFeatures sf = measure_features(shorts, GarmentType::shorts, pants.joints);
    CHECK(sf.inseam_px > 20);
    CHECK(sf.inseam_px < 70);
    // Sleeves: none (tank top), half (t-shirt), full (long sleeves).
    cv::Mat top = skirt.labels == 51;
    CHECK(classify_upper(measure_shape_cues(top, skirt.joints)) == GarmentType::t_shirt);
    cv::Mat tank = top.clone();
    cv::Mat arms = (skirt.labels == 51);
    tank.setTo(0);
    const cv::Point torso[4] = {{170, 130}, {230, 130}, {236, 300}, {164, 300}};
    cv::fillConvexPoly(tank, torso, 4, cv::Scalar(255));
    CHECK(classify_upper(measure_shape_cues(tank, skirt.joints)) == GarmentType::tank_top);
    cv::Mat longs = top.clone();
    using J = Joint;
    const auto p = [&](J j) { return cv::Point(int(skirt.joints[j].x()), int(skirt.joints[j].y())); };
    cv::line(longs, p(J::right_shoulder), p(J::right_elbow), 255, 26);
    cv::line(longs, p(J::right_elbow), p(J::right_hand), 255, 24);
    CHECK(classify_upper(measure_shape_cues(longs, skirt.joints)) == GarmentType::long_sleeve_top);
}

TEST_CASE("lower-garment length is the continuous run down the legs", "[vision][garments][classify]") {
    const test::SyntheticFigure pants = test::make_figure(test::Bottom::pants);
    const GarmentShapeCues pc = measure_shape_cues(pants.labels == 31, pants.joints);
    CHECK(pc.leg_fraction > 0.9);
    // Shorts (cut 75 px below the hips) plus boots at the ankles, separated from them by bare
    // legs: the lowest pixels reach the ankles, but the garment does not run down the legs.
    cv::Mat shorts = (pants.labels == 31);
    shorts.rowRange(380, shorts.rows).setTo(0);
    cv::Mat with_boots = shorts.clone();
    cv::rectangle(with_boots, cv::Point(164, 470), cv::Point(192, 550), cv::Scalar(255), cv::FILLED);
    cv::rectangle(with_boots, cv::Point(208, 470), cv::Point(236, 550), cv::Scalar(255), cv::FILLED);
    const GarmentShapeCues bc = measure_shape_cues(with_boots, pants.joints);
    CHECK(bc.hem_fraction > 0.9);
    CHECK(bc.leg_fraction > 0.25);
    CHECK(bc.leg_fraction < 0.35);
    CHECK(classify_lower(bc) == GarmentType::shorts);
    // The same boots under full pants do not change them.
    cv::Mat pants_boots = (pants.labels == 31) | with_boots;
    CHECK(classify_lower(measure_shape_cues(pants_boots, pants.joints)) == GarmentType::pants);
    // Pants under a tunic that hangs 60 px below the hips (a quarter of hips -> ankles): the
    // walk starts where the pants show, and they still run down the legs. (From the hip
    // row, the walk stopped at once: leg fraction 0, read as shorts.)
    const double hip_y = pants.joints.mid_hip().y();
    cv::Mat under_tunic = (pants.labels == 31);
    under_tunic.rowRange(0, int(hip_y) + 60).setTo(0);
    const GarmentShapeCues tc = measure_shape_cues(under_tunic, pants.joints);
    CHECK(tc.leg_fraction > 0.9);
    CHECK(classify_lower(tc) == GarmentType::pants);

    // A skirt (no crotch gap): shorts when its hem is above mid-thigh, skirt below.
    const test::SyntheticFigure skirt = test::make_figure(test::Bottom::skirt);
    cv::Mat mini = (skirt.labels == 42);
    mini.rowRange(345, mini.rows).setTo(0);  // hem 40 px below the hips of 240 px to the ankles
    const GarmentShapeCues mc = measure_shape_cues(mini, skirt.joints);
    CHECK(mc.leg_fraction < 0.2);
    CHECK(classify_lower(mc) == GarmentType::shorts);
    cv::Mat knee = (skirt.labels == 42);
    knee.rowRange(385, knee.rows).setTo(0);
    const GarmentShapeCues kc = measure_shape_cues(knee, skirt.joints);
    CHECK(kc.leg_fraction > 0.3);
    CHECK(classify_lower(kc) == GarmentType::skirt);
}

TEST_CASE("a long garment that widens from the thighs to the knees is a skirt", "[vision][garments][classify]") {
    const test::SyntheticFigure pants = test::make_figure(test::Bottom::pants);
    const GarmentShapeCues pc = measure_shape_cues(pants.labels == 31, pants.joints);
    // Two 24 px legs at the knees under a 76 px wide top: the legs narrow downwards.
    CHECK(pc.knee_width_ratio == Approx(48.0 / 76.0).margin(0.05));
    CHECK(classify_lower(pc) == GarmentType::pants);
    // A maxi skirt flaring from 64 px at the waist to 120 px at the ankles (hips 305, knees
    // 430, ankles 545): 95 px at the knees over 79 px at the thighs.
    cv::Mat maxi = cv::Mat::zeros(pants.labels.size(), CV_8UC1);
    const cv::Point flared[4] = {{168, 290}, {232, 290}, {260, 540}, {140, 540}};
    cv::fillConvexPoly(maxi, flared, 4, cv::Scalar(255));
    const GarmentShapeCues mc = measure_shape_cues(maxi, pants.joints);
    CHECK(mc.hem_fraction > 0.9);
    CHECK(mc.leg_fraction > 0.9);
    CHECK(mc.knee_width_ratio > 1.15);
    CHECK(classify_lower(mc) == GarmentType::skirt);
    // A straight tube to the ankles has the silhouette of wide-leg trousers with touching
    // legs: pants (the known confusion of straight maxi skirts, docs/vision.md).
    cv::Mat tube = cv::Mat::zeros(pants.labels.size(), CV_8UC1);
    cv::rectangle(tube, cv::Point(166, 290), cv::Point(234, 540), cv::Scalar(255), cv::FILLED);
    const GarmentShapeCues tc = measure_shape_cues(tube, pants.joints);
    CHECK(tc.knee_width_ratio == Approx(1.0).margin(0.02));
    CHECK(classify_lower(tc) == GarmentType::pants);
    // A garment ending above the knees has no knee width.
    cv::Mat mini = maxi.clone();
    mini.rowRange(380, mini.rows).setTo(0);
    CHECK(measure_shape_cues(mini, pants.joints).knee_width_ratio == 0);
}

TEST_CASE("a sleeve wraps the arm: a torso beside a hanging arm is no sleeve", "[vision][garments][classify]") {
    // Both arms hang straight down beside a tank top's torso, their lines 3 px outside its
    // sides: within the 0.8 % H (4 px) disc of the arm line all the way to the hands, but
    // nothing lies on the arms' outer halves.
    test::SyntheticFigure f = test::make_figure();
    using J = Joint;
    f.joints[J::right_shoulder] = {158, 125};
    f.joints[J::right_elbow] = {158, 215};
    f.joints[J::right_hand] = {158, 300};
    f.joints[J::left_shoulder] = {242, 125};
    f.joints[J::left_elbow] = {242, 215};
    f.joints[J::left_hand] = {242, 300};
    cv::Mat tank = cv::Mat::zeros(f.labels.size(), CV_8UC1);
    cv::rectangle(tank, cv::Point(161, 118), cv::Point(239, 310), cv::Scalar(255), cv::FILLED);
    const GarmentShapeCues tc = measure_shape_cues(tank, f.joints);
    CHECK(tc.sleeve_fraction < 0.12);
    CHECK(classify_upper(tc) == GarmentType::tank_top);
    CHECK(measure_features(tank, GarmentType::tank_top, f.joints).sleeve_length_px < 10);
    // Short sleeves (26 px wide) over the upper 40 % of the upper arms: a t-shirt.
    cv::Mat tee = tank.clone();
    cv::rectangle(tee, cv::Point(145, 118), cv::Point(171, 161), cv::Scalar(255), cv::FILLED);
    cv::rectangle(tee, cv::Point(229, 118), cv::Point(255, 161), cv::Scalar(255), cv::FILLED);
    const GarmentShapeCues sc = measure_shape_cues(tee, f.joints);
    CHECK(sc.sleeve_fraction == Approx(36.0 / 175).margin(0.05));
    CHECK(classify_upper(sc) == GarmentType::t_shirt);
    // Sleeves down to the wrists, still beside the torso: long sleeves.
    cv::Mat longs = tank.clone();
    cv::line(longs, cv::Point(158, 125), cv::Point(158, 300), cv::Scalar(255), 24);
    cv::line(longs, cv::Point(242, 125), cv::Point(242, 300), cv::Scalar(255), 24);
    const GarmentShapeCues lc = measure_shape_cues(longs, f.joints);
    CHECK(lc.sleeve_fraction > 0.95);
    CHECK(classify_upper(lc) == GarmentType::long_sleeve_top);
}

TEST_CASE("hair over the shoulders hides a sleeve but does not end it", "[vision][garments][classify]") {
    // Long sleeves on both arms, with hair (class 19) hanging over both shoulders and the
    // upper arms for 30 px (> the 2 % H gap a run bridges).
    const test::SyntheticFigure f = test::make_figure();
    using J = Joint;
    const auto p = [&](J j) { return cv::Point(int(f.joints[j].x()), int(f.joints[j].y())); };
    cv::Mat labels = f.labels.clone();
    for (const auto& [s, e, h] : {std::tuple{J::right_shoulder, J::right_elbow, J::right_hand},
                                  std::tuple{J::left_shoulder, J::left_elbow, J::left_hand}}) {
        cv::line(labels, p(s), p(e), cv::Scalar(51), 26);
        cv::line(labels, p(e), p(h), cv::Scalar(51), 24);
        const Eigen::Vector2d d = (f.joints[e] - f.joints[s]).normalized();
        const Eigen::Vector2d a = f.joints[s] + 5 * d, b = f.joints[s] + 35 * d;
        cv::line(labels, cv::Point(int(a.x()), int(a.y())), cv::Point(int(b.x()), int(b.y())),
                 cv::Scalar(19), 30);
    }
    const cv::Mat top = labels == 51;
    const cv::Mat hiding = sleeve_hiding_mask(labels, LabelTable::fashionista());
    CHECK(cv::countNonZero(hiding & (labels != 19)) == 0);
    // Without the hair mask the run stops under the hair: no sleeve.
    CHECK(classify_upper(measure_shape_cues(top, f.joints)) == GarmentType::tank_top);
    const GarmentShapeCues c = measure_shape_cues(top, f.joints, hiding);
    CHECK(c.sleeve_fraction > 0.9);
    CHECK(classify_upper(c) == GarmentType::long_sleeve_top);
    CHECK(measure_features(top, GarmentType::long_sleeve_top, f.joints, hiding).sleeve_length_px > 150);
    // Hair over a bare arm is no sleeve: the run stays at the shoulder.
    cv::Mat bare = labels.clone();
    bare.setTo(41, (labels == 51) & ~(f.labels == 51));  // the added sleeves back to skin
    CHECK(classify_upper(measure_shape_cues(bare == 51, f.joints, hiding)) != GarmentType::long_sleeve_top);
    // A hiding mask of the wrong size is rejected.
    CHECK_THROWS_AS(measure_shape_cues(top, f.joints, cv::Mat(10, 10, CV_8UC1, cv::Scalar(0))),
                    InvalidInput);
}

TEST_CASE("bare arms with the skin's colour are no sleeves, sleeves of the top's fabric are", "[vision][garments][classify]") {
    // The drawn figure's blue t-shirt with short sleeves; its skin-coloured arms labelled
    // as the top (the automatic cut's mistake on a pale arm beside a white top).
    const test::SyntheticFigure f = test::make_figure();
    using J = Joint;
    const auto p = [&](J j) { return cv::Point(int(f.joints[j].x()), int(f.joints[j].y())); };
    cv::Mat arms = cv::Mat::zeros(f.labels.size(), CV_8UC1);
    for (const auto& [s, e, h] : {std::tuple{J::right_shoulder, J::right_elbow, J::right_hand},
                                  std::tuple{J::left_shoulder, J::left_elbow, J::left_hand}}) {
        cv::line(arms, p(s), p(e), cv::Scalar(255), 26);
        cv::line(arms, p(e), p(h), cv::Scalar(255), 26);
    }
    arms &= f.labels == 41;
    const cv::Mat fabric = f.labels == 51;
    const cv::Mat top = fabric | arms, skin = (f.labels == 41) & ~arms;
    REQUIRE(classify_upper(measure_shape_cues(top, f.joints)) == GarmentType::long_sleeve_top);
    const cv::Mat bare = bare_arm_pixels(f.photo, top, skin, f.joints);
    CHECK(cv::countNonZero(bare & fabric) == 0);
    CHECK(cv::countNonZero(bare & arms) > 0.8 * cv::countNonZero(arms));
    CHECK(classify_upper(measure_shape_cues(top & ~bare, f.joints)) == GarmentType::t_shirt);
    // Long sleeves of the top's fabric stay sleeves.
    cv::Mat sleeved = f.photo.clone();
    sleeved.setTo(cv::Scalar(190, 120, 60), arms);
    CHECK(cv::countNonZero(bare_arm_pixels(sleeved, top, skin, f.joints)) == 0);
    // A skin-coloured (nude) top: its sleeves are not told from arms by colour, and kept.
    cv::Mat nude = f.photo.clone();
    nude.setTo(cv::Scalar(140, 170, 225), fabric);
    CHECK(cv::countNonZero(bare_arm_pixels(nude, top, skin, f.joints)) == 0);
    // No skin to compare with: nothing changes.
    CHECK(cv::countNonZero(bare_arm_pixels(f.photo, top, cv::Mat::zeros(top.size(), CV_8UC1), f.joints)) == 0);
    CHECK_THROWS_AS(bare_arm_pixels(f.photo, top, cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)), f.joints),
                    InvalidInput);
}

#include <drape/vision/garment_type.hpp>
#include <drape/vision/joints.hpp>
#include <drape/vision/label_table.hpp>

#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

using namespace drape;
using namespace drape::vision;

TEST_CASE("the Fashionista label table has the labels.txt ids and roles", "[vision][labels]") {
    const LabelTable& t = LabelTable::fashionista();
    CHECK(t.name(0) == "null");
    CHECK(t.name(41) == "skin");
    CHECK(t.name(58) == "wedges");
    CHECK_FALSE(t.contains(59));
    CHECK(t.id("t-shirt") == 51);
    CHECK(t.role(14) == LabelRole::full_garment);
    CHECK(t.role(42) == LabelRole::lower_garment);
    CHECK(t.role(25) == LabelRole::lower_garment);  // jeans
    CHECK(t.role(5) == LabelRole::upper_garment);   // blouse
    CHECK(t.role(2) == LabelRole::occluder);        // bag
    CHECK(t.role(19) == LabelRole::hair);
    CHECK(t.ids_with_role(LabelRole::skin) == std::vector<int>{41});
    CHECK_THROWS_AS(LabelTable::from_names({{1, "a"}, {1, "b"}}), InvalidInput);
    CHECK_THROWS_AS(LabelTable::from_names({{255, "a"}}), InvalidInput);
}

TEST_CASE("garment types round-trip their names and ids", "[vision][labels]") {
    for (int i = 0; i < kGarmentTypeCount; ++i) {
        const auto t = static_cast<GarmentType>(i);
        CHECK(parse_garment_type(to_string(t)) == t);
        CHECK(LabelTable::fashionista().contains(label_id_of(t)));
    }
    CHECK_FALSE(parse_garment_type("kilt").has_value());
    CHECK(part_of(GarmentType::dress) == GarmentPart::full);
    CHECK(LabelTable::fashionista().role(label_id_of(GarmentType::pants)) == LabelRole::lower_garment);
    CHECK(LabelTable::fashionista().role(label_id_of(GarmentType::tank_top)) == LabelRole::upper_garment);
}

TEST_CASE("joints validate their position and give the body height", "[vision][joints]") {
    Joints j;
    for (int i = 0; i < kJointCount; ++i) j.px[size_t(i)] = {100, 100};
    j[Joint::head] = {100, 10};
    j[Joint::neck] = {100, 50};
    for (Joint k : {Joint::left_hip, Joint::right_hip}) j[k] = {100, 150};
    for (Joint k : {Joint::left_knee, Joint::right_knee}) j[k] = {100, 250};
    for (Joint k : {Joint::left_ankle, Joint::right_ankle}) j[k] = {100, 350};
    CHECK(j.body_height_px() == Approx(340 / 0.955));
    CHECK(j.scaled(2).body_height_px() == Approx(680 / 0.955));
    CHECK_NOTHROW(j.validate(200, 400));
    j[Joint::left_hand] = {250, 100};
    CHECK_THROWS_WITH(j.validate(200, 400), Catch::Contains("left_hand"));
    j[Joint::left_hand] = {std::nan(""), 100};
    CHECK_THROWS_AS(j.validate(200, 400), InvalidInput);
}

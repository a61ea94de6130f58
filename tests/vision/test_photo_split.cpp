// The fixed tuning / held-out split of an evaluation folder (photo_split.hpp).
#include <drape/vision/photo_split.hpp>

#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

using namespace drape;
using namespace drape::vision;

namespace {

/// A synthetic folder listing of `n` names, in a scrambled (not sorted) order.
std::vector<std::string> listing(int n) {
    std::vector<std::string> names;
    for (int i = 0; i < n; ++i) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "fashionista_%06d", (i * 7919) % 100000);
        names.emplace_back(buf);
    }
    std::reverse(names.begin(), names.end());
    std::rotate(names.begin(), names.begin() + n / 3, names.end());
    return names;
}

}  // namespace

TEST_CASE("the photo split: even sorted positions tune, odd held out", "[vision][split]") {
    const std::vector<std::string> names = listing(109);
    const auto tune = select_photo_split(names, PhotoSplit::tune);
    const auto held = select_photo_split(names, PhotoSplit::heldout);
    CHECK(tune.size() == 55);
    CHECK(held.size() == 54);
    CHECK(select_photo_split(names, PhotoSplit::all).size() == 109);
    std::vector<std::string> sorted = names;
    std::sort(sorted.begin(), sorted.end());
    for (size_t i = 0; i < sorted.size(); ++i) {
        const auto& part = i % 2 == 0 ? tune : held;
        CHECK(std::binary_search(part.begin(), part.end(), sorted[i]));
    }
    // The part of a name depends on the set, not on the listing's order.
    const auto parts = photo_split_parts(names);
    std::vector<std::string> shuffled = names;
    std::reverse(shuffled.begin(), shuffled.end());
    const auto parts_rev = photo_split_parts(shuffled);
    for (size_t i = 0; i < names.size(); ++i) CHECK(parts[i] == parts_rev[names.size() - 1 - i]);
    // 30 names: 15 / 15.
    CHECK(select_photo_split(listing(30), PhotoSplit::tune).size() == 15);
    CHECK(select_photo_split(listing(30), PhotoSplit::heldout).size() == 15);
}

TEST_CASE("the photo split rejects bad names and parts", "[vision][split]") {
    CHECK_THROWS_AS(photo_split_parts({"a", "b", "a"}), InvalidInput);
    CHECK_THROWS_AS(photo_split_parts({"a", ""}), InvalidInput);
    CHECK_THROWS_AS(parse_photo_split("held-out"), InvalidInput);
    CHECK(parse_photo_split("heldout") == PhotoSplit::heldout);
    CHECK(parse_photo_split("tune") == PhotoSplit::tune);
    CHECK(parse_photo_split("all") == PhotoSplit::all);
}

// The learned layout prior of the automatic segmentation (libvision/src/body_layout.hpp,
// layout_frame.hpp, layout_prior_data.cpp): frame cells and the class probabilities the
// embedded counts give on a drawn standing figure's joints.
#include "synthetic_figure.hpp"

#include "body_layout.hpp"
#include "layout_frame.hpp"
#include "layout_prior_data.hpp"

#include <catch2/catch.hpp>

#include <set>

using namespace drape;
using namespace drape::vision;
using namespace drape::vision::detail;

namespace {

/// p(label) at image point (x, y).
double prob(const std::array<cv::Mat, kAutoLabels>& p, AutoLabel l, const Eigen::Vector2d& q) {
    return p[size_t(l)].at<float>(int(q.y()), int(q.x()));
}

}  // namespace

TEST_CASE("body frame cells: nearest bone, position along it, signed distance", "[vision][layout]") {
    const auto fig = test::make_figure();
    const Joints& j = fig.joints;
    const auto seg = frame_segments(j);
    const double H = j.body_height_px();
    // A point on the right thigh's line, a third of the way down: bone 0, along bin 3, the
    // two distance bins next to the line.
    const Eigen::Vector2d thigh = j[Joint::right_hip] + 0.35 * (j[Joint::right_knee] - j[Joint::right_hip]);
    const int c = frame_cell(seg, H, thigh);
    CHECK(c / (kFrameAlong * kFrameAcross) == 0);
    CHECK((c / kFrameAcross) % kFrameAlong == 3);
    const int across = c % kFrameAcross;
    CHECK((across == kFrameAcross / 2 || across == kFrameAcross / 2 - 1));
    // Far from the body: an outer distance bin; every cell index within range.
    std::set<int> cells;
    for (int y = 0; y < fig.photo.rows; y += 7)
        for (int x = 0; x < fig.photo.cols; x += 7) {
            const int k = frame_cell(seg, H, {x + 0.5, y + 0.5});
            REQUIRE(k >= 0);
            REQUIRE(k < kFrameCells);
            cells.insert(k);
        }
    CHECK(cells.size() > 300);
    const int corner = frame_cell(seg, H, {0.5, 0.5}) % kFrameAcross;
    CHECK((corner == 0 || corner == kFrameAcross - 1));
}

TEST_CASE("the learned layout puts the classes where the hand labels had them", "[vision][layout]") {
    // The embedded counts come from hand-labelled photos (tools/derive_layout_prior.cpp);
    // on a drawn standing figure the most likely class must follow the body.
    std::uint64_t total = 0;
    for (int c = 0; c < kFrameCells; ++c)
        for (int l = 0; l < kLayoutPriorClasses; ++l) total += kLayoutPriorCounts[c][l];
    REQUIRE(total > 1000000);  // the table is not the empty bootstrap file
    const auto fig = test::make_figure();
    const Joints& j = fig.joints;
    const auto p = learned_layout(fig.photo.size(), j, 20.0);
    // Probabilities sum to 1 everywhere.
    for (int y = 0; y < fig.photo.rows; y += 13)
        for (int x = 0; x < fig.photo.cols; x += 13) {
            double sum = 0;
            for (int l = 0; l < kAutoLabels; ++l) sum += p[size_t(l)].at<float>(y, x);
            REQUIRE(sum == Approx(1.0).margin(1e-4));
        }
    const Eigen::Vector2d chest = j.mid_shoulder() + 0.35 * (j.mid_hip() - j.mid_shoulder());
    const Eigen::Vector2d thigh = j[Joint::left_hip] + 0.25 * (j[Joint::left_knee] - j[Joint::left_hip]);
    const Eigen::Vector2d face = j[Joint::neck] + 0.5 * (j[Joint::head] - j[Joint::neck]);
    const Eigen::Vector2d shin = j[Joint::right_knee] + 0.5 * (j[Joint::right_ankle] - j[Joint::right_knee]);
    const Eigen::Vector2d foot = j[Joint::left_ankle] + Eigen::Vector2d(0, 0.01 * j.body_height_px());
    const Eigen::Vector2d aside = j[Joint::right_hip] + Eigen::Vector2d(-0.25 * j.body_height_px(), 0);
    CHECK(prob(p, kUpper, chest) > 0.6);
    CHECK(prob(p, kLower, thigh) > 0.5);
    CHECK(prob(p, kSkin, face) > 0.5);
    CHECK(prob(p, kBackground, aside) > 0.8);
    // Lower legs: bare skin, tights or trousers, rarely background.
    CHECK(prob(p, kBackground, shin) < 0.2);
    // Shoes: "other" is the likeliest class at the foot.
    int best = 0;
    for (int l = 1; l < kAutoLabels; ++l)
        if (prob(p, AutoLabel(l), foot) > prob(p, AutoLabel(best), foot)) best = l;
    CHECK(best == kOther);
}

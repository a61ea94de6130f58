#include <drape/garment/silhouette_distance.hpp>

#include <drape/core/distance_transform.hpp>
#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>

namespace drape::garment {

namespace {

// The pixels of `mask` with a 4-neighbour off (or on the image border): its outline.
std::vector<std::uint8_t> outline(const BinaryImage& mask) {
    const int w = mask.width, h = mask.height;
    std::vector<std::uint8_t> out(mask.pixels.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!mask.on(x, y)) continue;
            const bool edge = x == 0 || y == 0 || x == w - 1 || y == h - 1 || !mask.on(x - 1, y) ||
                              !mask.on(x + 1, y) || !mask.on(x, y - 1) || !mask.on(x, y + 1);
            if (edge) out[static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)] = 1;
        }
    return out;
}

void check_same_size(const BinaryImage& a, const BinaryImage& b, const char* what) {
    if (b.width == 0 && b.height == 0 && b.pixels.empty()) return;
    if (a.width != b.width || a.height != b.height || b.pixels.size() != a.pixels.size())
        throw InvalidInput(std::string("silhouette distance: ") + what + " is " + std::to_string(b.width) + " x " +
                           std::to_string(b.height) + ", the target garment " + std::to_string(a.width) + " x " +
                           std::to_string(a.height));
}

bool present(const BinaryImage& b) { return !b.pixels.empty(); }

}  // namespace

int BinaryImage::count() const {
    return static_cast<int>(std::count_if(pixels.begin(), pixels.end(), [](std::uint8_t v) { return v != 0; }));
}

bool SilhouetteDistanceOptions::is_valid(std::string* why) const {
    if (!(occluder_margin_px >= 0) || !std::isfinite(occluder_margin_px)) {
        if (why) *why = "occluder_margin_px must be >= 0 (got " + std::to_string(occluder_margin_px) + ")";
        return false;
    }
    if (!(cap_px > 0) || !std::isfinite(cap_px)) {
        if (why) *why = "cap_px must be > 0 (got " + std::to_string(cap_px) + ")";
        return false;
    }
    return true;
}

SilhouetteScorer::SilhouetteScorer(SilhouetteTarget target, SilhouetteDistanceOptions options)
    : target_(std::move(target)), options_(options) {
    std::string why;
    if (!options_.is_valid(&why)) throw InvalidInput("silhouette distance options: " + why);
    const BinaryImage& g = target_.garment;
    if (g.width <= 0 || g.height <= 0 ||
        g.pixels.size() != static_cast<size_t>(g.width) * static_cast<size_t>(g.height))
        throw InvalidInput("silhouette distance: the target garment image is empty or its pixel count does not match " +
                           std::to_string(g.width) + " x " + std::to_string(g.height));
    check_same_size(g, target_.occluders, "the occluder image");
    const auto line = outline(g);
    to_target_ = core::distance_transform(g.width, g.height, line, true);
    if (present(target_.occluders))
        near_occluder_ = core::distance_transform(g.width, g.height, target_.occluders.pixels, true);
    for (size_t i = 0; i < line.size(); ++i) {
        if (!line[i]) continue;
        const int x = static_cast<int>(i % static_cast<size_t>(g.width)), y = static_cast<int>(i / static_cast<size_t>(g.width));
        // The image border is not the garment's outline (the photo cuts it there).
        if (x == 0 || y == 0 || x == g.width - 1 || y == g.height - 1) continue;
        if (!near_occluder_.empty() && near_occluder_[i] <= options_.occluder_margin_px + 1.0) continue;
        target_boundary_.push_back(static_cast<int>(i));
    }
}

SilhouetteDistance SilhouetteScorer::score(const CandidateSilhouette& c) const {
    const BinaryImage& g = target_.garment;
    check_same_size(g, c.visible, "the candidate's visible image");
    if (!present(c.visible)) throw InvalidInput("silhouette distance: the candidate's visible image is empty");
    check_same_size(g, c.occluded, "the candidate's occluded image");
    const int w = g.width, h = g.height;
    const double cap2 = options_.cap_px * options_.cap_px;
    std::vector<float> near_front;
    if (present(c.occluded)) near_front = core::distance_transform(w, h, c.occluded.pixels, true);
    const double margin = options_.occluder_margin_px + 1.0;

    SilhouetteDistance out;
    const auto line = outline(c.visible);
    double sum_c = 0;
    for (size_t i = 0; i < line.size(); ++i) {
        if (!line[i]) continue;
        const int x = static_cast<int>(i % static_cast<size_t>(w)), y = static_cast<int>(i / static_cast<size_t>(w));
        if (x == 0 || y == 0 || x == w - 1 || y == h - 1) continue;
        if (!near_front.empty() && near_front[i] <= margin) continue;            // occlusion edge
        if (!near_occluder_.empty() && near_occluder_[i] <= margin) continue;    // hidden in the photo
        const double d = std::min<double>(to_target_[i], options_.cap_px);
        sum_c += d * d;
        ++out.candidate_points;
    }
    double sum_t = 0;
    if (!target_boundary_.empty()) {
        const auto to_candidate = core::distance_transform(w, h, line, true);
        for (const int i : target_boundary_) {
            const size_t k = static_cast<size_t>(i);
            if (!near_front.empty() && near_front[k] <= margin) continue;  // the candidate is hidden there
            const double d = std::min<double>(to_candidate[k], options_.cap_px);
            sum_t += d * d;
            ++out.target_points;
        }
    }
    const double mc = out.candidate_points ? sum_c / out.candidate_points : cap2;
    const double mt = out.target_points ? sum_t / out.target_points : cap2;
    out.candidate_to_target_px = std::sqrt(mc);
    out.target_to_candidate_px = std::sqrt(mt);
    out.energy_px2 = 0.5 * (mc + mt);
    return out;
}

}  // namespace drape::garment

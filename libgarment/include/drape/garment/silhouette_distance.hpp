// The silhouette term of the recovery (paper eq. 9-10): how far the outline of a draped
// candidate garment, projected with the fitted camera, lies from the garment's outline in
// the photo, over the visible, non-occluded boundary only. Plain image data in (libgarment
// does not depend on libvision or on a renderer): the caller rasterises both.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace drape::garment {

/// A row-major 8-bit image, width x height, 0 = off, non-zero = on.
struct BinaryImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;  ///< width * height

    bool on(int x, int y) const { return pixels[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)] != 0; }
    int count() const;
};

/// The garment as the photo shows it.
struct SilhouetteTarget {
    BinaryImage garment;     ///< the garment's pixels (its segmentation mask, or its filled polygons)
    /// Pixels where the photo cannot show the garment's own outline: whatever may lie in
    /// front of it (hair, arms, bags, the other garments) and the image border band. Target
    /// boundary points next to these are ignored, and so are candidate points over them.
    /// Same size as `garment`; empty (0 x 0) = none.
    BinaryImage occluders;
};

/// A candidate drape as the fitted camera sees it.
struct CandidateSilhouette {
    BinaryImage visible;     ///< the garment's visible pixels (z-buffered against the body and other garments)
    /// Pixels where something of the scene lies in front of the garment's projection (the
    /// body, other garments): the visible outline there is an occlusion edge, not the
    /// garment's. Same size; empty = none.
    BinaryImage occluded;
};

struct SilhouetteDistanceOptions {
    /// Boundary points within this distance (pixels) of an occluder are not counted, >= 0.
    double occluder_margin_px = 2.0;
    /// A point's distance is capped here (pixels), so one far stray region does not dominate, > 0.
    double cap_px = 60.0;
    bool is_valid(std::string* why = nullptr) const;
};

struct SilhouetteDistance {
    /// The energy: ½ (mean d² of candidate boundary points to the target outline + mean d²
    /// of target boundary points to the candidate outline), pixels²; a one-sided sum would
    /// favour shrinking the garment. cap_px² when either side has no counted point.
    double energy_px2 = 0;
    double candidate_to_target_px = 0;  ///< RMS distance, candidate side
    double target_to_candidate_px = 0;  ///< RMS distance, target side
    int candidate_points = 0;           ///< counted candidate boundary pixels
    int target_points = 0;              ///< counted target boundary pixels
};

/// Scores candidates against one target: the target's outline and its distance field are
/// computed once (construction), each score() then costs one distance transform of the
/// candidate's outline. score() is const and may be called from several threads at once.
class SilhouetteScorer {
  public:
    /// \throw drape::InvalidInput if the images are empty, their sizes differ, or the
    ///        options are invalid (naming the field).
    SilhouetteScorer(SilhouetteTarget target, SilhouetteDistanceOptions options = {});

    /// \throw drape::InvalidInput if the candidate's size differs from the target's.
    SilhouetteDistance score(const CandidateSilhouette& candidate) const;

    int width() const { return target_.garment.width; }
    int height() const { return target_.garment.height; }
    int target_points() const { return static_cast<int>(target_boundary_.size()); }

  private:
    SilhouetteTarget target_;
    SilhouetteDistanceOptions options_;
    std::vector<float> near_occluder_;   ///< distance to the nearest occluder pixel
    std::vector<float> to_target_;       ///< distance to the target's outline
    std::vector<int> target_boundary_;   ///< pixel indices of the counted target outline
};

}  // namespace drape::garment

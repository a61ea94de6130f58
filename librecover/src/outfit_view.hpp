// Private to librecover: the garment targets from the segmentation, and candidate drapes as
// the fitted camera sees them (librender's z-buffer rasteriser).
#pragma once

#include "candidate_draper.hpp"

#include <drape/body/body_model.hpp>
#include <drape/body/camera.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/silhouette_distance.hpp>
#include <drape/recover/outfit_meshes.hpp>
#include <drape/vision/label_table.hpp>
#include <drape/vision/segmentation.hpp>

#include <opencv2/core.hpp>

#include <vector>

namespace drape::recover {

/// The garment `label_id` as the photo shows it; its occluders are the segmentation's
/// occlusion band, hair, occluder classes (bags, belts, outerwear) and the garments layered
/// over it (`in_front`, e.g. a top's hem over the waistband of the pants).
garment::SilhouetteTarget silhouette_target(const vision::Segmentation& seg, const vision::LabelTable& table,
                                            int label_id, const std::vector<int>& in_front);

struct OutfitRaster {
    cv::Mat labels;                                          ///< CV_8UC1 class ids
    std::vector<garment::CandidateSilhouette> silhouettes;   ///< per garment
};

/// How far the other garments are moved in depth, along their camera rays, in a candidate's
/// view (OutfitView::candidate_scene), metres: more than the gap between a garment draped on
/// the body alone and one layered under it (about 1–3 cm), less than a torso's depth, so
/// a top's back hanging below its front hem stays behind the pants' front.
constexpr double kLayerDepthM = 0.05;

class OutfitView {
  public:
    OutfitView(const body::BodyModel& model, const Eigen::MatrixXd& body_vertices, const body::Camera& camera,
               int width, int height);

    /// The body with the other garments of candidate `c` and the candidate itself last
    /// (class ids: the candidate 1, the others 2, 3, ...). The other garments are moved
    /// along their camera rays by kLayerDepthM, behind the candidate if worn under it, in
    /// front if worn over it: their images are unchanged, their occlusion follows the layers.
    OutfitMeshes candidate_scene(const DrapedCandidate& c) const;
    /// Candidate `c`'s silhouette with the body and the other garments in front or behind.
    garment::CandidateSilhouette candidate(const DrapedCandidate& c) const;
    const body::Camera& camera() const { return camera_; }
    int width() const { return width_; }
    int height() const { return height_; }

    /// The body (label `body_label`) and the garments, each with its label.
    OutfitRaster project(const std::vector<const garment::GarmentMesh*>& meshes,
                         const std::vector<const Eigen::MatrixX3d*>& positions, const std::vector<int>& labels,
                         int body_label) const;

    /// The body posed as draped, with no garment.
    const OutfitMeshes& body() const { return body_; }

  private:
    OutfitMeshes body_;
    body::Camera camera_;
    int width_, height_;
};

}  // namespace drape::recover

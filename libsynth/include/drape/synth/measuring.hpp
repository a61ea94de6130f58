// What is measured on a draped and rendered scene for its ground truth and its report:
// each garment's mean curvature and deepest point inside the body, the image joints
// projected from the posed skeleton, and the wrinkle density P detected on the render.
#pragma once

#include <drape/body/pose.hpp>
#include <drape/synth/draping.hpp>
#include <drape/synth/sampling.hpp>
#include <drape/vision/joints.hpp>
#include <drape/vision/wrinkle_density.hpp>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace drape::synth {

/// Mean over the vertices of garment i's local curvature (cloth::vertex_local_curvature,
/// 1/m) in its draped state, per garment.
std::vector<double> mean_curvatures(const garment::DressedOutfit& outfit);

/// The vertex of a garment that lies deepest inside the body.
struct DeepestInside {
    bool found = false;            ///< false: no vertex inside (within 0.1 m of the surface)
    std::string panel;             ///< the pattern panel of the vertex
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< world, as draped
    double depth_m = 0;            ///< below the body's surface
    std::string body_joint;        ///< the joint that mainly moves the body face it is under ("" none)
};

/// Per garment, where it is deepest inside the posed body (#B x 3 world metres).
std::vector<DeepestInside> deepest_inside(const Eigen::MatrixXd& body_vertices,
                                          const garment::DressedOutfit& outfit);

/// The 14 image joints (body::kImageJoints) of the posed skeleton moved by scene.placement,
/// projected by scene.camera (image frame, pixel centres at +0.5).
vision::Joints project_joints(const SynthScene& scene, const body::PosedBody& posed);

/// Wrinkles detected on one garment's visible part of the render.
struct GarmentWrinkles {
    vision::WrinkleSummary summary;  ///< message "garment not visible" when no pixel shows it
    int visible_pixels = 0;          ///< pixels labelled with the garment's label
};

/// Per garment, vision::detect_wrinkles on `colour` within the pixels of `labels` equal to
/// its label, for a person of the scene's height; a detector refusal (e.g. a joint outside
/// the frame) is kept as the summary's message with P = 0. `detector` is the detector's
/// options (its person_height_m is replaced by the scene's).
std::vector<GarmentWrinkles> measure_wrinkles(const SynthScene& scene, const cv::Mat& colour, const cv::Mat& labels,
                                              const vision::Joints& joints, const vision::WrinkleOptions& detector = {});

}  // namespace drape::synth

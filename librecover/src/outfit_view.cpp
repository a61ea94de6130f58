#include "outfit_view.hpp"

#include <drape/recover/label_mask.hpp>

#include <algorithm>

namespace drape::recover {

namespace {

garment::BinaryImage binary(const cv::Mat& m) {
    garment::BinaryImage b;
    b.width = m.cols;
    b.height = m.rows;
    b.pixels.resize(static_cast<size_t>(m.cols) * static_cast<size_t>(m.rows));
    for (int y = 0; y < m.rows; ++y) {
        const std::uint8_t* row = m.ptr<std::uint8_t>(y);
        for (int x = 0; x < m.cols; ++x) b.pixels[static_cast<size_t>(y) * m.cols + x] = row[x] ? 1 : 0;
    }
    return b;
}

OutfitGarment outfit_garment(const garment::GarmentMesh& mesh, const Eigen::MatrixX3d& positions, int class_id,
                             const char* name) {
    OutfitGarment g;
    g.name = name;
    g.V = positions;
    g.F = mesh.cloth.faces;
    g.class_id = class_id;
    return g;
}

// Garment `k` of a label mask: its visible pixels, and where something lies in front of it.
garment::CandidateSilhouette silhouette_of(const LabelMask& m, size_t k) {
    garment::CandidateSilhouette s;
    s.visible = binary(m.visible[k + 1]);
    cv::Mat hidden;
    cv::bitwise_and(m.coverage[k + 1], ~m.visible[k + 1], hidden);
    s.occluded = binary(hidden);
    return s;
}

// Moves every vertex along its camera ray by `delta_m` (> 0: away from the camera), which
// keeps its image: pinhole rays leave the centre (0, 0, distance_m); weak perspective looks
// down -Z.
Eigen::MatrixX3d along_camera_rays(const Eigen::MatrixX3d& V, const body::Camera& camera, double delta_m) {
    Eigen::MatrixX3d out = V;
    if (camera.model == body::CameraModel::weak_perspective) {
        out.col(2).array() -= delta_m;
        return out;
    }
    const Eigen::RowVector3d centre(0, 0, camera.distance_m);
    for (Eigen::Index i = 0; i < out.rows(); ++i) {
        const Eigen::RowVector3d ray = out.row(i) - centre;
        const double n = ray.norm();
        if (n > 0) out.row(i) += (delta_m / n) * ray;
    }
    return out;
}

}  // namespace

garment::SilhouetteTarget silhouette_target(const vision::Segmentation& seg, const vision::LabelTable& table,
                                            int label_id, const std::vector<int>& in_front) {
    garment::SilhouetteTarget t;
    t.garment.width = t.occluders.width = seg.labels.cols;
    t.garment.height = t.occluders.height = seg.labels.rows;
    const size_t n = static_cast<size_t>(seg.labels.cols) * static_cast<size_t>(seg.labels.rows);
    t.garment.pixels.assign(n, 0);
    t.occluders.pixels.assign(n, 0);
    const int hair = table.hair_id();
    for (int y = 0; y < seg.labels.rows; ++y)
        for (int x = 0; x < seg.labels.cols; ++x) {
            const int id = seg.labels.at<std::uint8_t>(y, x);
            const size_t k = static_cast<size_t>(y) * seg.labels.cols + x;
            if (id == label_id) t.garment.pixels[k] = 1;
            const bool occluder = id == hair || table.role(id) == vision::LabelRole::occluder ||
                                  std::find(in_front.begin(), in_front.end(), id) != in_front.end() ||
                                  (!seg.occlusion.empty() && seg.occlusion.at<std::uint8_t>(y, x) != 0);
            if (occluder && id != label_id) t.occluders.pixels[k] = 1;
        }
    return t;
}

OutfitView::OutfitView(const body::BodyModel& model, const Eigen::MatrixXd& body_vertices, const body::Camera& camera,
                       int width, int height)
    : camera_(camera), width_(width), height_(height) {
    body_.body_V = body_vertices;
    body_.body_F = model.faces;
}

OutfitMeshes OutfitView::candidate_scene(const DrapedCandidate& c) const {
    OutfitMeshes scene = body_;
    // The candidate was re-draped on the body alone (garment::SizingDrape does not layer), so
    // its depth against the other garments as first draped need not be the worn one, and the
    // wrong layer could hide an outline (docs/recovery.md, "Layers in the candidate's view").
    // Each other garment is moved along its camera rays, which keeps its image, by
    // kLayerDepthM: away from the camera when worn under the candidate, towards it when over.
    for (size_t j = 0; j < c.other_meshes.size(); ++j) {
        const double delta = c.other_index[j] < c.index ? kLayerDepthM : -kLayerDepthM;
        scene.garments.push_back(outfit_garment(c.other_meshes[j], along_camera_rays(c.other_positions[j], camera_, delta),
                                                2 + static_cast<int>(j), "other"));
    }
    scene.garments.push_back(outfit_garment(c.mesh, c.positions, 1, "candidate"));
    return scene;
}

garment::CandidateSilhouette OutfitView::candidate(const DrapedCandidate& c) const {
    const OutfitMeshes scene = candidate_scene(c);
    LabelMaskOptions o;
    o.width_px = width_;
    o.height_px = height_;
    o.coverage = true;
    LabelMask m;
    label_mask(scene, camera_, o, m);
    return silhouette_of(m, scene.garments.size() - 1);
}

OutfitRaster OutfitView::project(const std::vector<const garment::GarmentMesh*>& garments,
                                 const std::vector<const Eigen::MatrixX3d*>& positions, const std::vector<int>& labels,
                                 int body_label) const {
    OutfitMeshes scene = body_;
    scene.body_class_id = body_label;
    for (size_t i = 0; i < garments.size(); ++i)
        scene.garments.push_back(outfit_garment(*garments[i], *positions[i], labels[i], "garment"));
    LabelMaskOptions o;
    o.width_px = width_;
    o.height_px = height_;
    o.coverage = true;
    LabelMask m;
    label_mask(scene, camera_, o, m);
    OutfitRaster out;
    out.labels = m.labels;
    for (size_t i = 0; i < garments.size(); ++i) out.silhouettes.push_back(silhouette_of(m, i));
    return out;
}

}  // namespace drape::recover

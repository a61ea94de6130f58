#include "outfit_view.hpp"

#include <drape/render/rasterize.hpp>

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

render::Mesh garment_mesh(const garment::GarmentMesh& mesh, const Eigen::MatrixX3d& positions, int label,
                          const char* name) {
    render::Mesh m;
    m.name = name;
    m.V = positions;
    m.F = mesh.cloth.faces;
    m.label = label;
    return m;
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
    body_.name = "body";
    body_.V = body_vertices;
    body_.F = model.faces;
    body_.label = 41;
}

garment::CandidateSilhouette OutfitView::candidate(const CandidateDraper&, int, const DrapedCandidate& c, int) const {
    std::vector<render::Mesh> meshes;
    meshes.push_back(body_);
    for (size_t j = 0; j < c.other_meshes.size(); ++j)
        meshes.push_back(garment_mesh(c.other_meshes[j], c.other_positions[j], 2 + static_cast<int>(j), "other garment"));
    meshes.push_back(garment_mesh(c.mesh, c.positions, 1, "candidate garment"));
    render::RasterOptions ro;
    ro.width_px = width_;
    ro.height_px = height_;
    ro.coverage = true;
    render::RasterImages images;
    render::rasterize(meshes, camera_, ro, images);
    garment::CandidateSilhouette s;
    s.visible = binary(images.visible.back());
    cv::Mat hidden;
    cv::bitwise_and(images.coverage.back(), ~images.visible.back(), hidden);
    s.occluded = binary(hidden);
    return s;
}

OutfitRaster OutfitView::project(const std::vector<const garment::GarmentMesh*>& garments,
                                 const std::vector<const Eigen::MatrixX3d*>& positions, const std::vector<int>& labels,
                                 int body_label) const {
    std::vector<render::Mesh> meshes;
    meshes.push_back(body_);
    meshes.back().label = body_label;
    for (size_t i = 0; i < garments.size(); ++i)
        meshes.push_back(garment_mesh(*garments[i], *positions[i], labels[i], "garment"));
    render::RasterOptions ro;
    ro.width_px = width_;
    ro.height_px = height_;
    ro.coverage = true;
    render::RasterImages images;
    render::rasterize(meshes, camera_, ro, images);
    OutfitRaster out;
    out.labels = images.labels;
    for (size_t i = 0; i < garments.size(); ++i) {
        garment::CandidateSilhouette s;
        s.visible = binary(images.visible[i + 1]);
        cv::Mat hidden;
        cv::bitwise_and(images.coverage[i + 1], ~images.visible[i + 1], hidden);
        s.occluded = binary(hidden);
        out.silhouettes.push_back(std::move(s));
    }
    return out;
}

}  // namespace drape::recover

#include <drape/vision/garment_result.hpp>

#include <drape/vision/image_io.hpp>

#include <drape/core/errors.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace drape::vision {

bool GarmentOptions::is_valid(std::string* why) const {
    if (!wrinkles.is_valid(why)) return false;
    if (!(polygon_tolerance_fraction >= 0)) {
        if (why) *why = "polygon_tolerance_fraction must be >= 0";
        return false;
    }
    if (!(min_area_fraction >= 0 && min_area_fraction < 1)) {
        if (why) *why = "min_area_fraction must be in [0, 1)";
        return false;
    }
    return true;
}

GarmentType garment_type_of_class(const cv::Mat& mask, int label_id, const LabelTable& table,
                                  const Joints& joints, const cv::Mat& hiding) {
    const std::string& name = table.name(label_id);
    if (table.role(label_id) == LabelRole::full_garment) return GarmentType::dress;
    if (name == "skirt") return GarmentType::skirt;
    if (name == "shorts") return GarmentType::shorts;
    if (table.role(label_id) == LabelRole::lower_garment) return GarmentType::pants;
    require(table.role(label_id) == LabelRole::upper_garment, "class ", label_id, " ('", name,
            "') is not a garment class");
    return classify_upper(measure_shape_cues(mask, joints, hiding));
}

namespace {

Eigen::Matrix<double, Eigen::Dynamic, 2> to_eigen(const std::vector<cv::Point>& c) {
    Eigen::Matrix<double, Eigen::Dynamic, 2> m(static_cast<Eigen::Index>(c.size()), 2);
    for (size_t i = 0; i < c.size(); ++i) {
        m(Eigen::Index(i), 0) = c[i].x + 0.5;
        m(Eigen::Index(i), 1) = c[i].y + 0.5;
    }
    return m;
}

std::vector<SilhouettePiece> silhouette(const cv::Mat& mask, double tolerance) {
    std::vector<std::vector<cv::Point>> contours;
    std::vector<cv::Vec4i> hierarchy;
    cv::findContours(mask.clone(), contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
    auto simplify = [&](const std::vector<cv::Point>& c) {
        if (tolerance <= 0) return c;
        std::vector<cv::Point> out;
        cv::approxPolyDP(c, out, tolerance, true);
        return out;
    };
    std::vector<SilhouettePiece> pieces;
    for (size_t i = 0; i < contours.size(); ++i) {
        if (hierarchy[i][3] >= 0) continue;  // a hole; added with its parent
        SilhouettePiece p;
        p.outer = to_eigen(simplify(contours[i]));
        for (int h = hierarchy[i][2]; h >= 0; h = hierarchy[static_cast<size_t>(h)][0])
            p.holes.push_back(to_eigen(simplify(contours[static_cast<size_t>(h)])));
        pieces.push_back(std::move(p));
    }
    return pieces;
}

}  // namespace

std::vector<GarmentResult> describe_garments(const cv::Mat& image, const Segmentation& seg,
                                             const Joints& joints, const LabelTable& table,
                                             const GarmentOptions& options,
                                             const std::optional<GarmentType>& hint) {
    std::string why;
    require(options.is_valid(&why), "GarmentOptions: ", why);
    check_image(image, CV_8UC3, "photo");
    require(!seg.labels.empty() && seg.labels.type() == CV_8UC1 && seg.labels.size() == image.size(),
            "describe_garments: the label map must be CV_8UC1 of the photo's size");
    joints.validate(image.cols, image.rows);
    int counts[256] = {};
    for (auto it = seg.labels.begin<std::uint8_t>(); it != seg.labels.end<std::uint8_t>(); ++it)
        ++counts[*it];
    const double min_area = options.min_area_fraction * double(seg.labels.total());
    const double H = joints.body_height_px();
    const cv::Mat hiding = sleeve_hiding_mask(seg.labels, table);
    std::vector<GarmentResult> out;
    for (int id = 0; id < kUnmarked; ++id) {
        const LabelRole role = table.role(id);
        if (counts[id] == 0 || counts[id] < min_area ||
            (role != LabelRole::upper_garment && role != LabelRole::lower_garment &&
             role != LabelRole::full_garment))
            continue;
        GarmentResult g;
        g.label_id = id;
        g.class_name = table.name(id);
        const cv::Mat mask = seg.labels == id;
        g.area_px = counts[id];
        auto listed = std::find_if(seg.garment_types.begin(), seg.garment_types.end(),
                                   [id](const auto& p) { return p.first == id; });
        g.type = listed != seg.garment_types.end() ? listed->second
                                                   : garment_type_of_class(mask, id, table, joints, hiding);
        if (hint && part_of(*hint) == part_of(g.type)) g.type = *hint;
        g.cues = measure_shape_cues(mask, joints, hiding);
        g.features = measure_features(mask, g.type, joints, hiding);
        g.silhouette = silhouette(mask, options.polygon_tolerance_fraction * H);
        // Hidden part: pixels inside the outer outlines that are not this garment.
        cv::Mat filled = cv::Mat::zeros(mask.size(), CV_8UC1);
        std::vector<std::vector<cv::Point>> outer;
        cv::findContours(mask.clone(), outer, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
        cv::drawContours(filled, outer, -1, cv::Scalar(255), cv::FILLED);
        const int hidden = cv::countNonZero(filled & ~mask);
        g.occlusion_fraction = double(hidden) / double(hidden + g.area_px);
        g.wrinkles = detect_wrinkles(image, mask, seg.occlusion, joints, options.wrinkles, &g.folds);
        out.push_back(std::move(g));
    }
    std::sort(out.begin(), out.end(),
              [](const GarmentResult& a, const GarmentResult& b) { return a.area_px > b.area_px; });
    return out;
}

}  // namespace drape::vision

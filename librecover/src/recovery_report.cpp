#include <drape/recover/recovery_report.hpp>

#include <drape/garment/pattern_svg.hpp>
#include <drape/vision/segmentation.hpp>
#include <drape/vision/wrinkle_density.hpp>

#include <cstdio>
#include <string>

namespace drape::recover {

namespace {

std::string num(double v, int digits = 2) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

}  // namespace

OutfitMeshes outfit_meshes(const body::BodyModel& model, const RecoveryResult& r) {
    OutfitMeshes m;
    m.body_V = r.body_vertices;
    m.body_F = model.faces;
    for (const RecoveredGarment& g : r.garments) {
        OutfitGarment o;
        o.name = garment_choice_name(g.choice);
        o.V = g.positions;
        o.F = g.mesh.cloth.faces;
        o.UV = g.mesh.uv;
        o.class_id = g.label_id;
        m.garments.push_back(std::move(o));
    }
    return m;
}

ReportContent recovery_report(const cv::Mat& photo, const RecoveryResult& r, const RecoverSummary& s,
                              const cv::Mat& overlay, const std::string& title) {
    ReportContent c;
    c.title = title;
    c.images.push_back(report_image("The photo", photo, "image/jpeg"));
    if (!r.segmentation.labels.empty())
        c.images.push_back(report_image("Segmentation", vision::draw_segmentation(photo, r.segmentation.labels), "image/jpeg"));
    for (const vision::GarmentResult& g : r.seen) {
        if (g.folds.empty() || r.segmentation.labels.empty()) continue;
        const cv::Mat mask = r.segmentation.labels == g.label_id;
        c.images.push_back(report_image("Folds of the " + g.class_name + " (P = " + num(g.wrinkles.density_per_m2, 1) +
                                            " per m²)",
                                        vision::draw_folds(photo, mask, g.folds), "image/jpeg"));
    }
    if (!overlay.empty()) c.images.push_back(report_image("The recovered body and garments over the photo", overlay, "image/jpeg"));
    if (!r.mask.empty())
        c.images.push_back(report_image("mask.png: the recovery projected with the fitted camera", vision::draw_segmentation(photo, r.mask),
                                        "image/jpeg"));

    ReportTable garments;
    garments.caption = "Garments";
    garments.header = {"garment", "class", "sizing G (cm, deg)", "silhouette RMS px", "drape"};
    ReportTable material;
    material.caption = "Material";
    material.header = {"garment", "base fabric", "bending scale", "range", "nearest measured fabric", "P (1/m²)",
                       "K target (1/m)", "K (1/m)"};
    for (size_t i = 0; i < r.garments.size(); ++i) {
        const RecoveredGarment& g = r.garments[i];
        std::string sizing;
        const auto p = garment::sizing_parameters(g.type);
        const auto v = garment::sizing_values(g.sizing);
        for (size_t k = 0; k < p.size(); ++k) sizing += (k ? ", " : "") + p[k].name + " " + num(v[k], 1);
        std::string drape = g.drape.usable ? "usable" : "not usable";
        drape += " (penetration " + num(1000 * g.drape.penetration_max_m, 1) + " mm, seam gap " +
                 num(1000 * g.drape.seam_gap_max_m, 1) + " mm, " + std::to_string(g.drape.self_intersections) +
                 " self-intersections)";
        if (!g.drape.message.empty()) drape += ": " + g.drape.message;
        if (g.drape.source == DrapeState::Source::search)
            drape += "; the output drape was not usable: the search's re-drape at " + num(g.drape.edge_cm, 1) +
                     " cm edges is shown";
        garments.rows.push_back({garment_choice_name(g.choice) + (g.supported ? "" : " (unsupported: " + g.unsupported_reason + ")"),
                                 g.class_name, sizing, num(g.silhouette_rms_px, 1), drape});
        material.rows.push_back({garment_choice_name(g.choice), g.base_fabric, num(g.material.bending_scale, 2),
                                 num(g.bending_low, 2) + " – " + num(g.bending_high, 2), g.nearest_fabric,
                                 g.wrinkle_density_per_m2 >= 0 ? num(g.wrinkle_density_per_m2, 1) : "not measured",
                                 num(g.target_curvature_per_m, 2), num(g.mean_curvature_per_m, 2)});
        c.svgs.push_back({"Sewing pattern " + std::to_string(i) + ": " + garment_choice_name(g.choice),
                          garment::pattern_to_svg(g.pattern)});
    }
    c.tables.push_back(garments);
    c.tables.push_back(material);
    ReportTable body;
    body.caption = "Body";
    body.header = {"stature m", "weight kg", "chest m", "waist m", "hip m"};
    body.rows.push_back({num(r.fit.shape[body::Semantic::height_m], 3), num(r.fit.shape[body::Semantic::weight_kg], 1),
                         num(r.fit.shape[body::Semantic::chest_girth_m], 3),
                         num(r.fit.shape[body::Semantic::waist_girth_m], 3),
                         num(r.fit.shape[body::Semantic::hip_girth_m], 3)});
    c.tables.push_back(body);
    ReportTable time;
    time.caption = "Seconds per stage";
    time.header = {"segment", "body", "dress", "sizing", "material", "final drape", "total", "candidate drapes"};
    time.rows.push_back({num(s.seconds_segment, 1), num(s.seconds_fit, 1), num(s.seconds_dress, 1), num(s.seconds_sizing, 1),
                         num(s.seconds_material, 1), num(s.seconds_final, 1), num(s.seconds, 1),
                         std::to_string(s.evaluations)});
    c.tables.push_back(time);
    c.notes.push_back(s.brief_report());
    return c;
}

}  // namespace drape::recover

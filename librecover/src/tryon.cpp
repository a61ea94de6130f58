#include <drape/recover/tryon.hpp>

#include <drape/body/measurements.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/errors.hpp>
#include <drape/recover/label_mask.hpp>
#include <drape/recover/overlay.hpp>
#include <drape/vision/label_table.hpp>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>

namespace drape::recover {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct Cancelled {};

body::ShapedBody shape_of(const body::BodyModel& model, const body::SemanticRequest& request, const std::string& who,
                          body::SemanticShape* shape = nullptr) {
    const body::SemanticShape s = model.prior.complete(request);
    body::ShapedBody shaped;
    const body::ShapeSummary summary = body::shape_body(model, s, {}, shaped);
    require(summary.usable(), "tryon: the ", who, " cannot be shaped: ", summary.brief_report());
    if (shape) *shape = s;
    return shaped;
}

// The photo's person mask (every class but the background) or skin mask, as the body fit reads them.
body::Mask class_mask(const cv::Mat& labels, int id, bool all_but) {
    body::Mask m;
    m.width = labels.cols;
    m.height = labels.rows;
    m.pixels.assign(size_t(m.width) * size_t(m.height), 0);
    for (int y = 0; y < labels.rows; ++y)
        for (int x = 0; x < labels.cols; ++x)
            if ((labels.at<std::uint8_t>(y, x) == id) != all_but) m.pixels[size_t(y) * size_t(m.width) + size_t(x)] = 1;
    return m;
}

bool is_garment_role(vision::LabelRole r) {
    return r == vision::LabelRole::upper_garment || r == vision::LabelRole::lower_garment ||
           r == vision::LabelRole::full_garment;
}

}  // namespace

std::string tryon_stage_name(TryOnStage s) {
    switch (s) {
        case TryOnStage::fitting_body: return "fitting the body";
        case TryOnStage::grading: return "grading";
        case TryOnStage::draping: return "draping";
        case TryOnStage::rendering: return "rendering";
    }
    return "?";
}

bool TryOnOptions::is_valid(std::string* why) const {
    std::ostringstream s;
    if (!(std::isfinite(edge_cm) && edge_cm > 0.5 && edge_cm <= 20)) s << "edge_cm = " << edge_cm << " must be in (0.5, 20]";
    else if (max_drape_steps < 1) s << "max_drape_steps = " << max_drape_steps << " must be >= 1";
    else if (threads < 1) s << "threads = " << threads << " must be >= 1";
    else if (overlay_samples < 1 || overlay_samples > 4096) s << "overlay_samples = " << overlay_samples << " must be in 1..4096";
    else {
        std::string w;
        if (!grading.is_valid(&w)) s << w;
    }
    if (s.str().empty()) return true;
    if (why) *why = "TryOnOptions::" + s.str();
    return false;
}

int tryon_class_id(garment::GarmentType type) {
    const vision::LabelTable& t = vision::LabelTable::fashionista();
    switch (type) {
        case garment::GarmentType::skirt: return t.id("skirt");
        case garment::GarmentType::pants: return t.id("pants");
        case garment::GarmentType::tshirt: return t.id("t-shirt");
        case garment::GarmentType::dress: return t.id("dress");
    }
    return 0;
}

bool TryOnSummary::usable(const TryOnResult& result) const {
    if (termination != TryOnTermination::draped || result.garments.empty()) return false;
    for (const TriedOnGarment& g : result.garments)
        if (!g.drape.usable || !g.grading.usable()) return false;
    return true;
}

std::string TryOnSummary::brief_report() const {
    std::ostringstream os;
    os << std::fixed << std::setprecision(1);
    switch (termination) {
        case TryOnTermination::draped: os << "draped"; break;
        case TryOnTermination::graded: os << "graded only"; break;
        case TryOnTermination::body_fit_failed: os << "body fit failed"; break;
        case TryOnTermination::drape_failed: os << "drape failed"; break;
        case TryOnTermination::cancelled: os << "cancelled"; break;
    }
    if (!message.empty()) os << " (" << message << ")";
    if (termination == TryOnTermination::draped) os << ": " << drape.brief_report();
    os << "; " << seconds << " s (fit " << seconds_fit << ", grade " << seconds_grade << ", drape " << seconds_drape
       << ", render " << seconds_render << ")";
    return os.str();
}

OutfitMeshes tryon_outfit_meshes(const body::BodyModel& model, const TryOnResult& r) {
    OutfitMeshes m;
    m.body_V = r.body_vertices;
    m.body_F = model.faces;
    for (const TriedOnGarment& g : r.garments)
        m.garments.push_back(OutfitGarment{g.source.name, g.positions, g.mesh.cloth.faces, g.mesh.uv, g.class_id});
    return m;
}

TryOnSummary tryon(const body::BodyModel& model, const TryOnInputs& in, const TryOnOptions& options, TryOnResult& out) {
    const auto t0 = Clock::now();
    std::string why;
    require(options.is_valid(&why), "tryon: ", why);
    require(!in.garments.empty(), "tryon: no garment to try on");
    for (size_t i = 0; i < in.garments.size(); ++i) {
        const TryOnGarment& g = in.garments[i];
        const std::string who = "tryon: garment " + std::to_string(i) + " '" + g.name + "'";
        require(g.sizing.type == g.type, who, ": its sizing is of another template (",
                garment::garment_type_name(g.sizing.type), ")");
        require(g.material.is_valid(&why), who, ": ", why);
        try {
            garment::make_pattern(g.sizing);
        } catch (const InvalidInput& e) {
            throw InvalidInput(who + ": " + e.what());
        }
    }
    const bool photo = !in.target.body.has_value();
    if (photo) {
        require(!in.target.photo_bgr.empty() && in.target.photo_bgr.type() == CV_8UC3,
                "tryon: the target photo must be a non-empty 8-bit BGR image (or give a target body)");
        require(in.target.strokes.empty() || (in.target.strokes.size() == in.target.photo_bgr.size() &&
                                              in.target.strokes.type() == CV_8UC1),
                "tryon: the strokes must be CV_8UC1 of the photo's size");
    }
    out = TryOnResult{};
    TryOnSummary summary;
    const auto report = [&](TryOnStage stage, int step) {
        TryOnProgress p;
        p.stage = stage;
        p.step = step;
        p.seconds = since(t0);
        if (options.on_progress && !options.on_progress(p)) throw Cancelled{};
    };
    const auto finish = [&](TryOnTermination t, std::string message) {
        summary.termination = t;
        summary.message = std::move(message);
        summary.seconds = since(t0);
        return summary;
    };

    try {
        // ---- 1. The target body: shaped from the request, or fitted to the photo.
        report(TryOnStage::fitting_body, 0);
        auto ts = Clock::now();
        body::Pose pose = in.target.pose;
        Eigen::Vector3d offset = Eigen::Vector3d::Zero();
        if (!photo) {
            out.shaped = shape_of(model, *in.target.body, "target body", &out.shape);
        } else {
            const vision::SegmentationOptions seg_options;
            const vision::LabelTable& table = seg_options.table;
            const vision::SegmentationSummary seg =
                in.target.strokes.empty()
                    ? vision::segment_automatic(in.target.photo_bgr, in.target.joints, seg_options, out.segmentation)
                    : vision::segment_with_strokes(in.target.photo_bgr, in.target.strokes, &in.target.joints, seg_options,
                                                   out.segmentation);
            if (out.segmentation.labels.empty())
                return finish(TryOnTermination::body_fit_failed, "the photo could not be segmented: " + seg.brief_report());
            body::FitInputs fit_in;
            for (int j = 0; j < body::kImageJointCount; ++j)
                fit_in.joints_px.row(j) = in.target.joints.px[size_t(j)].transpose();
            fit_in.marks = in.target.joints.marks;
            fit_in.person = class_mask(out.segmentation.labels, table.background_id(), true);
            fit_in.skin = class_mask(out.segmentation.labels, table.skin_id(), false);
            if (fit_in.skin.count() == 0) fit_in.skin = body::Mask{};
            fit_in.height_m = in.target.height_m;
            fit_in.gender = in.target.gender;
            body::FitOptions fit_options;
            fit_options.threads = options.threads;
            const body::FitSummary fit = body::fit_body(model, fit_in, fit_options, out.fit);
            if (!fit.usable()) return finish(TryOnTermination::body_fit_failed, fit.brief_report());
            out.shape = out.fit.shape;
            out.shaped = body::shape_from_coefficients(model, out.fit.coefficients);
            // Draped standing where the dressing puts the body; the fitted root translation (a
            // rigid offset of the scene) is added back to everything afterwards.
            pose = out.fit.pose;
            offset = pose.translation;
            pose.translation.setZero();
        }
        summary.seconds_fit = since(ts);

        // ---- 2. Grade every garment from its own body to the target.
        report(TryOnStage::grading, 0);
        ts = Clock::now();
        const garment::GradingBody to = garment::measure_for_grading(model, out.shaped);
        std::vector<garment::GarmentRequest> requests;
        for (size_t i = 0; i < in.garments.size(); ++i) {
            const TryOnGarment& g = in.garments[i];
            const garment::GradingBody from =
                garment::measure_for_grading(model, shape_of(model, g.source_body, "body of garment " + std::to_string(i)));
            TriedOnGarment t;
            t.source = g;
            t.grading = garment::grade_sizing(g.sizing, from, to, options.grading, t.sizing);
            t.original_pattern = garment::make_pattern(g.sizing);
            t.class_id = tryon_class_id(g.type);
            if (t.grading.termination == garment::GradingTermination::invalid_pattern)
                return finish(TryOnTermination::drape_failed, "garment " + std::to_string(i) + " '" + g.name +
                                                                  "': the graded sizing makes no pattern: " +
                                                                  t.grading.message);
            garment::GarmentRequest r;
            r.type = g.type;
            r.sizing = t.sizing;
            r.material = g.material;
            requests.push_back(r);
            out.garments.push_back(std::move(t));
        }
        summary.seconds_grade = since(ts);
        if (!options.drape) return finish(TryOnTermination::graded, "");

        // ---- 3. Dress and drape the outfit.
        report(TryOnStage::draping, 0);
        ts = Clock::now();
        garment::DressOutfitOptions o;
        o.mesh.target_edge_cm = options.edge_cm;
        o.drape.max_steps = std::max(600, options.max_drape_steps);
        o.drape.min_steps = std::min(o.drape.min_steps, o.drape.max_steps);
        // Over a photo (camera on +Z) the arms are cleared of the trunk by the turn that
        // changes their image least, as in recovery.
        if (photo) o.arm_clearance.view_direction = Eigen::Vector3d::UnitZ();
        bool cancelled = false;
        if (options.on_progress)
            o.drape.on_progress = [&](const garment::DrapeProgress& p) {
                TryOnProgress q;
                q.stage = TryOnStage::draping;
                q.step = p.step;
                q.seconds = since(t0);
                cancelled = !options.on_progress(q);
                return !cancelled;
            };
        garment::DressedOutfit dressed;
        const garment::DressOutfitSummary ds = garment::dress_outfit(model, out.shaped, pose, requests, o, dressed);
        summary.drape = ds.drape;
        summary.seconds_drape = since(ts);
        if (ds.termination == garment::DressOutfitTermination::cancelled || cancelled) throw Cancelled{};
        if (ds.termination == garment::DressOutfitTermination::meshing_failed)
            return finish(TryOnTermination::drape_failed, ds.message);
        out.pose = dressed.pose;
        out.pose.translation += offset;
        out.body_vertices = dressed.body_vertices.rowwise() + offset.transpose();
        for (size_t i = 0; i < out.garments.size(); ++i) {
            TriedOnGarment& g = out.garments[i];
            g.pattern = dressed.patterns[i];
            g.mesh = dressed.meshes[i];
            g.positions = dressed.positions[i].rowwise() + offset.transpose();
            // Usable as recover() calls a final drape usable: the drape's own criteria and this
            // garment's independent check within the same tolerances.
            const garment::GarmentStateCheck& c = dressed.checks[i];
            const bool within = c.max_penetration_m <= ds.drape.penetration_tolerance_m &&
                                c.max_seam_gap_m < ds.drape.seam_gap_tolerance_m && c.self_intersections == 0;
            g.drape = DrapeState{ds.usable() && within,  ds.drape.converged,
                                 c.max_penetration_m,     c.max_seam_gap_m,
                                 c.self_intersections,    DrapeState::Source::output,
                                 options.edge_cm,         ds.drape.message};
        }

        // ---- 4. A photo target: the garments over the photo, and where the own garment shows.
        if (photo) {
            report(TryOnStage::rendering, 0);
            ts = Clock::now();
            const OutfitMeshes outfit = tryon_outfit_meshes(model, out);
            const cv::Mat& image = in.target.photo_bgr;
            // The person's own arms and head are the body's surface: where the body is nearest
            // the photo shows through (body_opacity 0); hair lies in front of everything.
            OverlayOptions overlay_options;
            overlay_options.body_opacity = 0.0;
            overlay_options.garment_opacity = 1.0;
            overlay_options.samples_per_pixel = options.overlay_samples;
            overlay_options.threads = options.threads;
            out.overlay = render_overlay(image, outfit, out.fit.camera, overlay_options);
            const vision::LabelTable& table = vision::LabelTable::fashionista();
            const cv::Mat hair = out.segmentation.labels == table.hair_id();
            image.copyTo(out.overlay, hair);
            LabelMaskOptions mask_options;
            mask_options.width_px = image.cols;
            mask_options.height_px = image.rows;
            LabelMask projected;
            label_mask(outfit, out.fit.camera, mask_options, projected);
            out.mask = projected.labels;
            out.own_garment_mask = cv::Mat::zeros(image.size(), CV_8UC1);
            long long own = 0, showing = 0;
            for (int y = 0; y < image.rows; ++y)
                for (int x = 0; x < image.cols; ++x) {
                    if (!is_garment_role(table.role(out.segmentation.labels.at<std::uint8_t>(y, x)))) continue;
                    ++own;
                    const int id = out.mask.at<std::uint8_t>(y, x);
                    if (id == 0 || id == outfit.body_class_id) {
                        out.own_garment_mask.at<std::uint8_t>(y, x) = 255;
                        ++showing;
                    }
                }
            out.own_garment_fraction = own > 0 ? double(showing) / double(own) : 0.0;
            summary.seconds_render = since(ts);
        }
    } catch (const Cancelled&) {
        return finish(TryOnTermination::cancelled, "cancelled");
    }
    return finish(TryOnTermination::draped, "");
}

}  // namespace drape::recover

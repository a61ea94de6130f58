// The recovery pipeline (docs/recovery.md): segment -> fit the body -> initial sizing ->
// dress -> rounds of (sizing search, material search) -> final drape -> mask.
#include <drape/recover/recover.hpp>

#include "candidate_draper.hpp"
#include "initial_sizing.hpp"
#include "joint_pose_material.hpp"
#include "wrinkle_synthesis.hpp"
#include "outfit_view.hpp"

#include <drape/body/measurements.hpp>
#include <drape/cloth/cloth_mesh.hpp>
#include <drape/cloth/local_curvature.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/arm_clearance.hpp>
#include <drape/garment/curvature_calibration.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/garment/silhouette_distance.hpp>
#include <drape/vision/label_table.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace drape::recover {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Image classes the templates cannot represent: the closest template's result is returned
// and the garment is marked unsupported (paper section 7, "Limitations").
const std::set<std::string>& unsupported_classes() {
    static const std::set<std::string> names = {"romper", "jumpsuit", "bodysuit", "coat",     "jacket",
                                                "blazer", "cardigan", "vest",     "cape",     "suit",
                                                "sweater", "sweatshirt", "intimate", "swimwear"};
    return names;
}

GarmentChoice choice_of(vision::GarmentType t) {
    switch (t) {
        case vision::GarmentType::t_shirt: return GarmentChoice::tshirt;
        case vision::GarmentType::tank_top: return GarmentChoice::tank;
        case vision::GarmentType::long_sleeve_top: return GarmentChoice::longsleeve;
        case vision::GarmentType::dress: return GarmentChoice::dress;
        case vision::GarmentType::skirt: return GarmentChoice::skirt;
        case vision::GarmentType::pants: return GarmentChoice::pants;
        case vision::GarmentType::shorts: return GarmentChoice::shorts;
    }
    return GarmentChoice::tshirt;
}

bool is_upper(garment::GarmentType t) { return t == garment::GarmentType::tshirt; }
bool is_lower(garment::GarmentType t) { return t == garment::GarmentType::skirt || t == garment::GarmentType::pants; }

// Which seen garments to recover, inner (bottom) first: the asked ones matched by template,
// or a dress / an upper and a lower garment as seen.
std::vector<std::pair<GarmentChoice, int>> choose_garments(const std::vector<vision::GarmentResult>& seen,
                                                           const std::vector<GarmentChoice>& asked,
                                                           std::string& why_none) {
    std::vector<std::pair<GarmentChoice, int>> out;  // (choice, index into seen)
    std::set<int> used;
    if (!asked.empty()) {
        std::set<garment::GarmentType> templates;
        for (const GarmentChoice c : asked)
            if (!templates.insert(template_of(c)).second)
                throw InvalidInput("the garment template '" + garment::garment_type_name(template_of(c)) +
                                   "' is asked for twice (" + garment_choice_name(c) + ")");
        for (const GarmentChoice c : asked) {
            int best = -1;
            for (size_t i = 0; i < seen.size(); ++i) {
                if (used.count(static_cast<int>(i))) continue;
                const garment::GarmentType t = template_of(choice_of(seen[i].type));
                const bool same = t == template_of(c) ||
                                  // a one-piece seen where a top or bottom is asked (and the reverse) still
                                  // gives its silhouette
                                  (template_of(c) == garment::GarmentType::dress && (is_upper(t) || is_lower(t))) ||
                                  (t == garment::GarmentType::dress && template_of(c) != garment::GarmentType::dress);
                if (same && (best < 0 || seen[i].area_px > seen[static_cast<size_t>(best)].area_px))
                    best = static_cast<int>(i);
            }
            if (best < 0) {
                why_none = "no " + garment_choice_name(c) + " found in the photo (the segmentation found " +
                           std::to_string(seen.size()) + " garment class(es))";
                return {};
            }
            used.insert(best);
            out.push_back({c, best});
        }
    } else {
        int dress = -1, upper = -1, lower = -1;
        for (size_t i = 0; i < seen.size(); ++i) {  // seen is largest first
            const garment::GarmentType t = template_of(choice_of(seen[i].type));
            if (t == garment::GarmentType::dress && dress < 0) dress = static_cast<int>(i);
            if (is_upper(t) && upper < 0) upper = static_cast<int>(i);
            if (is_lower(t) && lower < 0) lower = static_cast<int>(i);
        }
        const auto area = [&](int i) { return i < 0 ? 0 : seen[static_cast<size_t>(i)].area_px; };
        if (dress >= 0 && area(dress) >= area(upper) + area(lower)) {
            out.push_back({choice_of(seen[static_cast<size_t>(dress)].type), dress});
        } else {
            if (lower >= 0) out.push_back({choice_of(seen[static_cast<size_t>(lower)].type), lower});
            if (upper >= 0) out.push_back({choice_of(seen[static_cast<size_t>(upper)].type), upper});
            if (out.empty() && dress >= 0) out.push_back({choice_of(seen[static_cast<size_t>(dress)].type), dress});
        }
        if (out.empty()) why_none = "the segmentation found no garment";
    }
    // Inner first: the bottom under the top's hem.
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return is_lower(template_of(a.first)) && !is_lower(template_of(b.first));
    });
    return out;
}

body::Mask mask_of(const cv::Mat& labels, const std::function<bool(int)>& keep) {
    body::Mask m;
    m.width = labels.cols;
    m.height = labels.rows;
    m.pixels.assign(static_cast<size_t>(m.width) * static_cast<size_t>(m.height), 0);
    for (int y = 0; y < labels.rows; ++y)
        for (int x = 0; x < labels.cols; ++x)
            if (keep(labels.at<std::uint8_t>(y, x))) m.pixels[static_cast<size_t>(y) * m.width + x] = 1;
    return m;
}

// A garment's drape message: the outfit drape's own, and which of its checks failed (the
// garments are draped together: one garment's fault makes the outfit, so every garment,
// not usable, and result.json says why).
std::string outfit_drape_message(const garment::DrapeSummary& d) {
    const std::string failed = d.failed_checks();
    if (failed.empty()) return d.message;
    return "the outfit's drape: " + failed + (d.message.empty() ? std::string() : " (" + d.message + ")");
}

double mean_curvature(const garment::GarmentMesh& mesh, const Eigen::MatrixX3d& positions) {
    const std::vector<cloth::Hinge> hinges = cloth::build_hinges(mesh.cloth);
    return cloth::vertex_local_curvature(mesh.cloth, hinges, positions).mean();
}

// The measured fabric nearest to `m`: the smallest mean |log10 ratio| over the positive
// bending and stretching entries of the simulated (scaled) tables.
std::string nearest_fabric(const cloth::Material& m) {
    std::string best;
    double best_d = std::numeric_limits<double>::infinity();
    for (const std::string& name : cloth::builtin_material_names()) {
        const cloth::Material f = cloth::builtin_material(name);
        double sum = 0;
        int n = 0;
        for (size_t r = 0; r < 3; ++r)
            for (size_t c = 0; c < 5; ++c) {
                const double a = m.bending_n_m[r][c] * m.bending_scale, b = f.bending_n_m[r][c] * f.bending_scale;
                if (a > 0 && b > 0) sum += std::abs(std::log10(a / b)), ++n;
            }
        for (size_t r = 0; r < 6; ++r)
            for (size_t c = 0; c < 4; ++c) {
                const double a = m.stretching_n_per_m[r][c] * m.stretching_scale,
                             b = f.stretching_n_per_m[r][c] * f.stretching_scale;
                if (a > 0 && b > 0) sum += std::abs(std::log10(a / b)), ++n;
            }
        const double d = n ? sum / n : std::numeric_limits<double>::infinity();
        if (d < best_d) best_d = d, best = name;
    }
    return best;
}

}  // namespace

RecoverSummary recover(const body::BodyModel& model, const RecoverInputs& in, const RecoverOptions& options,
                       RecoveryResult& out) {
    const auto t0 = Clock::now();
    std::string why;
    if (!options.is_valid(&why)) throw InvalidInput("recover options: " + why);
    if (in.image_bgr.empty() || in.image_bgr.type() != CV_8UC3)
        throw InvalidInput("recover: the photo must be a non-empty 8-bit BGR image");
    in.joints.validate(in.image_bgr.cols, in.image_bgr.rows);
    if (!in.strokes.empty() && (in.strokes.size() != in.image_bgr.size() || in.strokes.type() != CV_8UC1))
        throw InvalidInput("recover: the strokes are " + std::to_string(in.strokes.cols) + " x " +
                           std::to_string(in.strokes.rows) + " but the photo is " + std::to_string(in.image_bgr.cols) +
                           " x " + std::to_string(in.image_bgr.rows) + " (or not an 8-bit class-id image)");
    if (in.height_m && !(*in.height_m > 0.5 && *in.height_m < 2.5))
        throw InvalidInput("recover: height " + std::to_string(*in.height_m) + " m is outside (0.5, 2.5) m");
    const cloth::Material base = cloth::builtin_material(options.base_fabric);  // throws on an unknown name

    out = RecoveryResult{};
    RecoverSummary summary;
    std::atomic<long> evaluations{0};
    RecoverProgress progress;
    auto report = [&](Stage stage, int garment, int round, double best, double eta = -1) {
        progress.stage = stage;
        progress.garment = garment;
        progress.round = round;
        progress.evaluations = evaluations;
        progress.best_objective = best;
        progress.seconds = since(t0);
        progress.eta_seconds = eta;
        if (options.on_progress && !options.on_progress(progress)) throw Cancelled{};
    };
    auto finish = [&](RecoverTermination t, std::string message) {
        summary.termination = t;
        summary.message = std::move(message);
        summary.evaluations = evaluations;
        summary.seconds = since(t0);
        return summary;
    };

    try {
        // ---- 1. Segmentation and garment description (libvision).
        report(Stage::segmenting, -1, 0, 0);
        auto ts = Clock::now();
        const vision::SegmentationOptions seg_options;
        const vision::LabelTable& table = seg_options.table;
        const vision::SegmentationSummary seg =
            in.strokes.empty()
                ? vision::segment_automatic(in.image_bgr, in.joints, seg_options, out.segmentation)
                : vision::segment_with_strokes(in.image_bgr, in.strokes, &in.joints, seg_options, out.segmentation);
        out.seen = vision::describe_garments(in.image_bgr, out.segmentation, in.joints, table, vision::GarmentOptions{});
        summary.seconds_segment = since(ts);
        std::string none;
        const auto chosen = choose_garments(out.seen, in.garments, none);
        if (chosen.empty())
            return finish(RecoverTermination::no_garment,
                          none + (seg.message.empty() ? std::string() : " (" + seg.message + ")"));

        // ---- 2. The body (libbody), from the joints and the person's silhouette.
        report(Stage::fitting_body, -1, 0, 0);
        ts = Clock::now();
        body::FitInputs fit_in;
        for (int j = 0; j < body::kImageJointCount; ++j)
            fit_in.joints_px.row(j) = in.joints.px[static_cast<size_t>(j)].transpose();
        fit_in.marks = in.joints.marks;
        const int background = table.background_id(), skin = table.skin_id();
        fit_in.person = mask_of(out.segmentation.labels, [&](int id) { return id != background; });
        fit_in.skin = mask_of(out.segmentation.labels, [&](int id) { return id == skin; });
        if (fit_in.skin.count() == 0) fit_in.skin = body::Mask{};
        fit_in.height_m = in.height_m;
        fit_in.gender = in.gender;
        body::FitOptions fit_options;
        fit_options.threads = options.threads;
        const body::FitSummary fit = body::fit_body(model, fit_in, fit_options, out.fit);
        summary.seconds_fit = since(ts);
        if (!fit.usable()) return finish(RecoverTermination::body_fit_failed, fit.brief_report());
        out.joint_error_percent = 100.0 * fit.mean_joint_error_px / in.joints.body_height_px();
        out.shaped = body::shape_from_coefficients(model, out.fit.coefficients);
        const body::BodyMeasurements measured = body::measure_body(model, out.shaped.vertices);

        // ---- 3. Starting sizing per garment and the initial registration (the dressing pipeline).
        report(Stage::dressing, -1, 0, 0);
        ts = Clock::now();
        std::vector<garment::GarmentRequest> requests;
        for (const auto& [choice, index] : chosen) {
            const vision::GarmentResult& g = out.seen[static_cast<size_t>(index)];
            RecoveredGarment r;
            r.choice = choice;
            r.type = template_of(choice);
            r.label_id = g.label_id;
            r.class_name = g.class_name;
            if (unsupported_classes().count(g.class_name)) {
                r.supported = false;
                r.unsupported_reason = "the templates cannot represent a " + g.class_name + "; this is the closest template's (" +
                                       garment::garment_type_name(r.type) + ") result";
            }
            r.initial_sizing = initial_sizing(choice, g.features, g.cues, in.joints, model, out.shaped, measured);
            r.sizing = r.initial_sizing;
            r.base_fabric = options.base_fabric;
            r.material = base;
            r.wrinkle_density_per_m2 = g.wrinkles.usable() ? g.wrinkles.density_per_m2 : -1.0;  // -1: not measured
            out.garments.push_back(std::move(r));
            garment::GarmentRequest req;
            req.type = out.garments.back().type;
            req.sizing = out.garments.back().sizing;
            req.material = base;
            requests.push_back(req);
        }
        // Layer order (outfit_layers: bottom, then the top over its waistband).
        // Raised arms lowered (they would drag a top up by its armholes), then the arms
        // cleared of the trunk by the dressing.
        const body::Pose drape_pose = garment::lower_raised_arms(model, out.shaped, out.fit.pose,
                                                                 options.max_arm_elevation_degrees, &out.arms_lowered);
        CandidateDraper draper(model, out.shaped, drape_pose, options);
        const garment::DressOutfitSummary dressed = draper.dress(requests);
        summary.seconds_dress = since(ts);
        if (dressed.termination == garment::DressOutfitTermination::meshing_failed)
            return finish(RecoverTermination::drape_failed, dressed.message);
        out.pose = draper.outfit().pose;
        out.arms_cleared = draper.outfit().arms;
        out.body_vertices = draper.outfit().body_vertices;

        // ---- 4. Targets: each garment's silhouette and what may hide it in the photo.
        OutfitView view(model, out.body_vertices, out.fit.camera, in.image_bgr.cols, in.image_bgr.rows);
        std::vector<garment::SilhouetteScorer> scorers;
        for (size_t i = 0; i < out.garments.size(); ++i) {
            std::vector<int> in_front;  // garments layered over this one
            for (size_t j = i + 1; j < out.garments.size(); ++j) in_front.push_back(out.garments[j].label_id);
            scorers.emplace_back(silhouette_target(out.segmentation, table, out.garments[i].label_id, in_front));
        }

        // ---- 5. Rounds of (material, sizing) per garment (paper Algorithm 1).
        for (int round = 1; round <= options.rounds; ++round) {
            bool improved = false;
            // Outer garments first: a top is not hidden by the pants under it, while the pants'
            // visible outline depends on where the top's hem now lies (set_sizing re-drapes it).
            for (size_t k = out.garments.size(); k-- > 0;) {
                const size_t i = k;
                RecoveredGarment& g = out.garments[i];
                // Material: the bending scale whose drape has the target curvature.
                if (options.estimate_material && g.wrinkle_density_per_m2 >= 0 &&
                    options.material_target == MaterialTarget::wrinkle_synthesis) {
                    // Analysis by synthesis: the bending scale whose render shows the photo's P.
                    ts = Clock::now();
                    g.target_curvature_per_m =
                        garment::curvature_from_wrinkle_density(g.type, g.wrinkle_density_per_m2).k_per_m;
                    const int gi = static_cast<int>(i);
                    const SynthesisSearch ss = search_bending_by_synthesis(g.wrinkle_density_per_m2, [&](double x) {
                        cloth::Material m = g.material;
                        m.bending_scale = std::pow(10.0, x);
                        const DrapedCandidate c = draper.drape(gi, g.sizing, m, 0);
                        ++evaluations;
                        report(Stage::material, gi, round, 0);
                        return rendered_wrinkle_density(view.candidate_scene(c), view, in.joints,
                                                        options.synthesis_samples, options.threads);
                    });
                    const double before = g.material_history.empty() ? std::numeric_limits<double>::infinity()
                                                                     : g.material_history.back();
                    g.material_history.push_back(std::min(before, ss.objective));
                    if (ss.objective < before) {
                        g.material.bending_scale = std::pow(10.0, ss.log10_bending_scale);
                        draper.set_material(gi, g.material);
                        g.bending_low = std::pow(10.0, ss.low);
                        g.bending_high = std::pow(10.0, ss.high);
                        improved = true;
                    }
                    g.seconds_material += since(ts);
                    summary.seconds_material += since(ts);
                } else if (options.estimate_material && g.wrinkle_density_per_m2 >= 0) {
                    ts = Clock::now();
                    // The calibrated mapping of P (docs/material-estimation.md).
                    const garment::CurvatureTarget target =
                        garment::curvature_from_wrinkle_density(g.type, g.wrinkle_density_per_m2);
                    g.target_curvature_per_m = target.k_per_m;
                    garment::MaterialSearchOptions mo;
                    mo.start_log10_bending = std::clamp(std::log10(g.material.bending_scale), mo.min_log10_bending,
                                                        mo.max_log10_bending);
                    if (round == 1) mo.start_log10_bending = target.log10_bending_scale;
                    mo.max_iterations = options.quality == Quality::fast ? 4 : 8;
                    mo.max_evaluations = options.quality == Quality::fast ? 8 : 12;
                    const auto ms = garment::search_bending(
                        target.k_per_m,
                        [&](double x) {
                            cloth::Material m = g.material;
                            m.bending_scale = std::pow(10.0, x);
                            const DrapedCandidate c = draper.drape(static_cast<int>(i), g.sizing, m, 0);
                            ++evaluations;
                            report(Stage::material, static_cast<int>(i), round, 0);
                            return mean_curvature(c.mesh, c.positions);
                        },
                        mo);
                    const double before = g.material_history.empty() ? std::numeric_limits<double>::infinity()
                                                                     : g.material_history.back();
                    const double r = (ms.mean_curvature_per_m - target.k_per_m) / target.k_per_m;
                    g.material_history.push_back(r * r);
                    if (r * r < before) {
                        g.material.bending_scale = ms.bending_scale();
                        draper.set_material(static_cast<int>(i), g.material);
                        improved = true;
                    }
                    // The confidence range: the calibration's K interval through the local slope.
                    const double h = 0.15;
                    const double x = ms.log10_bending_scale;
                    const double xl = std::max(0.0, x - h), xh = std::min(2.0, x + h);
                    auto k_at = [&](double xx) {
                        cloth::Material m = g.material;
                        m.bending_scale = std::pow(10.0, xx);
                        const DrapedCandidate c = draper.drape(static_cast<int>(i), g.sizing, m, 0);
                        ++evaluations;
                        return mean_curvature(c.mesh, c.positions);
                    };
                    const double slope = (k_at(xh) - k_at(xl)) / (xh - xl);  // dK / dlog10 s_b (< 0 usually)
                    double lo = 0, hi = 2;
                    if (std::abs(slope) > 1e-9) {
                        const double a = x + (target.k_high_per_m - ms.mean_curvature_per_m) / slope;
                        const double b = x + (target.k_low_per_m - ms.mean_curvature_per_m) / slope;
                        lo = std::clamp(std::min(a, b), 0.0, 2.0);
                        hi = std::clamp(std::max(a, b), 0.0, 2.0);
                    }
                    g.bending_low = std::pow(10.0, std::min(lo, x));
                    g.bending_high = std::pow(10.0, std::max(hi, x));
                    g.seconds_material += since(ts);
                    summary.seconds_material += since(ts);
                }
                // Sizing: PSO on the silhouette distance.
                ts = Clock::now();
                garment::SizingSearchOptions so;
                so.particles = options.particles;
                so.generations = options.generations;
                so.threads = options.threads;
                so.seed = options.seed + static_cast<unsigned>(101 * round + i);
                so.free = free_parameters(g.choice, g.initial_sizing);
                so.lower_bounds = lower_bounds(g.initial_sizing, options.min_ease_cm);
                so.constrain = garment::tie_dress_waist;
                so.box_fraction = round == 1 ? 0.15 : 0.07;
                so.on_progress = [&](const garment::SizingSearchProgress& p) {
                    const double per_gen = p.generation > 0 ? p.seconds / p.generation : -1;
                    report(Stage::sizing, static_cast<int>(i), round, p.best,
                           per_gen > 0 ? per_gen * (p.generations - p.generation) : -1);
                    return true;
                };
                const int gi = static_cast<int>(i);
                const auto ss = garment::search_sizing(
                    g.sizing,
                    [&](const garment::GarmentSizing& candidate, int worker) {
                        const DrapedCandidate c = draper.drape(gi, candidate, g.material, worker);
                        ++evaluations;
                        const double e = scorers[i].score(view.candidate(c)).energy_px2;
                        // A re-drape that did not settle cleanly (slid, caught) is worse than its outline.
                        return c.usable ? e : 2.0 * e;
                    },
                    so);
                if (ss.termination == garment::SizingSearchTermination::cancelled) throw Cancelled{};
                const double before = g.sizing_history.empty() ? ss.start_objective : g.sizing_history.back();
                g.sizing_history.push_back(std::min(before, ss.best_objective));
                if (ss.best_objective < before) {
                    g.sizing = ss.best;
                    draper.set_sizing(gi, g.sizing);
                    if (before - ss.best_objective > 0.01 * before) improved = true;
                }
                g.seconds_sizing += since(ts);
                summary.seconds_sizing += since(ts);
            }
            if (!improved) break;
        }

        // ---- 6. The joint material-pose search (paper Algorithm 2), garment by garment: each
        // moves only the joints under it, so the pose gathers every garment's refinement.
        if (options.joint_pose_material && options.estimate_material) {
            for (size_t i = 0; i < out.garments.size(); ++i) {
                RecoveredGarment& g = out.garments[i];
                if (g.wrinkle_density_per_m2 < 0 || !(g.target_curvature_per_m > 0)) continue;
                ts = Clock::now();
                const int gi = static_cast<int>(i);
                report(Stage::pose_material, gi, 0, 0);
                const JointSearchResult js = joint_pose_material(
                    g.choice, draper.pose(), g.material.bending_scale, g.target_curvature_per_m,
                    [&](double bending, const body::Pose& pose, int worker) {
                        cloth::Material m = g.material;
                        m.bending_scale = bending;
                        const Eigen::MatrixX3d body = draper.posed_body(pose);
                        const DrapedCandidate c = draper.drape(gi, g.sizing, m, worker, &body);
                        ++evaluations;
                        return mean_curvature(c.mesh, c.positions);
                    },
                    options,
                    [&] {
                        report(Stage::pose_material, gi, 0, 0);
                        return true;
                    });
                g.joint_history = js.history;
                if (js.improved) {
                    draper.set_pose(js.pose);
                    g.material.bending_scale = js.bending_scale;
                    draper.set_material(gi, g.material);
                }
                g.seconds_material += since(ts);
                summary.seconds_material += since(ts);
            }
        }

        // ---- 7. The output drape at the output resolution, and its measures.
        report(Stage::final_drape, -1, 0, 0);
        ts = Clock::now();
        std::vector<garment::GarmentRequest> final_requests;
        for (const auto& g : out.garments) {
            garment::GarmentRequest r;
            r.type = g.type;
            r.sizing = g.sizing;
            r.material = g.material;
            final_requests.push_back(r);
        }
        garment::DressedOutfit final_outfit;
        const bool fresh = options.output_drape != OutputDrape::search;
        garment::DressOutfitSummary fs;
        if (fresh) {
            fs = draper.final_drape(final_requests, final_outfit);
            if (fs.termination == garment::DressOutfitTermination::meshing_failed)
                return finish(RecoverTermination::drape_failed, fs.message);
            if (fs.termination == garment::DressOutfitTermination::cancelled) throw Cancelled{};
            out.pose = final_outfit.pose;
            out.body_vertices = final_outfit.body_vertices;
        } else {
            out.pose = draper.photo_pose();
            out.body_vertices = draper.photo_body();
        }
        report(Stage::measuring, -1, 0, 0);
        for (size_t i = 0; i < out.garments.size(); ++i) {
            RecoveredGarment& g = out.garments[i];
            if (fresh) {
                g.pattern = final_outfit.patterns[i];
                g.mesh = final_outfit.meshes[i];
                g.positions = final_outfit.positions[i];
                const garment::GarmentStateCheck& c = final_outfit.checks[i];
                g.drape = DrapeState{fs.usable() && c.max_penetration_m <= fs.drape.penetration_tolerance_m &&
                                         c.max_seam_gap_m < fs.drape.seam_gap_tolerance_m && c.self_intersections == 0,
                                     fs.drape.converged,
                                     c.max_penetration_m,
                                     c.max_seam_gap_m,
                                     c.self_intersections,
                                     DrapeState::Source::output,
                                     options.final_edge_cm,
                                     outfit_drape_message(fs.drape)};
            } else {
                g.pattern = garment::make_pattern(g.sizing);
            }
            // The output drape dresses afresh and can fail (crumpled, caught, exploded) where
            // the search's re-drapes of the same garment settled: `automatic` keeps the
            // search's re-drape of the recovered sizing and material then, at its resolution.
            const bool automatic = options.output_drape == OutputDrape::automatic && !g.drape.usable;
            if (!fresh || automatic) {
                try {
                    const DrapedCandidate c = draper.drape(static_cast<int>(i), g.sizing, g.material, 0);
                    if (!fresh || c.usable) {
                        g.mesh = c.mesh;
                        g.positions = c.positions;
                        g.drape = DrapeState{c.usable,           c.converged,
                                             c.penetration_max_m, c.seam_gap_max_m,
                                             c.self_intersections, DrapeState::Source::search,
                                             options.search_edge_cm,  std::string{}};
                    }
                } catch (const InvalidInput& e) {
                    // The search mesh refuses the recovered sizing (it was evaluated there, so
                    // rarely): `automatic` keeps the output drape; `search` has none.
                    if (!fresh)
                        return finish(RecoverTermination::drape_failed,
                                      "the search's re-drape of garment " + std::to_string(i) + ": " + e.what());
                }
            }
            g.mean_curvature_per_m = mean_curvature(g.mesh, g.positions);
            g.nearest_fabric = nearest_fabric(g.material);
            if (g.bending_low <= 0) g.bending_low = g.bending_high = g.material.bending_scale;
        }
        summary.seconds_final = since(ts);
        OutfitView final_view(model, out.body_vertices, out.fit.camera, in.image_bgr.cols, in.image_bgr.rows);
        std::vector<const garment::GarmentMesh*> meshes;
        std::vector<const Eigen::MatrixX3d*> positions;
        std::vector<int> labels;
        for (const auto& g : out.garments) {
            meshes.push_back(&g.mesh);
            positions.push_back(&g.positions);
            labels.push_back(g.label_id);
        }
        const OutfitRaster raster = final_view.project(meshes, positions, labels, skin);
        out.mask = raster.labels;
        for (size_t i = 0; i < out.garments.size(); ++i)
            out.garments[i].silhouette_rms_px = std::sqrt(scorers[i].score(raster.silhouettes[i]).energy_px2);
    } catch (const Cancelled&) {
        return finish(RecoverTermination::cancelled, "cancelled at stage '" + stage_name(progress.stage) + "'");
    }
    return finish(RecoverTermination::recovered, "");
}

}  // namespace drape::recover

// Names and options of the recovery: garment choices, quality presets, stages.
#include <drape/recover/recover.hpp>

#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>

#include <array>
#include <cmath>
#include <sstream>

namespace drape::recover {

namespace {

constexpr std::array<const char*, 7> kChoiceNames = {"skirt", "pants", "shorts", "tshirt", "tank", "longsleeve", "dress"};

}  // namespace

GarmentChoice garment_choice_from_name(const std::string& name) {
    for (size_t i = 0; i < kChoiceNames.size(); ++i)
        if (name == kChoiceNames[i]) return static_cast<GarmentChoice>(i);
    std::string all;
    for (const char* n : kChoiceNames) all += std::string(all.empty() ? "" : ", ") + n;
    throw InvalidInput("unknown garment '" + name + "' (expected one of " + all + ")");
}

std::string garment_choice_name(GarmentChoice c) { return kChoiceNames[static_cast<size_t>(c)]; }

garment::GarmentType template_of(GarmentChoice c) {
    switch (c) {
        case GarmentChoice::skirt: return garment::GarmentType::skirt;
        case GarmentChoice::pants:
        case GarmentChoice::shorts: return garment::GarmentType::pants;
        case GarmentChoice::tshirt:
        case GarmentChoice::tank:
        case GarmentChoice::longsleeve: return garment::GarmentType::tshirt;
        case GarmentChoice::dress: return garment::GarmentType::dress;
    }
    return garment::GarmentType::tshirt;
}

Quality quality_from_name(const std::string& name) {
    if (name == "fast") return Quality::fast;
    if (name == "default" || name == "normal") return Quality::normal;
    if (name == "fine") return Quality::fine;
    throw InvalidInput("unknown quality '" + name + "' (expected fast, default or fine)");
}

OutputDrape output_drape_from_name(const std::string& name) {
    if (name == "auto") return OutputDrape::automatic;
    if (name == "output") return OutputDrape::output;
    if (name == "search") return OutputDrape::search;
    throw InvalidInput("unknown output drape '" + name + "' (expected auto, output or search)");
}

std::string output_drape_name(OutputDrape d) {
    switch (d) {
        case OutputDrape::automatic: return "auto";
        case OutputDrape::output: return "output";
        case OutputDrape::search: return "search";
    }
    return "auto";
}

std::string quality_name(Quality q) {
    switch (q) {
        case Quality::fast: return "fast";
        case Quality::normal: return "default";
        case Quality::fine: return "fine";
    }
    return "default";
}

MaterialTarget material_target_from_name(const std::string& name) {
    if (name == "calibrated") return MaterialTarget::calibrated_curvature;
    if (name == "synthesis") return MaterialTarget::wrinkle_synthesis;
    throw InvalidInput("material target '" + name + "' is not one of calibrated, synthesis");
}

std::string material_target_name(MaterialTarget t) {
    return t == MaterialTarget::wrinkle_synthesis ? "synthesis" : "calibrated";
}

std::string stage_name(Stage s) {
    switch (s) {
        case Stage::segmenting: return "segmenting";
        case Stage::fitting_body: return "fitting the body";
        case Stage::dressing: return "dressing";
        case Stage::sizing: return "sizing";
        case Stage::material: return "material";
        case Stage::pose_material: return "pose and material";
        case Stage::final_drape: return "final drape";
        case Stage::measuring: return "measuring";
    }
    return "";
}

void apply_quality(RecoverOptions& o) {
    switch (o.quality) {
        case Quality::fast:
            o.search_edge_cm = 8.0;
            o.final_edge_cm = 5.0;
            o.particles = 16;
            o.generations = 3;
            o.rounds = 1;
            o.max_drape_steps = 300;
            break;
        case Quality::normal:
            o.search_edge_cm = 6.0;
            o.final_edge_cm = 4.0;
            o.particles = 40;
            o.generations = 5;
            o.rounds = 2;
            o.max_drape_steps = 400;
            break;
        case Quality::fine:
            o.search_edge_cm = 5.0;
            o.final_edge_cm = 2.5;
            o.particles = 40;
            o.generations = 10;
            o.rounds = 4;
            o.max_drape_steps = 600;
            break;
    }
}

bool RecoverOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (threads < 1) return fail("threads must be >= 1 (got " + std::to_string(threads) + ")");
    if (!(search_edge_cm > 0.2 && search_edge_cm <= 20))
        return fail("search_edge_cm must be in (0.2, 20] (got " + std::to_string(search_edge_cm) + ")");
    if (!(final_edge_cm > 0.2 && final_edge_cm <= 20))
        return fail("final_edge_cm must be in (0.2, 20] (got " + std::to_string(final_edge_cm) + ")");
    if (particles < 2) return fail("particles must be >= 2 (got " + std::to_string(particles) + ")");
    if (synthesis_samples < 1 || synthesis_samples > 64)
        return fail("synthesis_samples must be in 1..64 (got " + std::to_string(synthesis_samples) + ")");
    if (pose_particles < 2) return fail("pose_particles must be >= 2 (got " + std::to_string(pose_particles) + ")");
    if (pose_generations < 0)
        return fail("pose_generations must be >= 0 (got " + std::to_string(pose_generations) + ")");
    if (!(pose_max_degrees > 0 && pose_max_degrees <= 30))
        return fail("pose_max_degrees must be in (0, 30] (got " + std::to_string(pose_max_degrees) + ")");
    if (!(pose_prior_weight >= 0) || !std::isfinite(pose_prior_weight))
        return fail("pose_prior_weight must be >= 0 (got " + std::to_string(pose_prior_weight) + ")");
    if (generations < 0) return fail("generations must be >= 0 (got " + std::to_string(generations) + ")");
    if (rounds < 1) return fail("rounds must be >= 1 (got " + std::to_string(rounds) + ")");
    if (max_drape_steps < 20) return fail("max_drape_steps must be >= 20 (got " + std::to_string(max_drape_steps) + ")");
    if (!(max_arm_elevation_degrees >= 0 && max_arm_elevation_degrees <= 180))
        return fail("max_arm_elevation_degrees must be in [0, 180] (got " + std::to_string(max_arm_elevation_degrees) +
                    ")");
    if (!(min_ease_cm >= -10 && min_ease_cm <= 10))
        return fail("min_ease_cm must be in [-10, 10] (got " + std::to_string(min_ease_cm) + ")");
    try {
        cloth::builtin_material_info(base_fabric);  // its error names the fabrics there are
    } catch (const InvalidInput& e) {
        return fail("base_fabric '" + base_fabric + "' is not a measured fabric: " + e.what());
    }
    return true;
}

bool RecoverSummary::usable(const RecoveryResult& result) const {
    if (termination != RecoverTermination::recovered || result.garments.empty()) return false;
    for (const auto& g : result.garments)
        if (!g.drape.usable) return false;
    return true;
}

std::string RecoverSummary::brief_report() const {
    static const char* names[] = {"recovered", "no_garment", "body_fit_failed", "drape_failed", "cancelled"};
    std::ostringstream s;
    s << "recover: " << names[static_cast<int>(termination)] << " in " << seconds << " s (segment " << seconds_segment
      << ", body " << seconds_fit << ", dress " << seconds_dress << ", sizing " << seconds_sizing << ", material "
      << seconds_material << ", final " << seconds_final << "), " << evaluations << " candidate drapes";
    if (!message.empty()) s << "; " << message;
    return s.str();
}

}  // namespace drape::recover

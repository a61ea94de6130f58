#include <drape/io/animation_files.hpp>

#include <drape/io/json_io.hpp>
#include <drape/io/recovery_files.hpp>

#include <drape/body/model_io.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/garment_export.hpp>

#include "staging.hpp"

#include <cstdio>

namespace drape::io {

namespace fs = std::filesystem;

bool write_animation(const fs::path& out, const body::BodyModel& model, const body::ShapedBody& shaped,
                     const garment::DressedOutfit& outfit, const garment::AnimatedOutfit& animation,
                     const std::vector<std::string>& names, const nlohmann::json& report,
                     const std::function<bool()>& keep_going) {
    const std::size_t n = outfit.meshes.size();
    require(names.size() == n, "write_animation: ", names.size(), " names for ", n, " garments");
    require(!animation.frames.empty(), "write_animation: the animation has no frame");
    require(animation.frames.size() <= animation.motion.frames.size(), "write_animation: ", animation.frames.size(),
            " garment frames for ", animation.motion.frames.size(), " body frames");
    for (std::size_t k = 0; k < animation.frames.size(); ++k)
        require(animation.frames[k].size() == n, "write_animation: frame ", k, " has ", animation.frames[k].size(),
                " garments, the outfit ", n);
    // The body's motion cut to the frames simulated (a cancelled or failed run has fewer).
    body::Motion motion = animation.motion;
    motion.frames.resize(animation.frames.size());
    detail::Staging staging(out);
    std::vector<body::FrameMesh> meshes(n);
    static const Eigen::Vector3d palette[] = {{0.55, 0.08, 0.10}, {0.08, 0.20, 0.55}, {0.10, 0.40, 0.15},
                                              {0.60, 0.45, 0.05}};
    for (std::size_t g = 0; g < n; ++g) {
        body::FrameMesh& m = meshes[g];
        m.name = names[g];
        m.F = outfit.meshes[g].cloth.faces;
        m.UV = outfit.meshes[g].uv;
        m.colour_linear = palette[g % 4];
        for (const auto& frame : animation.frames) m.frames.push_back(frame[g]);
    }
    body::export_animated_glb(staging / "animation.glb", model, shaped, motion, meshes);
    fs::create_directories(staging / "frames");
    char name[64];
    for (std::size_t k = 0; k < animation.frames.size(); ++k)
        for (std::size_t g = 0; g < n; ++g) {
            std::snprintf(name, sizeof(name), "garment_%zu_%04zu.obj", g, k);
            garment::write_garment_obj(staging / "frames" / name, outfit.patterns[g], outfit.meshes[g],
                                       animation.frames[k][g],
                                       "drape animate: " + names[g] + ", frame " + std::to_string(k) + " at " +
                                           std::to_string(double(k) / motion.fps) + " s");
        }
    write_json_file(staging / "animation.json", report);
    if (keep_going && !keep_going()) return false;
    staging.commit();
    return true;
}

nlohmann::json animation_json(const garment::AnimateSummary& s) {
    nlohmann::json frames = nlohmann::json::array();
    for (const garment::AnimationFrameCheck& c : s.checks)
        frames.push_back({{"time_s", c.time_s},
                          {"max_penetration_m", c.max_penetration_m},
                          {"vertices_inside", c.vertices_inside},
                          {"deepest_joint", c.deepest_joint},
                          {"self_intersections", c.self_intersections},
                          {"max_speed_m_per_s", c.max_speed_m_per_s},
                          {"max_slip_m", c.max_slip_m},
                          {"newton_iterations", c.newton_iterations},
                          {"seconds", c.seconds},
                          {"cpu_seconds", c.cpu_seconds}});
    return {{"usable", s.usable()},
            {"message", s.message},
            {"brief_report", s.brief_report()},
            {"frames", s.frames},
            {"vertices", s.vertices},
            {"substeps", s.checks.size() > 1 ? s.checks[1].substeps : 0},
            {"max_penetration_m", s.max_penetration_m},
            {"max_self_intersections", s.max_self_intersections},
            {"max_speed_m_per_s", s.max_speed_m_per_s},
            {"max_slip_m", s.max_slip_m},
            {"seconds_blend", s.seconds_blend},
            {"seconds_per_frame", s.seconds_per_frame},
            {"cpu_seconds_per_frame", s.cpu_seconds_per_frame},
            {"seconds", s.seconds},
            {"per_frame", frames}};
}

recover::AnimateGarmentsInputs read_animation_inputs(const std::vector<std::string>& specs, const std::string& motion) {
    if (specs.empty()) throw InvalidInput("no garment given: name a result folder (DIR or DIR:N)");
    recover::AnimateGarmentsInputs in;
    in.motion = motion;
    for (const std::string& spec : specs) {
        const SavedRecovery saved = read_recovery_folder(spec);
        if (&spec == &specs.front()) in.body = saved.body, in.pose = saved.pose;
        for (const SavedGarment& g : saved.garments) {
            if (!g.supported)
                throw InvalidInput(spec + ": garment " + std::to_string(g.index) + " ('" + g.garment +
                                   "') was not recovered (unsupported), it cannot be animated");
            in.garments.push_back({g.type, g.sizing, g.material});
        }
    }
    return in;
}

nlohmann::json animation_report(const recover::AnimateGarmentsSummary& summary,
                                const recover::AnimateGarmentsOptions& options, const std::string& motion,
                                const std::vector<std::string>& garments) {
    nlohmann::json report = animation_json(summary.animate);
    report["motion"] = motion;
    report["fps"] = options.fps;
    report["wind_m_per_s"] = {options.wind_m_per_s.x(), options.wind_m_per_s.y(), options.wind_m_per_s.z()};
    report["garments"] = garments;
    report["drape"] = summary.dress.brief_report();
    return report;
}

}  // namespace drape::io

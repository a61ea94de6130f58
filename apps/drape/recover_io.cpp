#include "recover_io.hpp"

#include "interrupt.hpp"

#include <drape/recover/recover.hpp>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace drape::app {

using namespace io;

recover::RecoverOptions recover_options(const RecoverFlags& f, const std::string& prefix) {
    install_interrupt_handlers();
    recover::RecoverOptions options;
    options.quality = recover::quality_from_name(f.quality);
    recover::apply_quality(options);
    options.threads = f.threads;
    options.seed = f.seed;
    if (f.particles) options.particles = *f.particles;
    if (f.generations) options.generations = *f.generations;
    if (f.rounds) options.rounds = *f.rounds;
    options.estimate_material = !f.no_material;
    options.joint_pose_material = f.joint_pose;
    if (f.max_arm_elevation) options.max_arm_elevation_degrees = *f.max_arm_elevation;
    if (f.min_ease) options.min_ease_cm = *f.min_ease;
    if (f.base_fabric) options.base_fabric = *f.base_fabric;
    options.material_target = recover::material_target_from_name(f.material_target);
    options.output_drape = recover::output_drape_from_name(f.output_drape);
    struct Printer {
        std::string last_stage;
        std::chrono::steady_clock::time_point last_print = std::chrono::steady_clock::now() - std::chrono::seconds(10);
    };
    auto state = std::make_shared<Printer>();
    options.on_progress = [state, prefix](const recover::RecoverProgress& p) {
        const std::string stage = recover::stage_name(p.stage);
        const auto now = std::chrono::steady_clock::now();
        if (stage != state->last_stage || now - state->last_print > std::chrono::seconds(2)) {
            std::ostringstream line;
            line << std::fixed << std::setprecision(1) << prefix << ": [" << p.seconds << " s] " << stage;
            if (p.garment >= 0) line << ", garment " << p.garment;
            if (p.round > 0) line << ", round " << p.round;
            line << ", " << p.evaluations << " drapes";
            if (p.stage == recover::Stage::sizing) line << ", best " << std::setprecision(2) << p.best_objective << " px²";
            if (p.eta_seconds >= 0) line << std::setprecision(0) << ", ETA " << p.eta_seconds << " s";
            std::cerr << line.str() << "\n";
            state->last_stage = stage;
            state->last_print = now;
        }
        return !interrupted();
    };
    return options;
}

}  // namespace drape::app

#include "joint_pose_material.hpp"

#include <drape/core/errors.hpp>
#include <drape/garment/material_search.hpp>
#include <drape/garment/particle_swarm.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace drape::recover {

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

std::vector<body::Joint> joints_under(GarmentChoice choice) {
    using J = body::Joint;
    switch (choice) {
        case GarmentChoice::skirt:
        case GarmentChoice::shorts: return {J::right_hip, J::left_hip};
        case GarmentChoice::pants: return {J::right_hip, J::left_hip, J::right_knee, J::left_knee};
        case GarmentChoice::tshirt:
        case GarmentChoice::tank: return {J::chest, J::right_shoulder, J::left_shoulder};
        case GarmentChoice::longsleeve: return {J::right_shoulder, J::left_shoulder, J::right_elbow, J::left_elbow};
        case GarmentChoice::dress: return {J::right_hip, J::left_hip, J::right_shoulder, J::left_shoulder};
    }
    return {};
}

body::Pose perturbed_pose(const body::Pose& pose, const std::vector<body::Joint>& joints,
                          const std::vector<double>& degrees) {
    require(degrees.size() == 3 * joints.size(), "perturbed_pose: ", degrees.size(), " angles for ", joints.size(),
            " joints (need 3 per joint)");
    body::Pose out = pose;
    for (size_t k = 0; k < joints.size(); ++k) {
        const int j = static_cast<int>(joints[k]);
        const Eigen::Vector3d a = pose.rotations.row(j).transpose();
        const double angle = a.norm();
        const Eigen::Matrix3d own =
            angle > 0 ? Eigen::AngleAxisd(angle, a / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
        const double r = kPi / 180.0;
        const Eigen::Matrix3d delta = (Eigen::AngleAxisd(degrees[3 * k] * r, Eigen::Vector3d::UnitX()) *
                                       Eigen::AngleAxisd(degrees[3 * k + 1] * r, Eigen::Vector3d::UnitY()) *
                                       Eigen::AngleAxisd(degrees[3 * k + 2] * r, Eigen::Vector3d::UnitZ()))
                                          .toRotationMatrix();
        const Eigen::AngleAxisd both(delta * own);
        out.rotations.row(j) = (both.angle() * both.axis()).transpose();
    }
    return out;
}

JointSearchResult joint_pose_material(GarmentChoice choice, const body::Pose& pose, double bending_scale,
                                      double k_target_per_m, const CurvatureOfPose& curvature,
                                      const RecoverOptions& options, const std::function<bool()>& keep_going) {
    require(k_target_per_m > 0 && std::isfinite(k_target_per_m), "joint_pose_material: the target curvature ",
            k_target_per_m, " must be > 0");
    const std::vector<body::Joint> joints = joints_under(choice);
    const size_t n = 3 * joints.size();
    JointSearchResult out;
    out.pose = pose;
    out.bending_scale = bending_scale;
    auto relative2 = [&](double k) {
        const double r = (k - k_target_per_m) / k_target_per_m;
        return r * r;
    };
    auto prior = [&](const std::vector<double>& x) {
        double s = 0;
        for (double v : x) s += (v / options.pose_max_degrees) * (v / options.pose_max_degrees);
        return n > 0 ? options.pose_prior_weight * s / static_cast<double>(n) : 0.0;
    };
    // The start: the pose as fitted, the material of the G/C rounds.
    const double k0 = curvature(bending_scale, pose, 0);
    ++out.evaluations;
    out.k_per_m = k0;
    const double e0 = std::isfinite(k0) ? relative2(k0) : std::numeric_limits<double>::infinity();
    out.history.push_back(e0);

    // Pose step: the swarm over the angles, C fixed.
    garment::SwarmOptions so;
    so.particles = options.pose_particles;
    so.generations = options.pose_generations;
    so.threads = options.threads;
    so.seed = options.seed + 7919u;
    so.tolerance = 0;  // the budget is small: every generation runs
    so.on_progress = [&](const garment::SwarmProgress&) { return !keep_going || keep_going(); };
    const std::vector<double> lower(n, -options.pose_max_degrees), upper(n, options.pose_max_degrees);
    const garment::SwarmSummary sw = garment::minimise_swarm(
        std::vector<double>(n, 0.0), lower, upper,
        [&](const std::vector<double>& x, int worker) {
            const double k = curvature(bending_scale, perturbed_pose(pose, joints, x), worker);
            return std::isfinite(k) ? relative2(k) + prior(x) : std::numeric_limits<double>::infinity();
        },
        so);
    out.evaluations += sw.evaluations;
    const body::Pose best_pose = perturbed_pose(pose, joints, sw.best);
    const double e_pose = sw.best_objective;
    out.history.push_back(e_pose);
    if (sw.termination == garment::SwarmTermination::cancelled || sw.termination == garment::SwarmTermination::failed ||
        !(e_pose < e0))
        return out;

    // Material step: the bending scale by L-BFGS on the refined pose.
    garment::MaterialSearchOptions mo;
    mo.start_log10_bending = std::clamp(std::log10(bending_scale), mo.min_log10_bending, mo.max_log10_bending);
    mo.max_iterations = options.quality == Quality::fast ? 4 : 8;
    mo.max_evaluations = options.quality == Quality::fast ? 8 : 12;
    const double k_pose = curvature(bending_scale, best_pose, 0);
    ++out.evaluations;
    const double pose_prior = prior(sw.best);
    const garment::MaterialSearchSummary ms = garment::search_bending(
        k_target_per_m,
        [&](double x) {
            if (keep_going && !keep_going()) throw Cancelled{};
            return curvature(std::pow(10.0, x), best_pose, 0);
        },
        mo);
    out.evaluations += ms.evaluations;
    const double e_material = relative2(ms.mean_curvature_per_m) + pose_prior;
    out.history.push_back(std::min(e_pose, e_material));
    out.pose = best_pose;
    out.improved = true;
    out.bending_scale = e_material < e_pose ? ms.bending_scale() : bending_scale;
    out.k_per_m = e_material < e_pose ? ms.mean_curvature_per_m : k_pose;
    return out;
}

}  // namespace drape::recover

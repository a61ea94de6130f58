// drape_calibrate_image_joints: prints libbody/src/image_joint_offsets.cpp, the offsets of
// hand-marked image joints from the model's joints (body::ImageJointOffsets::hand_marked,
// docs/body-fitting.md "Image joints"), from the tuning part of a photo folder.
//
//     drape_calibrate_image_joints ../shared/data/photos-dev [ROUNDS] [POSTURE_WEIGHT] > libbody/src/image_joint_offsets.cpp
//
// Each round fits the body to every tuning photo (its hand labels give the person and
// skin masks) with the current offsets and a posture prior strong enough to keep the
// trunk and legs standing, then moves each left/right pair of offsets (mirrored in x; the
// neck's and head's stay on the midline) by the least-squares step that best explains the
// remaining joint residuals of all photos through the fitted bones' rotations and cameras.
// The fit does not use the embedded table, so a stale table does not matter.
#include "photo_folder.hpp"

#include <drape/body/fit_body.hpp>
#include <drape/io/body_fit_files.hpp>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace drape;

// kImageJoints order: the mirrored pairs (right, left) and the midline joints.
constexpr std::array<std::array<int, 2>, 6> kPairs = {{{0, 5}, {1, 4}, {2, 3}, {6, 11}, {7, 10}, {8, 9}}};
constexpr std::array<int, 2> kMidline = {12, 13};

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << "usage: drape_calibrate_image_joints PHOTO_FOLDER [ROUNDS=4] [POSTURE_WEIGHT=30]\n";
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    const int rounds = argc > 2 ? std::stoi(argv[2]) : 4;
    const double posture = argc > 3 ? std::stod(argv[3]) : 30.0;
    const std::vector<std::string> names = tools::photo_names(dir, true);
    const body::BodyModel& model = body::BodyModel::default_model();

    body::ImageJointOffsets offsets = body::ImageJointOffsets::none();
    for (int round = 0; round < rounds; ++round) {
        // Normal equations per group (6 pairs, 2 midline joints).
        std::array<Eigen::Matrix3d, 8> A;
        std::array<Eigen::Vector3d, 8> b;
        for (auto& m : A) m.setZero();
        for (auto& v : b) v.setZero();
        double error = 0, trunk = 0, leg = 0, knee = 0;
        int fitted = 0;
        for (const std::string& name : names) {
            io::BodyFitFiles files = io::read_body_fit_files(
                (dir / "images" / (name + ".jpg")).string(), (dir / "joints" / (name + ".json")).string(), "", "",
                (dir / "labels" / (name + ".png")).string());
            body::FitOptions options;
            options.posture_weight = posture;
            options.image_joints = offsets;
            body::BodyFit fit;
            const body::FitSummary summary = body::fit_body(model, files.inputs, options, fit);
            if (!summary.usable()) {
                std::cerr << name << ": " << summary.brief_report() << " (skipped)\n";
                continue;
            }
            const body::FitQuality q = body::fit_quality(model, files.inputs, fit, summary);
            error += q.mean_joint_error_percent;
            trunk += q.trunk_out_of_plane_deg;
            leg += q.leg_out_of_plane_deg;
            knee += q.knee_bend_deg;
            ++fitted;
            const body::PosedSkeleton skeleton =
                body::forward_kinematics(body::shape_from_coefficients(model, fit.coefficients).joints, fit.pose);
            const double s = fit.camera.model == body::CameraModel::weak_perspective
                                 ? fit.camera.scale_px_per_m
                                 : fit.camera.focal_px / fit.camera.distance_m;
            const auto add = [&](int group, int i, double mirror) {
                const int j = body::index(body::kImageJoints[static_cast<size_t>(i)]);
                const int p = std::max(0, body::kJointParents[static_cast<size_t>(j)]);
                Eigen::Matrix<double, 2, 3> J;
                const Eigen::Matrix3d R = skeleton.global[static_cast<size_t>(p)].linear();
                J.row(0) = s * R.row(0);
                J.row(1) = -s * R.row(1);
                J.col(0) *= mirror;
                const Eigen::Vector2d d = files.inputs.joints_px.row(i).transpose() - fit.joints_2d.row(i).transpose();
                A[static_cast<size_t>(group)] += J.transpose() * J;
                b[static_cast<size_t>(group)] += J.transpose() * d;
            };
            for (size_t g = 0; g < kPairs.size(); ++g) {
                add(static_cast<int>(g), kPairs[g][0], -1.0);
                add(static_cast<int>(g), kPairs[g][1], 1.0);
            }
            for (size_t m = 0; m < kMidline.size(); ++m) add(static_cast<int>(kPairs.size() + m), kMidline[m], 0.0);
        }
        if (fitted == 0) {
            std::cerr << "no photo could be fitted\n";
            return 1;
        }
        std::fprintf(stderr,
                     "round %d: %d photos, mean joint error %.2f %% of H, out of the image plane: trunk %.1f deg, "
                     "legs %.1f deg, knee bend %.1f deg\n",
                     round, fitted, error / fitted, trunk / fitted, leg / fitted, knee / fitted);
        for (size_t g = 0; g < A.size(); ++g) {
            // A small ridge keeps the depth component (seen only in turned or bent poses) tame.
            const double ridge = 1e-3 * A[g].trace() / 3.0 + 1e-9;
            // Only in the image plane of a standing body: a depth offset would only trade
            // against the bend of the bones towards the camera that the calibration removes.
            A[g].row(2).setZero();
            A[g].col(2).setZero();
            A[g](2, 2) = 1.0;
            b[g](2) = 0.0;
            if (g >= kPairs.size()) {
                A[g].row(0).setZero();
                A[g].col(0).setZero();
                A[g](0, 0) = 1.0;  // the midline joints stay on the midline
                b[g](0) = 0.0;
            }
            const Eigen::Vector3d step = (A[g] + ridge * Eigen::Matrix3d::Identity()).ldlt().solve(b[g]);
            const auto apply = [&](int i, double mirror) {
                Eigen::Vector3d o = offsets.offset_m.row(i).transpose();
                o += Eigen::Vector3d(mirror * step.x(), step.y(), step.z());
                offsets.offset_m.row(i) = o.transpose();
            };
            if (g < kPairs.size()) {
                apply(kPairs[g][0], -1.0);
                apply(kPairs[g][1], 1.0);
            } else {
                apply(kMidline[g - kPairs.size()], 0.0);
            }
        }
    }

    std::printf(
        "// ImageJointOffsets::hand_marked(): where hand-marked fashion photos put their 14 joints\n"
        "// relative to the model's joints. Printed by `drape_calibrate_image_joints` (tools/) from\n"
        "// the tuning part of ../shared/data/photos-dev, %zu photos, %d rounds, posture weight %g\n"
        "// (docs/body-fitting.md, \"Image joints\").\n"
        "#include <drape/body/fit_body.hpp>\n\nnamespace drape::body {\n\n"
        "ImageJointOffsets ImageJointOffsets::hand_marked() {\n    ImageJointOffsets o;\n"
        "    // kImageJoints order, metres, in the rest frame of the bone that ends at the joint.\n"
        "    o.offset_m <<\n",
        names.size(), rounds, posture);
    for (int i = 0; i < body::kImageJointCount; ++i)
        std::printf("        %.4f, %.4f, %.4f%s  // %s\n", offsets.offset_m(i, 0), offsets.offset_m(i, 1),
                    offsets.offset_m(i, 2), i + 1 < body::kImageJointCount ? "," : ";",
                    std::string(body::kImageJointNames[static_cast<size_t>(i)]).c_str());
    std::printf("    return o;\n}\n\n}  // namespace drape::body\n");
    return 0;
}

#include <drape/garment/arm_clearance.hpp>

#include <drape/cloth/intersections.hpp>
#include <drape/core/errors.hpp>

#include "dressing_internal.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <vector>

namespace drape::garment {

namespace {

constexpr double kPi = 3.14159265358979323846;
enum Region { kOther = 0, kTrunk = 1, kRightArm = 2, kLeftArm = 3 };

Region region_of_joint(int j) {
    using body::Joint;
    using body::index;
    if (j == index(Joint::pelvis) || j == index(Joint::spine) || j == index(Joint::chest)) return kTrunk;
    if (j == index(Joint::right_shoulder) || j == index(Joint::right_elbow) || j == index(Joint::right_wrist))
        return kRightArm;
    if (j == index(Joint::left_shoulder) || j == index(Joint::left_elbow) || j == index(Joint::left_wrist))
        return kLeftArm;
    return kOther;
}

}  // namespace

bool ArmClearanceOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& t) {
        if (why) *why = t;
        return false;
    };
    if (!(step_degrees > 0 && step_degrees <= 10))
        return fail("ArmClearanceOptions::step_degrees = " + std::to_string(step_degrees) + " must be in (0, 10]");
    if (!(max_degrees >= 0 && max_degrees <= 60))
        return fail("ArmClearanceOptions::max_degrees = " + std::to_string(max_degrees) + " must be in [0, 60]");
    return true;
}

std::string ArmClearanceSummary::brief_report() const {
    std::ostringstream os;
    os << (clear() ? "arms clear of the trunk" : "arms still cross the trunk") << ": " << crossings_before
       << " -> " << crossings_after << " crossing arm/trunk triangle pairs, right arm raised " << right_degrees
       << " deg, left " << left_degrees << " deg, " << trials << " trials";
    return os.str();
}

body::Pose raise_arms(const body::Pose& pose, double right_degrees, double left_degrees) {
    std::string why;
    require(pose.is_valid(&why), "raise_arms: pose: ", why);
    require(std::isfinite(right_degrees) && std::isfinite(left_degrees), "raise_arms: angles ", right_degrees, ", ",
            left_degrees, " must be finite");
    // Rotations about +Z lower the right arm and raise the left one (named_pose).
    body::Pose p = pose;
    const std::array<std::pair<body::Joint, double>, 2> turns = {
        std::make_pair(body::Joint::right_shoulder, -right_degrees), std::make_pair(body::Joint::left_shoulder, left_degrees)};
    for (const auto& [joint, deg] : turns) {
        const int j = body::index(joint);
        const Eigen::Vector3d a = p.rotations.row(j).transpose();
        const Eigen::AngleAxisd old(a.norm(), a.norm() > 0 ? Eigen::Vector3d(a.normalized()) : Eigen::Vector3d::UnitX());
        const Eigen::AngleAxisd turned(Eigen::AngleAxisd(deg * kPi / 180, Eigen::Vector3d::UnitZ()) * old);
        p.rotations.row(j) = (turned.angle() * turned.axis()).transpose();
    }
    return p;
}

body::Pose clear_arms_from_trunk(const body::BodyModel& model, const body::ShapedBody& shaped,
                                 const body::Pose& pose, const ArmClearanceOptions& options,
                                 ArmClearanceSummary* summary) {
    std::string why;
    require(options.is_valid(&why), "clear_arms_from_trunk: ", why);
    require(pose.is_valid(&why), "clear_arms_from_trunk: pose: ", why);
    require(shaped.vertices.rows() == model.vertex_count() && shaped.vertices.cols() == 3,
            "clear_arms_from_trunk: the shaped body has ", shaped.vertices.rows(), " vertices, the model ",
            model.vertex_count());
    // Region of each face: that of its vertices' dominant joints when all three agree.
    std::vector<int> vertex_region;
    for (const int joint : body::dominant_joints(model)) vertex_region.push_back(joint >= 0 ? region_of_joint(joint) : kOther);
    std::vector<int> face_region(size_t(model.faces.rows()), kOther);
    for (Eigen::Index f = 0; f < model.faces.rows(); ++f) {
        const int r = vertex_region[size_t(model.faces(f, 0))];
        if (r == vertex_region[size_t(model.faces(f, 1))] && r == vertex_region[size_t(model.faces(f, 2))])
            face_region[size_t(f)] = r;
    }
    // Crossings of each arm with the trunk in a pose.
    ArmClearanceSummary s;
    auto crossings = [&](const body::Pose& p) {
        ++s.trials;
        const Eigen::MatrixX3d X = body::pose_body(model, shaped, p).vertices;
        std::vector<std::pair<int, int>> pairs;
        cloth::count_self_intersections(X, model.faces, &pairs);
        std::array<int, 2> n{0, 0};  // right, left
        for (const auto& [a, b] : pairs) {
            const int ra = face_region[size_t(a)], rb = face_region[size_t(b)];
            for (int arm = 0; arm < 2; ++arm) {
                const int r = arm == 0 ? kRightArm : kLeftArm;
                if ((ra == r && rb == kTrunk) || (rb == r && ra == kTrunk)) ++n[size_t(arm)];
            }
        }
        return n;
    };
    auto raised = [&](double right_deg, double left_deg) { return raise_arms(pose, right_deg, left_deg); };
    std::array<int, 2> n = crossings(pose);
    s.crossings_before = n[0] + n[1];
    std::array<double, 2> raise{0, 0};  // right, left
    for (;;) {
        bool raised_one = false;
        for (size_t arm = 0; arm < 2; ++arm)
            if (n[arm] > 0 && raise[arm] + options.step_degrees <= options.max_degrees + 1e-9) {
                raise[arm] += options.step_degrees;
                raised_one = true;
            }
        if (!raised_one) break;
        n = crossings(raised(raise[0], raise[1]));
    }
    s.crossings_after = n[0] + n[1];
    s.right_degrees = raise[0];
    s.left_degrees = raise[1];
    if (summary) *summary = s;
    return raised(raise[0], raise[1]);
}

body::Pose lower_raised_arms(const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                             double max_elevation_degrees, ArmLoweringSummary* summary) {
    std::string why;
    require(pose.is_valid(&why), "lower_raised_arms: pose: ", why);
    require(std::isfinite(max_elevation_degrees) && max_elevation_degrees >= 0 && max_elevation_degrees <= 180,
            "lower_raised_arms: max_elevation_degrees = ", max_elevation_degrees, " must be in [0, 180]");
    require(shaped.vertices.rows() == model.vertex_count() && shaped.joints.rows() == body::kJointCount,
            "lower_raised_arms: the shaped body does not fit the model");
    ArmLoweringSummary s;
    body::Pose p = pose;
    using body::Joint;
    using body::index;
    const std::array<std::pair<Joint, Joint>, 2> arms = {std::make_pair(Joint::right_shoulder, Joint::right_elbow),
                                                         std::make_pair(Joint::left_shoulder, Joint::left_elbow)};
    for (size_t a = 0; a < arms.size(); ++a) {
        const body::PosedSkeleton k = body::forward_kinematics(shaped.joints, p);
        const Eigen::Vector3d down =
            (k.joints.row(index(Joint::pelvis)) - k.joints.row(index(Joint::neck))).transpose().normalized();
        const int sj = index(arms[a].first), ej = index(arms[a].second);
        const Eigen::Vector3d u = (k.joints.row(ej) - k.joints.row(sj)).transpose().normalized();
        const double elevation = std::acos(std::clamp(u.dot(down), -1.0, 1.0)) * 180 / kPi;
        double lowered = 0;
        const Eigen::Vector3d axis = u.cross(down);
        if (elevation > max_elevation_degrees && axis.norm() > 1e-9) {
            lowered = elevation - max_elevation_degrees;
            const Eigen::Matrix3d G = k.global[size_t(body::kJointParents[size_t(sj)])].linear();
            const Eigen::Matrix3d Q = Eigen::AngleAxisd(lowered * kPi / 180, axis.normalized()).toRotationMatrix();
            p.rotations.row(sj) = body::rotated_in_world(p.rotations.row(sj).transpose(), G, Q).transpose();
        }
        (a == 0 ? s.right_elevation_degrees : s.left_elevation_degrees) = elevation;
        (a == 0 ? s.right_lowered_degrees : s.left_lowered_degrees) = lowered;
    }
    if (summary) *summary = s;
    return p;
}

}  // namespace drape::garment

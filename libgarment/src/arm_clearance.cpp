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

// The body's trunk and arm faces (a face belongs to a region when its three vertices'
// dominant joints all do), and the crossings of an arm with the trunk in a pose: the one
// count both clearance paths use.
struct ArmTrunkFaces {
    Eigen::MatrixX3i trunk;
    std::array<Eigen::MatrixX3i, 2> arms;  // right, left

    explicit ArmTrunkFaces(const body::BodyModel& model) {
        std::vector<int> vertex_region;
        for (const int joint : body::dominant_joints(model))
            vertex_region.push_back(joint >= 0 ? region_of_joint(joint) : kOther);
        std::array<std::vector<int>, 4> rows;
        for (Eigen::Index f = 0; f < model.faces.rows(); ++f) {
            const int r = vertex_region[size_t(model.faces(f, 0))];
            if (r == vertex_region[size_t(model.faces(f, 1))] && r == vertex_region[size_t(model.faces(f, 2))])
                rows[size_t(r)].push_back(int(f));
        }
        auto gather = [&](int region) {
            const std::vector<int>& r = rows[size_t(region)];
            Eigen::MatrixX3i F(Eigen::Index(r.size()), 3);
            for (size_t i = 0; i < r.size(); ++i) F.row(Eigen::Index(i)) = model.faces.row(r[i]);
            return F;
        };
        trunk = gather(kTrunk);
        arms = {gather(kRightArm), gather(kLeftArm)};
    }
    // Intersecting (arm face, trunk face) pairs of arm 0 (right) or 1 (left) at positions X.
    int crossings(const Eigen::MatrixX3d& X, size_t arm) const {
        return cloth::count_intersections(X, arms[arm], X, trunk);
    }
};

// The pose with one arm turned at the shoulder by `Q` (a world rotation about the shoulder).
body::Pose turned_arm(const body::Pose& pose, int shoulder, const Eigen::Matrix3d& parent_world,
                      const Eigen::Matrix3d& Q) {
    body::Pose p = pose;
    p.rotations.row(shoulder) = body::rotated_in_world(pose.rotations.row(shoulder).transpose(), parent_world, Q).transpose();
    return p;
}

// clear_arms_from_trunk with a view direction: per arm, the turns on the grid (outward turn
// in the image plane a, swing in depth f) are tried in order of the image displacement of
// the elbow and wrist they cause; the first that leaves the arm clear of the trunk is kept.
body::Pose clear_arms_in_view(const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                              const ArmClearanceOptions& options, const ArmTrunkFaces& faces,
                              ArmClearanceSummary& s) {
    using body::Joint;
    using body::index;
    const Eigen::Vector3d v = options.view_direction.normalized();
    auto crossings = [&](const body::Pose& p, size_t arm) {
        ++s.trials;
        return faces.crossings(body::pose_body(model, shaped, p).vertices, arm);
    };
    auto in_image = [&](const Eigen::Vector3d& d) -> Eigen::Vector3d { return d - d.dot(v) * v; };
    const body::PosedSkeleton k = body::forward_kinematics(shaped.joints, pose);
    const std::array<std::array<Joint, 3>, 2> chains = {
        std::array<Joint, 3>{Joint::right_shoulder, Joint::right_elbow, Joint::right_wrist},
        std::array<Joint, 3>{Joint::left_shoulder, Joint::left_elbow, Joint::left_wrist}};
    body::Pose out = pose;
    for (size_t arm = 0; arm < 2; ++arm) {
        const int sj = index(chains[arm][0]);
        const Eigen::Vector3d S = k.joints.row(sj).transpose();
        const Eigen::Vector3d E = k.joints.row(index(chains[arm][1])).transpose() - S;
        const Eigen::Vector3d W = k.joints.row(index(chains[arm][2])).transpose() - S;
        // Image displacement of elbow and wrist under a turn Q at the shoulder.
        auto image_shift = [&](const Eigen::Matrix3d& Q) { return in_image(Q * E - E).norm() + in_image(Q * W - W).norm(); };
        const Eigen::Matrix3d G = k.global[size_t(body::kJointParents[size_t(sj)])].linear();
        const int before = crossings(pose, arm);
        s.crossings_before += before;
        if (before == 0) continue;
        // Depth swing axis: across the upper arm and the view (the parent's x if the upper
        // arm points along the view). Outward: the image-plane turn that takes the elbow
        // away from the neck, on the shoulder's side.
        Eigen::Vector3d across = E.normalized().cross(v);
        if (across.norm() < 1e-3) across = G.col(0).cross(v);
        if (across.norm() < 1e-9) across = G.col(0);
        across.normalize();
        // + depth = towards the viewer (along v).
        if ((across.cross(E)).dot(v) < 0) across = -across;
        const Eigen::Vector3d side = in_image(S - k.joints.row(index(Joint::neck)).transpose());
        const double outward = (v.cross(E)).dot(side) >= 0 ? 1.0 : -1.0;
        struct Turn {
            double a, f, cost;
            Eigen::Matrix3d Q;
        };
        std::vector<Turn> turns;
        const double rad = kPi / 180;
        for (double a = 0; a <= options.max_degrees + 1e-9; a += options.step_degrees)
            for (double f = -options.max_depth_degrees; f <= options.max_depth_degrees + 1e-9; f += options.depth_step_degrees) {
                const double fr = std::abs(f) < 1e-9 ? 0.0 : f;
                const Eigen::Matrix3d Q = (Eigen::AngleAxisd(outward * a * rad, v) * Eigen::AngleAxisd(fr * rad, across)).toRotationMatrix();
                turns.push_back({a, fr, image_shift(Q), Q});
            }
        // Cheapest first; ties: the smaller turn, then towards the viewer.
        std::stable_sort(turns.begin(), turns.end(), [](const Turn& x, const Turn& y) {
            if (std::abs(x.cost - y.cost) > 1e-12) return x.cost < y.cost;
            if (x.a + std::abs(x.f) != y.a + std::abs(y.f)) return x.a + std::abs(x.f) < y.a + std::abs(y.f);
            return x.f > y.f;
        });
        const Turn* chosen = nullptr;
        int left = before, tried = 0;
        for (const Turn& t : turns) {
            if (t.a == 0 && t.f == 0) continue;
            if (tried++ >= options.max_trials) break;
            const int n = crossings(turned_arm(out, sj, G, t.Q), arm);
            if (n == 0) {
                chosen = &t;
                left = 0;
                break;
            }
        }
        if (!chosen) {
            // Not cleared within the trials: the plain outward turn as far as allowed.
            const Eigen::Matrix3d Q = Eigen::AngleAxisd(outward * options.max_degrees * rad, v).toRotationMatrix();
            out = turned_arm(out, sj, G, Q);
            left = crossings(out, arm);
            (arm == 0 ? s.right_degrees : s.left_degrees) = options.max_degrees;
            s.image_shift_m += image_shift(Q);
        } else {
            out = turned_arm(out, sj, G, chosen->Q);
            (arm == 0 ? s.right_degrees : s.left_degrees) = chosen->a;
            (arm == 0 ? s.right_depth_degrees : s.left_depth_degrees) = chosen->f;
            s.image_shift_m += chosen->cost;
        }
        s.crossings_after += left;
    }
    return out;
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
    if (!view_direction.allFinite())
        return fail("ArmClearanceOptions::view_direction must be finite");
    if (!(depth_step_degrees > 0 && depth_step_degrees <= 30))
        return fail("ArmClearanceOptions::depth_step_degrees = " + std::to_string(depth_step_degrees) +
                    " must be in (0, 30]");
    if (!(max_depth_degrees >= 0 && max_depth_degrees <= 90))
        return fail("ArmClearanceOptions::max_depth_degrees = " + std::to_string(max_depth_degrees) +
                    " must be in [0, 90]");
    if (max_trials < 1 || max_trials > 10000)
        return fail("ArmClearanceOptions::max_trials = " + std::to_string(max_trials) + " must be in [1, 10000]");
    return true;
}

std::string ArmClearanceSummary::brief_report() const {
    std::ostringstream os;
    os << (clear() ? "arms clear of the trunk" : "arms still cross the trunk") << ": " << crossings_before
       << " -> " << crossings_after << " crossing arm/trunk triangle pairs, right arm raised " << right_degrees
       << " deg, left " << left_degrees << " deg";
    if (right_depth_degrees != 0 || left_depth_degrees != 0 || image_shift_m != 0)
        os << ", swung in depth right " << right_depth_degrees << " deg, left " << left_depth_degrees
           << " deg, elbows and wrists moved " << image_shift_m * 100 << " cm in the image";
    os << ", " << trials << " trials";
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
    const ArmTrunkFaces faces(model);
    ArmClearanceSummary s;
    if (options.view_direction.norm() > 0) {
        body::Pose p = clear_arms_in_view(model, shaped, pose, options, faces, s);
        if (summary) *summary = s;
        return p;
    }
    // Crossings of each arm (right, left) with the trunk in a pose.
    auto crossings = [&](const body::Pose& p) {
        ++s.trials;
        const Eigen::MatrixX3d X = body::pose_body(model, shaped, p).vertices;
        return std::array<int, 2>{faces.crossings(X, 0), faces.crossings(X, 1)};
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

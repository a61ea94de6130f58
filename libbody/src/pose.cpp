#include <drape/body/pose.hpp>

#include <drape/core/errors.hpp>

#include <cmath>
#include <string>

namespace drape::body {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double deg(double d) { return d * kPi / 180.0; }

Eigen::Matrix3d rotation_of(const Eigen::Vector3d& axis_angle) {
    const double angle = axis_angle.norm();
    if (angle < 1e-12) return Eigen::Matrix3d::Identity();
    return Eigen::AngleAxisd(angle, axis_angle / angle).toRotationMatrix();
}

bool is_end_site(int j) {
    return j == index(Joint::head_top) || j == index(Joint::right_toe) ||
           j == index(Joint::left_toe);
}

}  // namespace

bool Pose::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!translation.allFinite()) return fail("pose translation is not finite");
    for (int j = 0; j < kJointCount; ++j) {
        const Eigen::Vector3d r = rotations.row(j).transpose();
        if (!r.allFinite())
            return fail("pose rotation of joint '" + std::string(kJointNames[j]) + "' is not finite");
        if (r.norm() > kPi + 1e-9)
            return fail("pose rotation of joint '" + std::string(kJointNames[j]) + "' has angle " +
                        std::to_string(r.norm()) + " rad > pi (use the equivalent shorter rotation)");
    }
    return true;
}

Pose interpolate_pose(const Pose& a, const Pose& b, double s) {
    std::string why;
    require(s >= 0 && s <= 1, "interpolate_pose: s = ", s, " must be in [0, 1]");
    require(a.is_valid(&why), "interpolate_pose: first pose: ", why);
    require(b.is_valid(&why), "interpolate_pose: second pose: ", why);
    const auto quaternion = [](const Eigen::Vector3d& r) {
        const double angle = r.norm();
        return angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, r / angle)) : Eigen::Quaterniond::Identity();
    };
    Pose out;
    out.translation = (1 - s) * a.translation + s * b.translation;
    for (int j = 0; j < kJointCount; ++j) {
        const Eigen::AngleAxisd q(quaternion(a.rotations.row(j).transpose())
                                      .slerp(s, quaternion(b.rotations.row(j).transpose())));
        // AngleAxis from a unit quaternion has angle in [0, pi] (slerp takes the short arc).
        out.rotations.row(j) = (q.angle() * q.axis()).transpose();
    }
    return out;
}

Pose named_pose(NamedPose which) {
    Pose p;
    // The rest pose holds the arms about 45 degrees below horizontal (mannequin.hpp);
    // rotations about +Z lower the right arm and raise the left one.
    // Leaves the arms ~12 degrees off the body: the hands hang ~4 cm clear of the thighs, room
    // for a garment between them (at 8 degrees a mean female's hand was 0.6 mm from her thigh).
    const double arm_to_side = deg(33.0);
    switch (which) {
        case NamedPose::a_pose:
            break;
        case NamedPose::arms_down:
            p.rotations.row(index(Joint::right_shoulder)) << 0, 0, arm_to_side;
            p.rotations.row(index(Joint::left_shoulder)) << 0, 0, -arm_to_side;
            break;
        case NamedPose::t_pose:
            p.rotations.row(index(Joint::right_shoulder)) << 0, 0, -deg(45.0);
            p.rotations.row(index(Joint::left_shoulder)) << 0, 0, deg(45.0);
            break;
        case NamedPose::walking:
            // Mid-stride: right leg forward, left leg trailing, arms swinging opposite.
            p.rotations.row(index(Joint::right_shoulder)) << deg(18.0), 0, arm_to_side;
            p.rotations.row(index(Joint::left_shoulder)) << -deg(20.0), 0, -arm_to_side;
            p.rotations.row(index(Joint::right_elbow)) << -deg(15.0), 0, 0;
            p.rotations.row(index(Joint::left_elbow)) << -deg(20.0), 0, 0;
            p.rotations.row(index(Joint::right_hip)) << -deg(25.0), 0, 0;
            p.rotations.row(index(Joint::right_knee)) << deg(12.0), 0, 0;
            p.rotations.row(index(Joint::right_ankle)) << deg(8.0), 0, 0;
            p.rotations.row(index(Joint::left_hip)) << deg(15.0), 0, 0;
            p.rotations.row(index(Joint::left_knee)) << deg(30.0), 0, 0;
            p.rotations.row(index(Joint::left_ankle)) << -deg(12.0), 0, 0;
            p.rotations.row(index(Joint::pelvis)) << 0, deg(6.0), 0;
            p.rotations.row(index(Joint::chest)) << 0, -deg(8.0), 0;
            break;
    }
    return p;
}

JointLimits JointLimits::standard(const Eigen::Matrix<double, kJointCount, 3>& rest_joints) {
    JointLimits L;
    const Eigen::Vector3d forward(0, 0, 1);
    // First child of each joint, for the bone direction.
    std::array<int, kJointCount> child;
    child.fill(-1);
    for (int j = kJointCount - 1; j >= 1; --j) child[kJointParents[j]] = j;
    child[index(Joint::chest)] = index(Joint::neck);
    child[index(Joint::pelvis)] = index(Joint::spine);
    for (int j = 0; j < kJointCount; ++j) {
        Eigen::Vector3d y(0, 1, 0);
        if (child[j] >= 0) {
            const Eigen::Vector3d d = (rest_joints.row(child[j]) - rest_joints.row(j)).transpose();
            if (d.norm() > 1e-9) y = d.normalized();
        }
        Eigen::Vector3d x = y.cross(forward);
        if (x.norm() < 0.3) x = Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitX().dot(y) * y;
        x.normalize();
        const bool knee = j == index(Joint::right_knee) || j == index(Joint::left_knee);
        if (knee) x = -x;
        Eigen::Matrix3d F;
        F.col(0) = x;
        F.col(1) = y;
        F.col(2) = x.cross(y);
        L.frames[j] = F;
    }
    auto set = [&](Joint j, double fl, double fu, double tl, double tu, double al, double au) {
        L.lower.row(index(j)) << fl, tl, al;
        L.upper.row(index(j)) << fu, tu, au;
    };
    // flexion (x), twist (y), ab/adduction (z); radians. Ranges after standard clinical
    // range-of-motion tables, widened slightly since the prior is soft.
    set(Joint::pelvis, -kPi, kPi, -kPi, kPi, -kPi, kPi);
    set(Joint::spine, -0.40, 0.70, -0.60, 0.60, -0.40, 0.40);
    set(Joint::chest, -0.30, 0.50, -0.50, 0.50, -0.30, 0.30);
    set(Joint::neck, -0.60, 0.80, -0.90, 0.90, -0.60, 0.60);
    set(Joint::head, -0.50, 0.50, -0.60, 0.60, -0.40, 0.40);
    set(Joint::head_top, 0, 0, 0, 0, 0, 0);
    for (Joint c : {Joint::right_clavicle, Joint::left_clavicle})
        set(c, -0.35, 0.35, -0.35, 0.35, -0.35, 0.35);
    for (Joint s : {Joint::right_shoulder, Joint::left_shoulder})
        set(s, -1.00, 3.00, -1.50, 1.50, -2.40, 2.40);
    for (Joint e : {Joint::right_elbow, Joint::left_elbow}) set(e, 0.0, 2.60, -1.40, 1.40, -0.15, 0.15);
    for (Joint w : {Joint::right_wrist, Joint::left_wrist}) set(w, -1.20, 1.20, -0.30, 0.30, -0.50, 0.50);
    for (Joint h : {Joint::right_hip, Joint::left_hip}) set(h, -0.50, 2.20, -0.70, 0.70, -0.70, 0.70);
    for (Joint k : {Joint::right_knee, Joint::left_knee}) set(k, 0.0, 2.50, -0.20, 0.20, -0.10, 0.10);
    for (Joint a : {Joint::right_ankle, Joint::left_ankle}) set(a, -0.70, 0.60, -0.30, 0.30, -0.40, 0.40);
    for (Joint t : {Joint::right_toe, Joint::left_toe}) set(t, 0, 0, 0, 0, 0, 0);
    return L;
}

double JointLimits::violation(const Pose& pose) const {
    double sum = 0;
    for (int j = 0; j < kJointCount; ++j) {
        if (is_end_site(j)) continue;
        const Eigen::Vector3d a = frames[j].transpose() * pose.rotations.row(j).transpose();
        for (int k = 0; k < 3; ++k) {
            const double over = std::max(0.0, a[k] - upper(j, k)) + std::max(0.0, lower(j, k) - a[k]);
            sum += over * over;
        }
    }
    return sum;
}

Eigen::Vector3d rotated_in_world(const Eigen::Vector3d& local_axis_angle, const Eigen::Matrix3d& parent_world_rotation,
                                 const Eigen::Matrix3d& world_rotation) {
    const Eigen::AngleAxisd turned(Eigen::Matrix3d(parent_world_rotation.transpose() * world_rotation *
                                                   parent_world_rotation * rotation_of(local_axis_angle)));
    return turned.angle() * turned.axis();
}

PosedSkeleton forward_kinematics(const Eigen::Matrix<double, kJointCount, 3>& rest_joints,
                                 const Pose& pose) {
    std::string why;
    if (!pose.is_valid(&why)) throw InvalidInput(why);
    if (!rest_joints.allFinite()) throw InvalidInput("rest joint positions are not finite");
    PosedSkeleton out;
    for (int j = 0; j < kJointCount; ++j) {
        const int parent = kJointParents[j];
        Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
        local.linear() = rotation_of(pose.rotations.row(j).transpose());
        if (parent < 0) {
            local.translation() = rest_joints.row(j).transpose() + pose.translation;
            out.global[j] = local;
        } else {
            local.translation() = (rest_joints.row(j) - rest_joints.row(parent)).transpose();
            out.global[j] = out.global[parent] * local;
        }
        Eigen::Isometry3d unrest = Eigen::Isometry3d::Identity();
        unrest.translation() = -rest_joints.row(j).transpose();
        out.skinning[j] = out.global[j] * unrest;
        out.joints.row(j) = out.global[j].translation().transpose();
    }
    return out;
}

Eigen::MatrixXd skin_vertices(const BodyModel& model, const Eigen::MatrixXd& rest_vertices,
                              const PosedSkeleton& skeleton) {
    const auto& W = model.skin_weights;
    require(rest_vertices.cols() == 3 && rest_vertices.rows() == W.rows(),
            "skin_vertices: rest_vertices is ", rest_vertices.rows(), " x ", rest_vertices.cols(),
            ", expected ", W.rows(), " x 3 (the model's vertex count)");
    std::array<Eigen::Matrix<double, 3, 4>, kJointCount> T;
    for (int j = 0; j < kJointCount; ++j) T[j] = skeleton.skinning[j].matrix().topRows<3>();
    Eigen::MatrixXd out(rest_vertices.rows(), 3);
    // skin_weights is column-major (#V x J); a row-major copy would be faster but the
    // model keeps one layout; iterate columns and accumulate.
    out.setZero();
    for (int j = 0; j < W.outerSize(); ++j) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(W, j); it; ++it) {
            const Eigen::Vector3d p = rest_vertices.row(it.row()).transpose();
            out.row(it.row()) += it.value() * (T[j].leftCols<3>() * p + T[j].col(3)).transpose();
        }
    }
    return out;
}

PosedBody pose_body(const BodyModel& model, const ShapedBody& shaped, const Pose& pose) {
    const PosedSkeleton sk = forward_kinematics(shaped.joints, pose);
    return PosedBody{skin_vertices(model, shaped.vertices, sk), sk.joints};
}

}  // namespace drape::body

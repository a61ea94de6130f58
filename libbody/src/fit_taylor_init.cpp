#include "fit_taylor_init.hpp"

#include "fit_kinematics.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace drape::body::detail {

namespace {

// Image joint indices (kImageJoints order).
enum : int {
    i_r_ankle = 0, i_r_knee, i_r_hip, i_l_hip, i_l_knee, i_l_ankle, i_r_hand, i_r_elbow,
    i_r_shoulder, i_l_shoulder, i_l_elbow, i_l_hand, i_neck, i_head
};

using Rotations = Eigen::Matrix<double, kJointCount, 3>;
using Points = Eigen::Matrix<double, kImageJointCount, 3>;

Eigen::Vector3d row3(const Eigen::Matrix<double, kJointCount, 3>& m, Joint j) {
    return m.row(index(j)).transpose();
}

// Rotation taking the orthonormal frame built from (a0 primary, b0 secondary) to the one
// built from (a, b).
Eigen::Matrix3d align_frames(const Eigen::Vector3d& a0, const Eigen::Vector3d& b0,
                             const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    auto frame = [](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
        Eigen::Matrix3d F;
        const Eigen::Vector3d e1 = p.normalized();
        Eigen::Vector3d e2 = q - q.dot(e1) * e1;
        if (e2.norm() < 1e-9) e2 = e1.unitOrthogonal();
        e2.normalize();
        F.col(0) = e1;
        F.col(1) = e2;
        F.col(2) = e1.cross(e2);
        return F;
    };
    return frame(a, b) * frame(a0, b0).transpose();
}

Eigen::Matrix3d minimal_rotation(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    if (from.norm() < 1e-12 || to.norm() < 1e-12) return Eigen::Matrix3d::Identity();
    return Eigen::Quaterniond::FromTwoVectors(from, to).toRotationMatrix();
}

struct Posed {
    Rotations rotations = Rotations::Zero();
    Frames<double> frames;
};

void update(const Eigen::Matrix<double, kJointCount, 3>& rest, Posed& p) {
    Eigen::Matrix<double, kJointCount, 3, Eigen::RowMajor> rest_rm = rest;
    Eigen::Matrix<double, kJointCount, 3, Eigen::RowMajor> rot_rm = p.rotations;
    const double zero[3] = {0, 0, 0};
    forward_kinematics_t(rest_rm.data(), rot_rm.data(), zero, p.frames);
}

// Applies the world rotation `delta` about joint j (to j and its subtree).
void rotate_world(const Eigen::Matrix<double, kJointCount, 3>& rest, Posed& p, int j,
                  const Eigen::Matrix3d& delta) {
    const int parent = kJointParents[j];
    const Eigen::Matrix3d G = parent < 0 ? Eigen::Matrix3d::Identity() : p.frames.rotation[parent];
    p.rotations.row(j) = rotated_in_world(p.rotations.row(j).transpose(), G, delta).transpose();
    update(rest, p);
}

struct Limb {
    int root;        // shoulder / hip joint (kinematic)
    int middle;      // elbow / knee
    int end;         // wrist / ankle
    int i_root, i_middle, i_end;  // image joints
    Eigen::Vector3d flex;  // rest-world direction the distal segment moves to when flexing
};

const std::array<Limb, 4>& limbs() {
    static const std::array<Limb, 4> l = {{
        {index(Joint::right_shoulder), index(Joint::right_elbow), index(Joint::right_wrist),
         i_r_shoulder, i_r_elbow, i_r_hand, Eigen::Vector3d(0, 0, 1)},
        {index(Joint::left_shoulder), index(Joint::left_elbow), index(Joint::left_wrist),
         i_l_shoulder, i_l_elbow, i_l_hand, Eigen::Vector3d(0, 0, 1)},
        {index(Joint::right_hip), index(Joint::right_knee), index(Joint::right_ankle), i_r_hip,
         i_r_knee, i_r_ankle, Eigen::Vector3d(0, 0, -1)},
        {index(Joint::left_hip), index(Joint::left_knee), index(Joint::left_ankle), i_l_hip,
         i_l_knee, i_l_ankle, Eigen::Vector3d(0, 0, -1)},
    }};
    return l;
}

void pose_limb(const Eigen::Matrix<double, kJointCount, 3>& rest, Posed& p, const Limb& limb,
               const Points& target) {
    const Eigen::Vector3d u_t = target.row(limb.i_middle) - target.row(limb.i_root);
    const Eigen::Vector3d f_t = target.row(limb.i_end) - target.row(limb.i_middle);
    const Eigen::Vector3d u_c = p.frames.position[limb.middle] - p.frames.position[limb.root];
    const Eigen::Vector3d n_t = u_t.cross(f_t);
    const double bent = n_t.norm() / std::max(1e-12, u_t.norm() * f_t.norm());
    if (bent < std::sin(10.0 * M_PI / 180.0)) {
        rotate_world(rest, p, limb.root, minimal_rotation(u_c, u_t));
    } else {
        const Eigen::Vector3d u0 = rest.row(limb.middle) - rest.row(limb.root);
        const Eigen::Vector3d n0 = u0.cross(limb.flex);
        const Eigen::Matrix3d& G = p.frames.rotation[limb.root];
        rotate_world(rest, p, limb.root, align_frames(G * u0, G * n0, u_t, n_t));
    }
    const Eigen::Vector3d f_c = p.frames.position[limb.end] - p.frames.position[limb.middle];
    rotate_world(rest, p, limb.middle, minimal_rotation(f_c, f_t));
}

}  // namespace

double limit_violation(const Eigen::Matrix<double, kJointCount, 3>& rotations,
                       const JointLimits& limits, std::initializer_list<int> joints) {
    double cost = 0;
    for (int j : joints) {
        const Eigen::Vector3d r = rotations.row(j).transpose();
        const Eigen::Vector3d a = limits.frames[j].transpose() * r;
        for (int c = 0; c < 3; ++c) {
            const double below = std::max(0.0, limits.lower(j, c) - a[c]);
            const double above = std::max(0.0, a[c] - limits.upper(j, c));
            cost += below * below + above * above + 1e-3 * r[c] * r[c];
        }
    }
    return cost;
}

TaylorInit taylor_initialize(const Eigen::Matrix<double, kJointCount, 3>& rest,
                             const Eigen::Matrix<double, kImageJointCount, 2>& px,
                             const JointLimits& limits) {
    auto img = [&](int i) { return Eigen::Vector2d(px.row(i).transpose()); };
    const Eigen::Vector3d rest_hip_mid =
        0.5 * (row3(rest, Joint::right_hip) + row3(rest, Joint::left_hip));
    const Eigen::Vector2d img_hip_mid = 0.5 * (img(i_r_hip) + img(i_l_hip));

    // Model lengths of the image "bones".
    const double l_hips = (row3(rest, Joint::left_hip) - row3(rest, Joint::right_hip)).norm();
    const double l_torso = (row3(rest, Joint::neck) - rest_hip_mid).norm();
    const double l_head = (row3(rest, Joint::head_top) - row3(rest, Joint::neck)).norm();
    const double l_shoulders =
        (row3(rest, Joint::left_shoulder) - row3(rest, Joint::right_shoulder)).norm();
    const double d_torso = (img(i_neck) - img_hip_mid).norm();

    // Scale: the least foreshortened of torso and legs (Taylor: s >= every ratio).
    double s = d_torso / l_torso;
    for (const Limb& limb : {limbs()[2], limbs()[3]}) {
        const double l1 = (rest.row(limb.middle) - rest.row(limb.root)).norm();
        const double l2 = (rest.row(limb.end) - rest.row(limb.middle)).norm();
        s = std::max(s, (img(limb.i_middle) - img(limb.i_root)).norm() / l1);
        s = std::max(s, (img(limb.i_end) - img(limb.i_middle)).norm() / l2);
    }
    if (!(s > 0) || !std::isfinite(s)) s = 1.0;
    auto depth = [&](int a, int b, double length) {
        const double d = (img(a) - img(b)).norm() / s;
        return std::sqrt(std::max(0.0, length * length - d * d));
    };
    auto depth_pts = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, double length) {
        const double d = (a - b).norm() / s;
        return std::sqrt(std::max(0.0, length * length - d * d));
    };
    const double dz_hips = depth(i_l_hip, i_r_hip, l_hips);
    const double dz_torso = depth_pts(img(i_neck), img_hip_mid, l_torso);
    const double dz_head = depth(i_head, i_neck, l_head);
    const double dz_shoulders = depth(i_l_shoulder, i_r_shoulder, l_shoulders);

    Points base;
    for (int i = 0; i < kImageJointCount; ++i)
        base.row(i) << (px(i, 0) - img_hip_mid.x()) / s, -(px(i, 1) - img_hip_mid.y()) / s, 0.0;

    TaylorInit best;
    best.plausibility_cost = std::numeric_limits<double>::infinity();
    const std::initializer_list<int> torso_joints = {index(Joint::spine), index(Joint::chest),
                                                     index(Joint::neck), index(Joint::head)};
    for (int torso_signs = 0; torso_signs < 16; ++torso_signs) {
        const double s_hips = (torso_signs & 1) ? -1 : 1;
        const double s_torso = (torso_signs & 2) ? -1 : 1;
        const double s_head = (torso_signs & 4) ? -1 : 1;
        const double s_shoulders = (torso_signs & 8) ? -1 : 1;
        Points P = base;
        P(i_r_hip, 2) = -0.5 * s_hips * dz_hips;
        P(i_l_hip, 2) = 0.5 * s_hips * dz_hips;
        P(i_neck, 2) = s_torso * dz_torso;
        P(i_head, 2) = P(i_neck, 2) + s_head * dz_head;
        P(i_r_shoulder, 2) = P(i_neck, 2) - 0.5 * s_shoulders * dz_shoulders;
        P(i_l_shoulder, 2) = P(i_neck, 2) + 0.5 * s_shoulders * dz_shoulders;

        Posed torso;
        update(rest, torso);
        {
            const Eigen::Vector3d up0 = row3(rest, Joint::neck) - rest_hip_mid;
            const Eigen::Vector3d side0 = row3(rest, Joint::left_hip) - row3(rest, Joint::right_hip);
            const Eigen::Vector3d hip_mid = 0.5 * (P.row(i_r_hip) + P.row(i_l_hip)).transpose();
            const Eigen::Vector3d up = P.row(i_neck).transpose() - hip_mid;
            const Eigen::Vector3d side = (P.row(i_l_hip) - P.row(i_r_hip)).transpose();
            rotate_world(rest, torso, 0, align_frames(up0, side0, up, side));
            const Eigen::Vector3d sh_c = torso.frames.position[index(Joint::left_shoulder)] -
                                         torso.frames.position[index(Joint::right_shoulder)];
            const Eigen::Vector3d sh_t = (P.row(i_l_shoulder) - P.row(i_r_shoulder)).transpose();
            rotate_world(rest, torso, index(Joint::chest), minimal_rotation(sh_c, sh_t));
            const Eigen::Vector3d head_c = torso.frames.position[index(Joint::head_top)] -
                                           torso.frames.position[index(Joint::neck)];
            const Eigen::Vector3d head_t = (P.row(i_head) - P.row(i_neck)).transpose();
            rotate_world(rest, torso, index(Joint::neck), minimal_rotation(head_c, head_t));
        }
        double cost = limit_violation(torso.rotations, limits, torso_joints);
        Posed result = torso;
        int evaluated = 0;
        for (const Limb& limb : limbs()) {
            const double l1 = (rest.row(limb.middle) - rest.row(limb.root)).norm();
            const double l2 = (rest.row(limb.end) - rest.row(limb.middle)).norm();
            const double dz1 = depth(limb.i_middle, limb.i_root, l1);
            const double dz2 = depth(limb.i_end, limb.i_middle, l2);
            double best_limb = std::numeric_limits<double>::infinity();
            Posed best_posed;
            Points best_points = P;
            for (int signs = 0; signs < 4; ++signs) {
                Points Q = P;
                Q(limb.i_middle, 2) = Q(limb.i_root, 2) + ((signs & 1) ? -dz1 : dz1);
                Q(limb.i_end, 2) = Q(limb.i_middle, 2) + ((signs & 2) ? -dz2 : dz2);
                Posed trial = torso;
                pose_limb(rest, trial, limb, Q);
                const double c = limit_violation(trial.rotations, limits, {limb.root, limb.middle});
                ++evaluated;
                if (c < best_limb) {
                    best_limb = c;
                    best_posed = trial;
                    best_points = Q;
                }
            }
            cost += best_limb;
            for (int j : {limb.root, limb.middle}) result.rotations.row(j) = best_posed.rotations.row(j);
            P(limb.i_middle, 2) = best_points(limb.i_middle, 2);
            P(limb.i_end, 2) = best_points(limb.i_end, 2);
        }
        best.sign_combinations += evaluated;
        if (cost < best.plausibility_cost) {
            best.plausibility_cost = cost;
            best.rotations = result.rotations;
            best.joints_3d = P;
        }
    }

    Posed final_pose;
    final_pose.rotations = best.rotations;
    update(rest, final_pose);
    const Eigen::Vector3d posed_hip_mid = 0.5 * (final_pose.frames.position[index(Joint::right_hip)] +
                                                 final_pose.frames.position[index(Joint::left_hip)]);
    best.translation = -posed_hip_mid;
    best.scale_px_per_m = s;
    best.offset_px = img_hip_mid;
    return best;
}

}  // namespace drape::body::detail

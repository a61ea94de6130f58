// Private to libbody: the residuals of fit_body() as Ceres autodiff functors. Every one
// takes the same four parameter blocks (rotations 66, translation 3, camera 3, shape z 10;
// see fit_kinematics.hpp) so that any of them can be held constant per stage.
//
// Units: image residuals are in percent of the person's pixel height (`unit_px` = 1 % of
// it), so that the weights of docs/body-fitting.md do not depend on the photo's size.
#pragma once

#include "fit_distance_transform.hpp"
#include "fit_kinematics.hpp"

#include <drape/body/pose.hpp>
#include <drape/body/shape_prior.hpp>

#include <ceres/ceres.h>

#include <array>
#include <cmath>
#include <vector>

namespace drape::body::detail {

/// A residual d that grows like d near 0 and saturates at `cap` (a Geman-McClure-like
/// robustifier applied per residual, since a Ceres loss acts on a whole block).
template <class T>
T saturate(const T& d, double cap) {
    using std::sqrt;
    return d / sqrt(T(1.0) + (d / cap) * (d / cap));
}

/// Reprojection of the 14 model joints onto the image joints (28 residuals).
struct JointResidual {
    const LinearRest* rest;
    Camera fixed;
    Eigen::Matrix<double, kImageJointCount, 2> target_px;
    Eigen::Matrix<double, kImageJointCount, 3> offsets_m = Eigen::Matrix<double, kImageJointCount, 3>::Zero();
    double weight = 1;   ///< sqrt of the term weight
    double unit_px = 1;  ///< 1 % of the person's pixel height

    template <class T>
    bool operator()(const T* rot, const T* trans, const T* cam, const T* z, T* residuals) const {
        T joints[3 * kJointCount];
        rest_joints(*rest, z, joints);
        Frames<T> frames;
        forward_kinematics_t(joints, rot, trans, frames);
        for (int i = 0; i < kImageJointCount; ++i) {
            const auto p = project_t(fixed, cam, image_joint_t(frames, offsets_m, i));
            residuals[2 * i] = weight * (p[0] - target_px(i, 0)) / unit_px;
            residuals[2 * i + 1] = weight * (p[1] - target_px(i, 1)) / unit_px;
        }
        return true;
    }
};

/// A pull of sampled vertex `vertex` (an index into LinearRest::vertex_ids) to an image point.
struct Pull {
    int vertex = 0;
    Eigen::Vector2d target_px = Eigen::Vector2d::Zero();
};

/// Silhouette terms on a chunk of the sampled vertices:
///  - inside: each vertex in [first, first + count) should project into the person mask
///    (distance to the mask, 0 inside, saturating at `cap`): 1 residual per vertex;
///  - skin: each pull moves its vertex towards an uncovered skin pixel: 2 residuals each.
struct VertexResidual {
    const LinearRest* rest;
    Camera fixed;
    const DistanceField* outside;  ///< distance to the person mask
    int first = 0;
    int count = 0;
    double inside_weight = 1;
    std::vector<Pull> pulls;
    double pull_weight = 1;
    double unit_px = 1;
    double cap = 5;  ///< saturation, in units of unit_px

    int residual_count() const { return count + 2 * static_cast<int>(pulls.size()); }

    template <class T>
    bool operator()(const T* rot, const T* trans, const T* cam, const T* z, T* residuals) const {
        T joints[3 * kJointCount];
        rest_joints(*rest, z, joints);
        Frames<T> frames;
        forward_kinematics_t(joints, rot, trans, frames);
        auto projected = [&](int k) {
            return project_t(fixed, cam, skin_point(*rest, k, rest_vertex(*rest, k, z), frames));
        };
        for (int i = 0; i < count; ++i) {
            const auto p = projected(first + i);
            const T d = sample_bilinear(*outside, p[0], p[1]) / unit_px;
            residuals[i] = inside_weight * saturate(d, cap);
        }
        for (size_t i = 0; i < pulls.size(); ++i) {
            const auto p = projected(pulls[i].vertex);
            const T dx = (p[0] - pulls[i].target_px.x()) / unit_px;
            const T dy = (p[1] - pulls[i].target_px.y()) / unit_px;
            using std::sqrt;
            const T len = sqrt(dx * dx + dy * dy + 1e-12);
            const T scale = pull_weight * saturate(len, cap) / len;
            residuals[count + 2 * i] = scale * dx;
            residuals[count + 2 * i + 1] = scale * dy;
        }
        return true;
    }
};

/// Joint-limit prior (soft bounds, per axis-angle component) plus a weak pull towards the
/// rest pose that keeps unobserved rotations (twists, clavicles, wrists) well defined.
/// The root's rotation is free. 2 * kRotationParams residuals.
struct PosePriorResidual {
    JointLimits limits;
    double limit_weight = 10;       ///< per radian outside the limits
    /// Per rotation parameter (3 per joint, world-frame axis-angle components): weight per
    /// radian of rotation away from the rest pose. The root's entries weigh its tilt.
    std::array<double, kRotationParams> rest_weights{};

    template <class T>
    bool operator()(const T* rot, const T* /*trans*/, const T* /*cam*/, const T* /*z*/,
                    T* residuals) const {
        for (int j = 0; j < kJointCount; ++j) {
            for (int c = 0; c < 3; ++c) {
                const int i = 3 * j + c;
                if (j == 0) {
                    residuals[2 * i] = T(0);
                    residuals[2 * i + 1] = rest_weights[i] * rot[i];
                    continue;
                }
                // The limits bound the rotation's components in the joint's anatomical
                // frame (flexion, twist, abduction): a = frames[j]^T r.
                T a = T(0);
                for (int k = 0; k < 3; ++k) a += limits.frames[j](k, c) * rot[3 * j + k];
                T violation = T(0);
                if (a < T(limits.lower(j, c))) violation = T(limits.lower(j, c)) - a;
                if (a > T(limits.upper(j, c))) violation = a - T(limits.upper(j, c));
                residuals[2 * i] = limit_weight * violation;
                residuals[2 * i + 1] = rest_weights[i] * rot[i];
            }
        }
        return true;
    }
};

/// ANSUR Mahalanobis prior on z: sqrt_information (z - mean), plus a stiff pin of the
/// stature when it is known. kSemanticCount + 1 residuals.
struct ShapePriorResidual {
    Eigen::Matrix<double, kSemanticCount, kSemanticCount> sqrt_information;
    Eigen::Matrix<double, kSemanticCount, 1> mean;
    double weight = 1;
    double height_m = 0;           ///< 0 = unknown
    double height_sigma_m = 0.005;

    template <class T>
    bool operator()(const T* /*rot*/, const T* /*trans*/, const T* /*cam*/, const T* z,
                    T* residuals) const {
        for (int r = 0; r < kSemanticCount; ++r) {
            T s = T(0);
            for (int c = 0; c < kSemanticCount; ++c) s += sqrt_information(r, c) * (z[c] - mean[c]);
            residuals[r] = weight * s;
        }
        const int h = static_cast<int>(Semantic::height_m);
        residuals[kSemanticCount] =
            height_m > 0 ? (z[h] - height_m) / height_sigma_m : T(0);
        return true;
    }
};

}  // namespace drape::body::detail

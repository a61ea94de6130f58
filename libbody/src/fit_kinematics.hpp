// Private to libbody: forward kinematics, linear blend skinning and projection templated on
// the scalar type, so that Ceres can differentiate them with jets. The conventions are those
// of pose.cpp (forward_kinematics / skin_vertices):
//   global_root = [R_root | rest_root + translation]
//   global_j    = global_parent * [R_j | rest_j - rest_parent],  R_j = AngleAxis(rotations.row(j))
//   skinning_j  = global_j * translate(-rest_j)
// and of Camera::project (camera.hpp). test_fit_body.cpp checks both agreements.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/camera.hpp>
#include <drape/body/skeleton.hpp>

#include <ceres/rotation.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <vector>

namespace drape::body::detail {

/// Layout of the Ceres parameter blocks of a fit.
inline constexpr int kRotationParams = 3 * kJointCount;  ///< rotations, row-major 22 x 3
inline constexpr int kTranslationParams = 3;             ///< root translation, metres
inline constexpr int kCameraParams = 3;                  ///< weak: (s, tx, ty); pinhole: unused
inline constexpr int kShapeParams = kSemanticCount;      ///< the continuous semantic values z

/// The rest geometry as an affine function of z for one gender (c = A (v - v_ref) + b is
/// affine in z, and p0 + Z c and J = R (p0 + Z c) are linear in c):
///     joints(z)   = joint_offset + joint_jacobian * z       (3 kJointCount, row-major)
///     vertices(z) = vertex_offset + vertex_jacobian * z     (3 n, for vertex_ids)
struct LinearRest {
    Eigen::Matrix<double, 3 * kJointCount, 1> joint_offset;
    Eigen::Matrix<double, 3 * kJointCount, kSemanticCount> joint_jacobian;
    std::vector<int> vertex_ids;             ///< n sampled template vertices
    Eigen::VectorXd vertex_offset;           ///< 3n
    Eigen::Matrix<double, Eigen::Dynamic, kSemanticCount, Eigen::RowMajor> vertex_jacobian;
    /// Skin weights of the sampled vertices in CSR form: vertex k uses entries
    /// weight_start[k] .. weight_start[k+1]-1 of weight_joint / weight_value.
    std::vector<int> weight_start;
    std::vector<int> weight_joint;
    std::vector<double> weight_value;

    int vertex_count() const { return static_cast<int>(vertex_ids.size()); }
};

/// Builds the affine maps for `gender` and the template vertices `vertex_ids`.
LinearRest make_linear_rest(const BodyModel& model, Gender gender,
                            const std::vector<int>& vertex_ids);

/// Shape coefficients c(z) for a gender: c = A (v - v_ref) + b, v = [female, z].
Eigen::VectorXd semantic_to_coefficients(const BodyModel& model, Gender gender,
                                         const Eigen::Matrix<double, kSemanticCount, 1>& z);

template <class T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <class T>
using Mat3 = Eigen::Matrix<T, 3, 3>;

/// World transforms of every joint: x_world = R[j] * x_joint_frame + position[j].
template <class T>
struct Frames {
    std::array<Mat3<T>, kJointCount> rotation;
    std::array<Vec3<T>, kJointCount> position;  ///< posed joint positions
    std::array<Vec3<T>, kJointCount> rest;      ///< rest joint positions
};

/// Rest joints (3 kJointCount) of the affine map at z.
template <class T>
void rest_joints(const LinearRest& rest, const T* z, T* joints) {
    for (int i = 0; i < 3 * kJointCount; ++i) {
        T v = T(rest.joint_offset[i]);
        for (int k = 0; k < kSemanticCount; ++k) v += rest.joint_jacobian(i, k) * z[k];
        joints[i] = v;
    }
}

/// Forward kinematics. \param rest_joints 3 kJointCount, \param rotations 3 kJointCount
/// axis-angle, \param translation 3.
template <class T>
void forward_kinematics_t(const T* rest_joints, const T* rotations, const T* translation,
                          Frames<T>& out) {
    for (int j = 0; j < kJointCount; ++j) {
        out.rest[j] = Vec3<T>(rest_joints[3 * j], rest_joints[3 * j + 1], rest_joints[3 * j + 2]);
        Mat3<T> local;
        ceres::AngleAxisToRotationMatrix(rotations + 3 * j, local.data());  // column-major
        const int p = kJointParents[j];
        if (p < 0) {
            out.rotation[j] = local;
            out.position[j] =
                out.rest[j] + Vec3<T>(translation[0], translation[1], translation[2]);
        } else {
            out.rotation[j] = out.rotation[p] * local;
            out.position[j] = out.rotation[p] * (out.rest[j] - out.rest[p]) + out.position[p];
        }
    }
}

/// Image joint i (kImageJoints order) of the posed skeleton: its model joint plus its offset
/// in the frame of the bone that ends there (ImageJointOffsets).
template <class T>
Vec3<T> image_joint_t(const Frames<T>& frames, const Eigen::Matrix<double, kImageJointCount, 3>& offsets_m, int i) {
    const int j = index(kImageJoints[static_cast<size_t>(i)]);
    const int p = std::max(0, kJointParents[static_cast<size_t>(j)]);
    const Vec3<T> o(T(offsets_m(i, 0)), T(offsets_m(i, 1)), T(offsets_m(i, 2)));
    return frames.position[j] + frames.rotation[p] * o;
}

/// Linear blend skinning of one rest point with vertex k's weights.
template <class T>
Vec3<T> skin_point(const LinearRest& rest, int k, const Vec3<T>& x, const Frames<T>& frames) {
    Vec3<T> out = Vec3<T>::Zero();
    for (int e = rest.weight_start[k]; e < rest.weight_start[k + 1]; ++e) {
        const int j = rest.weight_joint[e];
        out += rest.weight_value[e] * (frames.rotation[j] * (x - frames.rest[j]) + frames.position[j]);
    }
    return out;
}

/// Rest position of sampled vertex k at z.
template <class T>
Vec3<T> rest_vertex(const LinearRest& rest, int k, const T* z) {
    Vec3<T> v;
    for (int d = 0; d < 3; ++d) {
        const int row = 3 * k + d;
        T s = T(rest.vertex_offset[row]);
        for (int i = 0; i < kSemanticCount; ++i) s += rest.vertex_jacobian(row, i) * z[i];
        v[d] = s;
    }
    return v;
}

/// Camera::project with the weak-perspective parameters taken from `cam` = (s, tx, ty)
/// (the fitted ones) and the pinhole parameters from `fixed`.
template <class T>
Eigen::Matrix<T, 2, 1> project_t(const Camera& fixed, const T* cam, const Vec3<T>& X) {
    if (fixed.model == CameraModel::weak_perspective)
        return {cam[0] * X[0] + cam[1], -cam[0] * X[1] + cam[2]};
    const T zc = T(fixed.distance_m) - X[2];
    return {T(fixed.focal_px) * X[0] / zc + T(fixed.offset_px.x()),
            T(fixed.focal_px) * -X[1] / zc + T(fixed.offset_px.y())};
}

}  // namespace drape::body::detail

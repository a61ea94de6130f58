#include <drape/vision/joints.hpp>

#include <drape/core/errors.hpp>

#include <cmath>

namespace drape::vision {

Eigen::Vector2d Joints::mid_hip() const {
    return 0.5 * ((*this)[Joint::left_hip] + (*this)[Joint::right_hip]);
}
Eigen::Vector2d Joints::mid_shoulder() const {
    return 0.5 * ((*this)[Joint::left_shoulder] + (*this)[Joint::right_shoulder]);
}
Eigen::Vector2d Joints::mid_knee() const {
    return 0.5 * ((*this)[Joint::left_knee] + (*this)[Joint::right_knee]);
}
Eigen::Vector2d Joints::mid_ankle() const {
    return 0.5 * ((*this)[Joint::left_ankle] + (*this)[Joint::right_ankle]);
}

double Joints::body_height_px() const {
    const double path = ((*this)[Joint::head] - (*this)[Joint::neck]).norm() +
                        ((*this)[Joint::neck] - mid_hip()).norm() +
                        (mid_hip() - mid_knee()).norm() + (mid_knee() - mid_ankle()).norm();
    return path / 0.955;
}

void Joints::validate(int width, int height) const {
    for (int i = 0; i < kJointCount; ++i) {
        const Eigen::Vector2d& p = px[static_cast<size_t>(i)];
        require(std::isfinite(p.x()) && std::isfinite(p.y()), "joint ", i, " (",
                kJointNames[static_cast<size_t>(i)], ") is not finite: (", p.x(), ", ", p.y(),
                ")");
        require(p.x() >= 0 && p.x() <= width && p.y() >= 0 && p.y() <= height, "joint ", i,
                " (", kJointNames[static_cast<size_t>(i)], ") at (", p.x(), ", ", p.y(),
                ") px lies outside the ", width, " x ", height, " image");
    }
    require(body_height_px() >= 8, "the joints give a body height of ", body_height_px(),
            " px (< 8 px): degenerate skeleton");
}

Joints Joints::scaled(double factor) const {
    Joints out = *this;
    for (auto& p : out.px) p *= factor;
    return out;
}

}  // namespace drape::vision

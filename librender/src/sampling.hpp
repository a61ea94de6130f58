// Deterministic per-pixel sampling: every random number is a hash of (pixel, sample,
// dimension), so a pixel's value does not depend on which thread computed it or when.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <numeric>

namespace drape::render::detail {

inline constexpr double kPi = 3.14159265358979323846;

/// SplitMix64's finaliser (Steele, Lea, Flood 2014): a good 64-bit mixing function.
inline std::uint64_t mix64(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/// Uniform in [0, 1) from a key.
inline double hash_unit(std::uint64_t key) {
    return static_cast<double>(mix64(key) >> 11) * (1.0 / 9007199254740992.0);
}

/// Stratified 2D samples for one pixel: the R2 low-discrepancy sequence (Roberts 2018,
/// based on the plastic number) with a per-pixel, per-dimension random shift
/// (Cranley-Patterson rotation) and a per-dimension permutation of the sample index, so
/// that the 2D dimensions (pixel jitter, sun disk, sky hemisphere) are decorrelated.
class PixelSampler {
public:
    static constexpr int kDimensions = 3;  ///< 2D pairs: pixel jitter, sun disk, sky hemisphere

    PixelSampler(int x, int y, int count) : count_(count) {
        const std::uint64_t key = mix64((static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) ^
                                        static_cast<std::uint32_t>(y));
        for (int dim = 0; dim < kDimensions; ++dim) {
            Dimension& d = dims_[dim];
            const std::uint64_t k = key ^ mix64(0x9e3779b97f4a7c15ULL * static_cast<std::uint64_t>(dim + 1));
            const int n = count;
            d.a = 1 + static_cast<int>(mix64(k + 3) % static_cast<std::uint64_t>(n > 1 ? n - 1 : 1));
            while (std::gcd(d.a, n) != 1) ++d.a;  // a coprime to n: s -> (a s + b) mod n permutes
            d.b = static_cast<int>(mix64(k + 4) % static_cast<std::uint64_t>(n));
            d.shift = {hash_unit(k + 1), hash_unit(k + 2)};
        }
    }

    /// 2D sample `s` (0 <= s < count) of dimension pair `dim` (< kDimensions).
    Eigen::Vector2d get(int s, int dim) const {
        const Dimension& d = dims_[dim];
        const long long idx = (static_cast<long long>(d.a) * s + d.b) % count_;
        constexpr double a1 = 0.75487766624669276005, a2 = 0.56984029099805326591;
        const double u = d.shift.x() + a1 * static_cast<double>(idx);
        const double v = d.shift.y() + a2 * static_cast<double>(idx);
        return {u - std::floor(u), v - std::floor(v)};
    }

private:
    struct Dimension {
        int a = 1;
        int b = 0;
        Eigen::Vector2d shift = Eigen::Vector2d::Zero();
    };
    Dimension dims_[kDimensions];
    int count_;
};

/// An orthonormal basis (t1, t2) completing unit vector n (Duff et al. 2017, "Building an
/// Orthonormal Basis, Revisited").
inline void orthonormal_basis(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2) {
    const double sign = std::copysign(1.0, n.z());
    const double a = -1.0 / (sign + n.z());
    const double b = n.x() * n.y() * a;
    t1 = {1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x()};
    t2 = {b, sign + n.y() * n.y() * a, -n.y()};
}

/// Cosine-weighted direction in the hemisphere about unit n.
inline Eigen::Vector3d cosine_hemisphere(const Eigen::Vector3d& n, const Eigen::Vector2d& u) {
    Eigen::Vector3d t1, t2;
    orthonormal_basis(n, t1, t2);
    const double r = std::sqrt(u.x()), phi = 2.0 * kPi * u.y();
    return (r * std::cos(phi) * t1 + r * std::sin(phi) * t2 + std::sqrt(std::max(0.0, 1.0 - u.x())) * n)
        .normalized();
}

/// A direction within the disk of angular radius atan(tan_radius) about unit d, uniform on
/// the tangent plane (the disk is small: the sun, a soft box).
inline Eigen::Vector3d cone_sample(const Eigen::Vector3d& d, double tan_radius, const Eigen::Vector2d& u) {
    if (tan_radius <= 0) return d;
    Eigen::Vector3d t1, t2;
    orthonormal_basis(d, t1, t2);
    const double r = tan_radius * std::sqrt(u.x()), phi = 2.0 * kPi * u.y();
    return (d + r * std::cos(phi) * t1 + r * std::sin(phi) * t2).normalized();
}

}  // namespace drape::render::detail

// The random generator of synthetic scenes: splitmix64 (Steele, Lea, Flood 2014), fully
// specified, with our own uniform, normal and truncated-normal draws, so that a scene does
// not depend on the standard library's distributions and is the same bytes on every build.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace drape::synth {

/// Independent streams of one seed: choosing another pose leaves body and sizing unchanged.
enum class Stream : std::uint64_t { body = 1, pose, garment, sizing, material, look, camera };

class Rng {
public:
    Rng(std::uint64_t seed, Stream stream)
        : state_(seed ^ (0x9E3779B97F4A7C15ull * (static_cast<std::uint64_t>(stream) + 1))) {
        next();
    }
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1), 53 bits.
    double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }
    /// Uniform in [lo, hi).
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    /// Uniform in 0..n-1. \pre n > 0
    std::size_t index(std::size_t n) { return std::size_t(uniform() * double(n)) % n; }
    /// Standard normal (Box-Muller, one value per two uniforms).
    double normal() {
        const double u1 = 1.0 - uniform(), u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
    }
    /// Standard normal redrawn until |z| <= limit.
    double truncated_normal(double limit) {
        for (;;) {
            const double z = normal();
            if (std::abs(z) <= limit) return z;
        }
    }

private:
    std::uint64_t state_;
};

}  // namespace drape::synth

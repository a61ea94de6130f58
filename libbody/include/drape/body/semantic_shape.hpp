// The semantic shape parameters z of the paper (section 3, "Human Body"), in SI units.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

namespace drape::body {

enum class Gender { female, male };

std::string_view to_string(Gender g);
/// Parses "female" / "male"; throws drape::InvalidInput naming the value otherwise.
Gender parse_gender(std::string_view s);

/// The ten continuous semantic parameters, in this fixed order (the order of the prior's
/// mean and covariance and of SemanticShape::continuous()).
enum class Semantic : int {
    height_m = 0,          ///< stature, floor to vertex of the head
    weight_kg = 1,         ///< body mass
    muscle = 2,            ///< 0 (little) .. 1 (very muscular); ANSUR proxy, see docs/shape-prior.md
    chest_girth_m = 3,     ///< horizontal girth at bust-point (nipple) level (ANSUR chestcircumference)
    waist_girth_m = 4,     ///< horizontal girth at the navel (ANSUR waistcircumference, omphalion)
    hip_girth_m = 5,       ///< girth at maximum buttock protrusion (ANSUR buttockcircumference)
    thigh_girth_m = 6,     ///< right thigh at the gluteal furrow (ANSUR thighcircumference)
    calf_girth_m = 7,      ///< right calf, maximum (ANSUR calfcircumference)
    shoulder_height_m = 8, ///< floor to right acromion (ANSUR acromialheight)
    crotch_height_m = 9,   ///< floor to crotch (ANSUR crotchheight, the leg length)
};
inline constexpr int kSemanticCount = 10;

/// JSON / CLI keys of the continuous parameters, in Semantic order.
inline constexpr std::array<std::string_view, kSemanticCount> kSemanticKeys = {
    "height_m",      "weight_kg",     "muscle",            "chest_girth_m",  "waist_girth_m",
    "hip_girth_m",   "thigh_girth_m", "calf_girth_m",      "shoulder_height_m",
    "crotch_height_m",
};

/// A complete set of semantic parameters.
struct SemanticShape {
    Gender gender = Gender::female;
    Eigen::Matrix<double, kSemanticCount, 1> values = Eigen::Matrix<double, kSemanticCount, 1>::Zero();

    double& operator[](Semantic s) { return values[static_cast<int>(s)]; }
    double operator[](Semantic s) const { return values[static_cast<int>(s)]; }
    /// Checks finiteness and physical plausibility (positive lengths, heights ordered:
    /// crotch < shoulder < stature, muscle in [0, 1]); explains the first failure in `why`.
    bool is_valid(std::string* why = nullptr) const;
};

/// A partial request: any subset of the parameters; the rest is predicted from the prior.
struct SemanticRequest {
    std::optional<Gender> gender;
    std::array<std::optional<double>, kSemanticCount> values{};

    std::optional<double>& operator[](Semantic s) { return values[static_cast<int>(s)]; }
    const std::optional<double>& operator[](Semantic s) const { return values[static_cast<int>(s)]; }
};

}  // namespace drape::body

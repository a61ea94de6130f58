// The data-driven cloth material of Wang, O'Brien and Ramamoorthi 2011 ("Data-Driven
// Elastic Models for Cloth: Modeling and Measurement", ACM TOG 30(4)), in the layout and
// units ArcSim ships it (see ../shared/materials/README.md): an areal density, a 6 x 4
// stretching table and a 3 x 5 bending table, plus the scale factors s_s and s_b that the
// garment recovery searches over.
#pragma once

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace drape::cloth {

/// One cloth material, in SI units.
///
/// Stretching: row 0 of `stretching_n_per_m` is the zero-strain sample (valid in every
/// direction); rows 1..5 are the samples at largest principal stretch w = 7/6 (Green strain
/// 1/6 * (1 + 1/12)) for the directions 0, 22.5, 45, 67.5 and 90 degrees from the pattern u
/// (weft) axis. Each row holds (k0, k1, k2, k3), the coefficients of the energy density
/// ψ = ½k0 G_uu² + k1 G_uu G_vv + ½k2 G_vv² + k3 G_uv² (after ArcSim's factor 2, see
/// stretching_stiffness), in N/m = J/m² per squared Green strain. Entries may be negative
/// in the measured data (k1, k3); interpolated values are clamped to >= 0.
///
/// Bending: `bending_n_m(r, c)` is the bending rigidity in N·m for hinge direction
/// r * 45 degrees from the u axis (r = 0, 1, 2) and curvature c * 10 1/m (c = 0..4), where
/// curvature = θ l / (A0 + A1) of a hinge (ArcSim's definition).
struct Material {
    double density_kg_per_m2 = 0;                     ///< areal density ρ, kg/m²
    std::array<std::array<double, 4>, 6> stretching_n_per_m{};  ///< see above, N/m
    std::array<std::array<double, 5>, 3> bending_n_m{};          ///< see above, N·m
    double stretching_scale = 1;  ///< s_s: multiplies every stretching value
    double bending_scale = 1;     ///< s_b: multiplies every bending value

    /// True if the density and scales are finite and > 0 and every table entry is finite.
    /// \param why if not null and the material is invalid, receives the reason.
    bool is_valid(std::string* why = nullptr) const;
};

/// Descriptive fields of a material file (Drape's own format, docs/materials.md). They do
/// not affect the simulation; any of them may be empty.
struct MaterialInfo {
    std::string name;         ///< short identifier, e.g. "gray-interlock"
    std::string description;  ///< free text, e.g. garment type and fibre content
    std::string source;       ///< citation of where the numbers come from
    std::string license;      ///< terms under which the numbers may be used
};

/// Reads a material file, detecting the format from its content:
/// - Drape's own format (docs/materials.md): a JSON object with "format": "drape-material",
///   "version": 1, SI-named fields, the scales and descriptive fields (returned in `info`).
///   It holds the Material fields exactly, so load_material(save_material(m)) == m bit for bit.
/// - otherwise ArcSim's format: {"density": ρ, "stretching": 6 x [4 numbers],
///   "bending": 3 x [5 numbers]}, whose numbers are already our SI units (see
///   ../shared/materials/README.md). Scales are set to 1; `info->name` is the file stem.
/// Lines starting with `//` (ArcSim's paper.json, aluminium.json) are accepted as comments.
/// \param info if not null, receives the descriptive fields (cleared first).
/// \throw drape::IoError if the file cannot be read (message names the file).
/// \throw drape::InvalidInput if the content is not valid JSON, a field is missing, unknown,
///        has the wrong shape or type, the "format" or "version" is not supported, or the
///        material is invalid (message names file and field).
Material load_material(const std::filesystem::path& path, MaterialInfo* info = nullptr);

/// Writes `material` in Drape's own material format (docs/materials.md) with the
/// descriptive fields of `info`, atomically (a failed write leaves `path` as it was).
/// Numbers are written in the shortest form that reads back to the same double.
/// \throw drape::InvalidInput if the material is invalid (Material::is_valid) or a text
///        field of `info` is not valid UTF-8.
/// \throw drape::IoError if the file cannot be written (message names the file).
void save_material(const Material& material, const std::filesystem::path& path,
                   const MaterialInfo& info = {});

/// The names of the materials built into the library, in a fixed order: the ten fabrics
/// measured by Wang, O'Brien and Ramamoorthi 2011 and ArcSim's hand-made "paper" and
/// "aluminium", transcribed from ArcSim 0.3.1's material files (research data, see
/// docs/materials.md for the citation and license notice).
std::vector<std::string> builtin_material_names();

/// A built-in material by name (see builtin_material_names), scales 1; equal bit for bit
/// to loading ArcSim's file of the same name and to data/materials/<name>.json.
/// \throw drape::InvalidInput if `name` is unknown (the message lists the known names).
Material builtin_material(const std::string& name);

/// The descriptive fields of a built-in material: name, fabric description, citation of
/// Wang et al. 2011 / ArcSim and ArcSim's license notice.
/// \throw drape::InvalidInput if `name` is unknown (the message lists the known names).
MaterialInfo builtin_material_info(const std::string& name);

/// The interpolated stretching coefficients for one strain state, in N/m, already
/// multiplied by ArcSim's factor 2 and by the stretching scale. The energy density is
/// ψ(G) = ½ k_uu G_uu² + k_uv G_uu G_vv + ½ k_vv G_vv² + k_shear G_uv².
struct StretchingStiffness {
    double k_uu = 0;     ///< k0
    double k_uv = 0;     ///< k1, the Poisson-like coupling
    double k_vv = 0;     ///< k2
    double k_shear = 0;  ///< k3
};

/// Stretching stiffness at largest principal stretch `stretch` (w = sqrt of the largest
/// eigenvalue of C = 2G + I, dimensionless) along direction `direction_rad` (angle of the
/// principal axis from the pattern u axis, folded into [0, π/2]).
/// Piecewise-linear: bilinear in w between 1 and 7/6 (constant beyond, row 0 for w <= 1)
/// and in direction between the 22.5-degree samples; each entry clamped to >= 0, then
/// multiplied by 2 and by `material.stretching_scale`.
/// \pre stretch and direction_rad finite. \throw drape::InvalidInput otherwise.
StretchingStiffness stretching_stiffness(const Material& material, double stretch,
                                         double direction_rad);

/// Stretching stiffness for the Green strain G (2 x 2, symmetric, pattern frame): the
/// stretch and direction come from the largest eigenpair of C = 2G + I.
/// \throw drape::InvalidInput if G is not finite.
StretchingStiffness stretching_stiffness(const Material& material,
                                         const Eigen::Matrix2d& green_strain);

/// Bending rigidity in N·m (times `material.bending_scale`) for a hinge edge at
/// `direction_rad` from the pattern u axis (any angle: folded into [0, π/2]) and hinge
/// curvature `curvature_per_m` = θ l / (A0 + A1). Bilinear between the table samples
/// (rows 0/45/90 degrees, columns 0/10/20/30/40 1/m), constant beyond 40 1/m; a negative
/// curvature extrapolates linearly from columns 0 and 1, as ArcSim does (callers that want
/// a sign-symmetric model pass |curvature|). The result is clamped to >= 0.
/// \throw drape::InvalidInput if an argument is not finite.
double bending_stiffness(const Material& material, double direction_rad,
                         double curvature_per_m);

}  // namespace drape::cloth

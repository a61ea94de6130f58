// From the wrinkle density P measured on a photo to the material search's target: the
// calibrated mapping of issue 21 ("Material C"), and the paper's ad-hoc interpolation it
// replaces (section 6.1: K(P)_target = I(P), I(1) = 1e-4 1/m, I(50) = 1e5 1/m).
//
// The calibration is fitted by tools/fit_curvature_calibration.cpp on synthetic scenes
// (data/synth/curvature_calibration.json: simulated, rendered, P measured on the renders
// by vision::detect_wrinkles) and embedded with the table it was fitted on and its
// cross-validated error (src/curvature_calibration_data.cpp, generated). Plain numbers in:
// libgarment does not depend on libvision. See docs/material-estimation.md.
#pragma once

#include <drape/garment/garment_type.hpp>

#include <array>
#include <string>
#include <vector>

namespace drape::garment {

/// What a measured P says about the garment's material, for the material optimiser.
struct CurvatureTarget {
    /// Target mean curvature 𝒦 (1/m; the mean over the garment's vertices of
    /// cloth::vertex_local_curvature, as truth.json's mean_curvature_per_m), and an interval
    /// from the calibration's leave-one-garment-out residuals (10th to 90th percentile).
    double k_per_m = 0;
    double k_low_per_m = 0;
    double k_high_per_m = 0;
    /// The bending scale s_b of the calibration's fabric mapped from P directly (log10),
    /// clamped to the calibrated range, with its interval (same percentiles, clamped).
    double log10_bending_scale = 0;
    double log10_bending_low = 0;
    double log10_bending_high = 0;
    /// P = 0: no fold reached the detector's limit. The value is then the calibration's
    /// level for fold-free garments (its interval from those garments alone): the folds
    /// are below the limit, so K is at most about k_high_per_m, s_b at least about
    /// log10_bending_low.
    bool censored = false;
    /// The fabric space the calibration holds for (its bending scales are multiples of
    /// this fabric's measured bending table).
    std::string fabric;
};

/// The calibrated target for a garment of `type` with wrinkle density `p_per_m2` (1/m²,
/// vision::detect_wrinkles' P: 0 when no fold is detected).
/// \throw drape::InvalidInput when p_per_m2 is negative or not finite.
CurvatureTarget curvature_from_wrinkle_density(GarmentType type, double p_per_m2);

/// The paper's mapping (section 6.1), K linear in P through I(1) = 1e-4 1/m and
/// I(50) = 1e5 1/m, P clamped to the paper's observed range [1, 50] 1/m² (the line
/// extrapolated below P = 1 would give a negative curvature). For comparison only.
/// \throw drape::InvalidInput when p_per_m2 is negative or not finite.
double paper_curvature_from_wrinkle_density(double p_per_m2);

// ---------------------------------------------------------------------------------------
// The calibration: its data, its model and its fit (used by the tool that generates the
// embedded calibration, and by the test that re-fits it).

/// One calibration garment: a single-garment synthetic scene and what was measured on it.
struct WrinkleCalibrationSample {
    std::string scene;            ///< the scene's name (folder)
    GarmentType type = GarmentType::skirt;
    std::string fabric;           ///< base fabric (truth.json material.base_fabric)
    double bending_scale = 1;     ///< s_b
    double p_midday_per_m2 = 0;   ///< P on image_midday.png (truth.json)
    double p_sunset_per_m2 = 0;   ///< P on image_sunset.png, same detector and mask
    double k_per_m = 0;           ///< truth.json mean_curvature_per_m
};

/// Model forms, for y = ln K or y = log10 s_b: with x = ln P,
///   y = offset[type] + slope[type] x        (P > 0)
///   y = offset[type] + censored_offset      (P = 0, no fold detected)
enum class WrinkleModelForm {
    type_constant,     ///< offset per type, no P (the baseline: what P adds)
    shared_line,       ///< one offset, one slope
    type_offset_line,  ///< offset per type, one slope
    type_line,         ///< offset and slope per type
};

/// "type_constant", "shared_line", "type_offset_line", "type_line".
std::string wrinkle_model_form_name(WrinkleModelForm form);

/// A fitted model (coefficients indexed by GarmentType) and its residual percentiles.
struct WrinkleModel {
    WrinkleModelForm form = WrinkleModelForm::type_offset_line;
    std::array<double, 4> offset{};
    std::array<double, 4> slope{};
    double censored_offset = 0;
    /// 10th and 90th percentiles of the leave-one-garment-out residuals y - ŷ, for P > 0
    /// and for P = 0 (the latter 0 when the data had fewer than 3 censored observations).
    double residual_low = 0, residual_high = 0;
    double censored_residual_low = 0, censored_residual_high = 0;

    /// ŷ for a garment of `type` with P = p_per_m2 (>= 0).
    double predict(GarmentType type, double p_per_m2) const;
};

/// What a model is fitted on: y against P, per observation, with the garment it belongs
/// to (leave-one-out leaves a garment's observations out together: both lightings).
struct WrinkleObservation {
    GarmentType type = GarmentType::skirt;
    double p_per_m2 = 0;
    double y = 0;
    int garment = 0;
};

/// Ordinary least squares of `form` on the observations (the residual percentiles are left
/// 0: see cross_validate_wrinkle_model). A coefficient the data cannot determine (a type
/// without observations, no censored observation) is 0.
/// \throw drape::InvalidInput on fewer observations than coefficients or bad values.
WrinkleModel fit_wrinkle_model(const std::vector<WrinkleObservation>& observations, WrinkleModelForm form);

/// Per observation of `predict`, ŷ of the model fitted on `fit_on` without that
/// observation's garment (leave one garment out: all its observations go together).
std::vector<double> leave_one_garment_out(const std::vector<WrinkleObservation>& fit_on,
                                          const std::vector<WrinkleObservation>& predict, WrinkleModelForm form);

/// fit_wrinkle_model on `fit_on` plus the residual percentiles of leave_one_garment_out
/// on `predict`.
WrinkleModel cross_validate_wrinkle_model(const std::vector<WrinkleObservation>& fit_on,
                                          const std::vector<WrinkleObservation>& predict, WrinkleModelForm form);

/// Which P a calibration was fitted on.
enum class WrinkleLighting { midday, both };

/// The observations of a calibration: y = ln K (curvature) or log10 s_b, on the midday P
/// or on both lightings (two observations per garment). Samples of another fabric than
/// `fabric` are left out.
std::vector<WrinkleObservation> wrinkle_observations(const std::vector<WrinkleCalibrationSample>& samples,
                                                     const std::string& fabric, bool bending,
                                                     WrinkleLighting lighting);

/// Leave-one-garment-out errors of a calibration, over the observations of both lightings
/// (each garment's P at mid-day and at sunset, predicted by the model fitted without it).
struct WrinkleCalibrationErrors {
    int garments = 0;
    double curvature_accuracy = 0;      ///< mean max(0, 1 - |K̂ - K| / K) (issue 21's metric)
    double curvature_abs_log10 = 0;     ///< mean |log10(K̂ / K)|
    double bending_abs_log10 = 0;       ///< mean |log10 ŝ_b - log10 s_b| (ŝ_b clamped to the range)
    double paper_curvature_accuracy = 0;  ///< the same metric for paper_curvature_from_wrinkle_density
    double paper_curvature_abs_log10 = 0;
};

/// The calibration: fabric space, model forms and fitted models, the table, the errors.
struct WrinkleCalibration {
    std::string fabric;                 ///< the fabric space (gray-interlock)
    double log10_bending_min = 0, log10_bending_max = 2;  ///< the calibrated s_b range
    WrinkleLighting lighting = WrinkleLighting::both;     ///< P the models were fitted on
    WrinkleModel curvature;             ///< y = ln K
    WrinkleModel bending;               ///< y = log10 s_b
    WrinkleCalibrationErrors errors;    ///< leave-one-garment-out, as fitted
    std::vector<WrinkleCalibrationSample> samples;  ///< the table (all fabrics measured)
};

/// Fits both models of the chosen forms on `samples` of `fabric` and measures their
/// leave-one-garment-out errors (what the tool does after choosing the forms).
WrinkleCalibration fit_wrinkle_calibration(const std::vector<WrinkleCalibrationSample>& samples,
                                           const std::string& fabric, WrinkleModelForm curvature_form,
                                           WrinkleModelForm bending_form, WrinkleLighting lighting);

/// The target of `calibration` for (type, P), as curvature_from_wrinkle_density.
/// \throw drape::InvalidInput when p_per_m2 is negative or not finite.
CurvatureTarget wrinkle_calibration_target(const WrinkleCalibration& calibration, GarmentType type,
                                           double p_per_m2);

/// The embedded calibration (src/curvature_calibration_data.cpp, generated by
/// drape_fit_curvature_calibration): the one curvature_from_wrinkle_density uses.
const WrinkleCalibration& embedded_wrinkle_calibration();

}  // namespace drape::garment

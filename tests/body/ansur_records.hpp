// ANSUR II records as semantic shapes (SI units), for tests and for the prior derivation
// tool (tools/derive_ansur_prior.cpp compiles this file too, so that the prior and the
// tests read the survey in exactly one way).
//
// The data are the ANSUR II public release (Gordon C.C. et al., 2012 Anthropometric Survey
// of U.S. Army Personnel: Methods and Summary Statistics, NATICK/TR-15/007, 2014; public
// domain), stored outside the source tree in ../shared/data/anthropometry. They are test and
// derivation data only: nothing here is linked into the libraries.
#pragma once

#include <drape/body/semantic_shape.hpp>

#include <Eigen/Core>

#include <filesystem>
#include <vector>

namespace drape::test {

/// One surveyed subject.
struct AnsurRecord {
    int subject_id = 0;  ///< `subjectid` (male file) / `SubjectId` (female file)
    drape::body::Gender gender = drape::body::Gender::female;
    /// The ten semantic values in drape::body::Semantic order and SI units: stature,
    /// weightkg / 10, the muscle proxy (see AnsurMuscleProxy), chest, waist (omphalion),
    /// buttock, thigh, calf circumferences, acromial height and crotch height, all mm / 1000.
    Eigen::Matrix<double, drape::body::kSemanticCount, 1> values =
        Eigen::Matrix<double, drape::body::kSemanticCount, 1>::Zero();
    /// bicepscircumferenceflexed + forearmcircumferenceflexed (metres): the input of the
    /// muscle proxy, kept for checks.
    double flexed_arm_girth_m = 0;
};

/// The muscle proxy of one gender. ANSUR II has no body-composition measure, so "muscle" is
/// how much flexed-arm girth a subject has for their height, weight and waist:
///   a      = bicepscircumferenceflexed + forearmcircumferenceflexed                 (metres)
///   a_hat  = c0 + c1 * height_m + c2 * weight_kg + c3 * waist_girth_m  (least squares)
///   muscle = Phi((a - a_hat) / s),  s = sqrt(RSS / (n - 4)),  Phi = standard normal CDF
/// so 0.5 is a typical arm for that build, 0.84 one residual SD more arm, 0.16 one less.
/// Height is a regressor so that tall, lean people are not called unmuscular for having
/// less girth per kilogram; weight and waist so that fat is not counted as muscle.
struct AnsurMuscleProxy {
    /// c0 (m), c1 (m per m of height), c2 (m per kg), c3 (m per m of waist)
    Eigen::Vector4d coefficients = Eigen::Vector4d::Zero();
    double residual_sd_m = 0;  ///< s
    int sample_count = 0;      ///< n

    /// The proxy for one subject, in (0, 1).
    double muscle(double flexed_arm_girth_m, double height_m, double weight_kg,
                  double waist_girth_m) const;
};

/// Fits the muscle proxy on all subjects of one file.
/// \param records  subjects of one gender (flexed_arm_girth_m, height, weight, waist set)
/// \throw drape::InvalidInput if fewer than 10 records are given.
AnsurMuscleProxy fit_muscle_proxy(const std::vector<AnsurRecord>& records);

/// The path of the CSV of one gender inside the anthropometry folder.
std::filesystem::path ansur_csv_path(const std::filesystem::path& anthropometry_dir,
                                     drape::body::Gender gender);

/// Every subject of both files: all females then all males, each sorted by subject id, with
/// the muscle proxy fitted on that gender's full file.
/// \param proxies  if not null, receives the female [0] and male [1] proxy fits
/// \throw drape::IoError naming the path if a CSV is missing or unreadable;
///        drape::InvalidInput if a needed column is absent or a value is not a number.
std::vector<AnsurRecord> load_ansur_all(const std::filesystem::path& anthropometry_dir,
                                        std::vector<AnsurMuscleProxy>* proxies = nullptr);

/// A deterministic, spread-out sample: `per_gender` females then `per_gender` males; of the
/// n subjects of a gender sorted by id, the ones at indices floor(i * n / per_gender).
/// The muscle proxy is the one fitted on the full file (as in load_ansur_all).
/// \throw drape::IoError as load_ansur_all; drape::InvalidInput if per_gender is not in
///        [1, n] for either gender.
std::vector<AnsurRecord> load_ansur_sample(const std::filesystem::path& anthropometry_dir,
                                           int per_gender);

}  // namespace drape::test

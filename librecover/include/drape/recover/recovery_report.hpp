// What a recovery shows its user: the outfit as plain meshes (for mask, overlay and glb) and
// the contents of report.html (the photo, segmentation, folds, overlay, mask, patterns,
// material and numbers).
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/recover/outfit_meshes.hpp>
#include <drape/recover/recover.hpp>
#include <drape/recover/report.hpp>

#include <opencv2/core.hpp>

namespace drape::recover {

/// The recovered body (posed as draped) and garments (with their pattern uv and class ids).
OutfitMeshes outfit_meshes(const body::BodyModel& model, const RecoveryResult& result);

/// The report of one recovery. `overlay` is render_overlay's image (empty: left out).
ReportContent recovery_report(const cv::Mat& photo, const RecoveryResult& result, const RecoverSummary& summary,
                              const cv::Mat& overlay, const std::string& title);

}  // namespace drape::recover

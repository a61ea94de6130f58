// report.html: a self-contained HTML report of a recovery (or a try-on) that opens from the
// file with no network: images embedded as base64 data URIs, SVG inline, CSS inline, no
// scripts (docs/recovery.md, "Output files"). Plain input: captions, encoded images, SVG
// text, tables of strings and notes, so the caller decides what to show (for recovery:
// the photo, segmentation, folds, overlay; pattern SVGs from garment::pattern_to_svg;
// material and numbers tables).
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace drape::recover {

/// An encoded image: PNG ("image/png") or JPEG ("image/jpeg") bytes as in a file.
struct ReportImage {
    std::string caption;
    std::vector<std::uint8_t> bytes;
    std::string mime = "image/png";
};

/// An SVG document (e.g. garment::pattern_to_svg), drawn inline. An XML prolog, a DOCTYPE
/// and the root's xmlns declarations are dropped (HTML puts <svg> in the SVG namespace).
struct ReportSvg {
    std::string caption;
    std::string svg;
};

struct ReportTable {
    std::string caption;
    std::vector<std::string> header;             ///< column titles; may be empty
    std::vector<std::vector<std::string>> rows;  ///< each at most header.size() cells when there is a header
};

/// What the report shows, in this order: title, images, SVGs, tables, notes.
struct ReportContent {
    std::string title = "Drape recovery";
    std::vector<ReportImage> images;
    std::vector<ReportSvg> svgs;
    std::vector<ReportTable> tables;
    std::vector<std::string> notes;
};

/// The report as one HTML5 document. Every text (title, captions, cells, notes) is
/// HTML-escaped (& < > " ').
/// \throw drape::InvalidInput naming the item (e.g. "image 2 'overlay'") and the problem:
///        a mime other than image/png or image/jpeg, bytes that are not of that format
///        (by their signature) or empty, an SVG that does not start with <svg, holds a
///        <script> or an http(s):// or protocol-relative reference after the xmlns
///        declarations are dropped, or a table row longer than its header.
std::string report_html(const ReportContent& content);

/// Writes report_html(content) to `path` atomically.
/// \throw drape::InvalidInput (see report_html); drape::IoError if it cannot be written.
void write_report_html(const std::filesystem::path& path, const ReportContent& content);

/// Encodes an 8-bit image (CV_8UC1 gray / class ids, CV_8UC3 BGR, CV_8UC4 BGRA) for the
/// report: mime "image/png" (lossless: masks, overlays) or "image/jpeg" (photos, at
/// `jpeg_quality` 1..100).
/// \throw drape::InvalidInput for an empty image, another type, another mime or quality.
ReportImage report_image(const std::string& caption, const cv::Mat& image, const std::string& mime = "image/png",
                         int jpeg_quality = 90);

/// Standard base64 (RFC 4648, with '=' padding) of `bytes`.
std::string base64_encode(const std::vector<std::uint8_t>& bytes);

}  // namespace drape::recover

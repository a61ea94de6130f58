#include <drape/recover/report.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cctype>
#include <regex>
#include <sstream>

namespace drape::recover {

namespace {

std::string escape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string item_name(const char* kind, std::size_t index, const std::string& caption) {
    return std::string(kind) + " " + std::to_string(index) + " '" + caption + "'";
}

bool starts_with(const std::vector<std::uint8_t>& bytes, std::initializer_list<std::uint8_t> signature) {
    return bytes.size() >= signature.size() && std::equal(signature.begin(), signature.end(), bytes.begin());
}

void check_image(const ReportImage& image, std::size_t index) {
    const std::string who = "report: " + item_name("image", index, image.caption);
    require(image.mime == "image/png" || image.mime == "image/jpeg", who, ": mime '", image.mime,
            "' is not image/png or image/jpeg");
    require(!image.bytes.empty(), who, ": no bytes");
    if (image.mime == "image/png")
        require(starts_with(image.bytes, {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A}), who,
                ": the bytes are not a PNG file (no PNG signature)");
    else
        require(starts_with(image.bytes, {0xFF, 0xD8, 0xFF}), who, ": the bytes are not a JPEG file (no SOI marker)");
}

/// The SVG document as an inline element: prolog, DOCTYPE and comments before the root
/// dropped, the root's xmlns declarations removed; checked for scripts and remote references.
std::string inline_svg(const ReportSvg& item, std::size_t index) {
    const std::string who = "report: " + item_name("svg", index, item.caption);
    std::string s = item.svg;
    static const std::regex head(R"(^(\s|<\?[\s\S]*?\?>|<!DOCTYPE[^>]*>|<!--[\s\S]*?-->)*)", std::regex::icase);
    s = std::regex_replace(s, head, "", std::regex_constants::format_first_only);
    require(lower(s.substr(0, 4)) == "<svg", who, ": the text does not start with an <svg> element");
    const std::size_t root_end = s.find('>');
    require(root_end != std::string::npos, who, ": the <svg> tag is not closed");
    static const std::regex xmlns(R"(\s+xmlns(:[A-Za-z_][\w.-]*)?\s*=\s*("[^"]*"|'[^']*'))");
    s = std::regex_replace(s.substr(0, root_end), xmlns, "") + s.substr(root_end);
    const std::string l = lower(s);
    require(l.find("<script") == std::string::npos, who, ": holds a <script> element");
    require(l.find("http://") == std::string::npos && l.find("https://") == std::string::npos, who,
            ": holds an http(s):// reference (the report must open without network)");
    static const std::regex protocol_relative(R"((href|src)\s*=\s*["']\s*//)", std::regex::icase);
    require(!std::regex_search(s, protocol_relative), who, ": holds a protocol-relative (//host) reference");
    return s;
}

constexpr const char* kStyle = R"(body{font-family:system-ui,-apple-system,"Segoe UI",Helvetica,Arial,sans-serif;margin:24px auto;max-width:1200px;padding:0 16px;color:#222;background:#fafafa}
h1{font-size:1.6em;margin:0 0 16px}
h2{font-size:1.2em;margin:28px 0 10px;border-bottom:1px solid #ddd;padding-bottom:4px}
.grid{display:flex;flex-wrap:wrap;gap:16px}
figure{margin:0;background:#fff;border:1px solid #ddd;border-radius:6px;padding:8px;flex:1 1 260px;max-width:100%}
figure img,figure svg{display:block;max-width:100%;height:auto;margin:0 auto}
figure.svg{flex-basis:100%}
figcaption{font-size:.9em;color:#555;margin-top:6px;text-align:center}
table{border-collapse:collapse;margin:6px 0 16px;background:#fff}
caption{text-align:left;font-weight:600;padding:4px 0}
th,td{border:1px solid #ccc;padding:4px 10px;text-align:left;font-variant-numeric:tabular-nums}
th{background:#f0f0f0}
ul.notes li{margin:4px 0}
footer{margin-top:32px;font-size:.8em;color:#888})";

}  // namespace

std::string base64_encode(const std::vector<std::uint8_t>& bytes) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 3 <= bytes.size(); i += 3) {
        const unsigned v = (unsigned(bytes[i]) << 16) | (unsigned(bytes[i + 1]) << 8) | bytes[i + 2];
        for (int s = 18; s >= 0; s -= 6) out += kAlphabet[(v >> s) & 63];
    }
    const std::size_t rest = bytes.size() - i;
    if (rest > 0) {
        const unsigned v = (unsigned(bytes[i]) << 16) | (rest == 2 ? unsigned(bytes[i + 1]) << 8 : 0u);
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

std::string report_html(const ReportContent& content) {
    for (std::size_t i = 0; i < content.images.size(); ++i) check_image(content.images[i], i);
    std::vector<std::string> svgs;
    for (std::size_t i = 0; i < content.svgs.size(); ++i) svgs.push_back(inline_svg(content.svgs[i], i));
    for (std::size_t t = 0; t < content.tables.size(); ++t) {
        const ReportTable& table = content.tables[t];
        for (std::size_t r = 0; r < table.rows.size(); ++r)
            require(table.header.empty() || table.rows[r].size() <= table.header.size(), "report: ",
                    item_name("table", t, table.caption), ": row ", r, " has ", table.rows[r].size(),
                    " cells, the header ", table.header.size());
    }

    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      << "<title>" << escape(content.title) << "</title>\n<style>\n" << kStyle << "\n</style>\n</head>\n<body>\n"
      << "<h1>" << escape(content.title) << "</h1>\n";
    if (!content.images.empty()) {
        h << "<section class=\"images\">\n<div class=\"grid\">\n";
        for (const ReportImage& image : content.images)
            h << "<figure><img alt=\"" << escape(image.caption) << "\" src=\"data:" << image.mime << ";base64,"
              << base64_encode(image.bytes) << "\"><figcaption>" << escape(image.caption)
              << "</figcaption></figure>\n";
        h << "</div>\n</section>\n";
    }
    if (!svgs.empty()) {
        h << "<section class=\"svgs\">\n<div class=\"grid\">\n";
        for (std::size_t i = 0; i < svgs.size(); ++i)
            h << "<figure class=\"svg\">" << svgs[i] << "<figcaption>" << escape(content.svgs[i].caption)
              << "</figcaption></figure>\n";
        h << "</div>\n</section>\n";
    }
    for (const ReportTable& table : content.tables) {
        h << "<table>\n<caption>" << escape(table.caption) << "</caption>\n";
        if (!table.header.empty()) {
            h << "<thead><tr>";
            for (const std::string& c : table.header) h << "<th>" << escape(c) << "</th>";
            h << "</tr></thead>\n";
        }
        h << "<tbody>\n";
        for (const auto& row : table.rows) {
            h << "<tr>";
            for (const std::string& c : row) h << "<td>" << escape(c) << "</td>";
            h << "</tr>\n";
        }
        h << "</tbody>\n</table>\n";
    }
    if (!content.notes.empty()) {
        h << "<h2>Notes</h2>\n<ul class=\"notes\">\n";
        for (const std::string& note : content.notes) h << "<li>" << escape(note) << "</li>\n";
        h << "</ul>\n";
    }
    h << "<footer>Written by Drape. This file is self-contained: it needs no network.</footer>\n</body>\n</html>\n";
    return h.str();
}

void write_report_html(const std::filesystem::path& path, const ReportContent& content) {
    write_text_atomically(path, report_html(content));
}

ReportImage report_image(const std::string& caption, const cv::Mat& image, const std::string& mime, int jpeg_quality) {
    const std::string who = "report_image '" + caption + "'";
    require(!image.empty(), who, ": the image is empty");
    require(image.type() == CV_8UC1 || image.type() == CV_8UC3 || image.type() == CV_8UC4, who,
            ": the image must be 8-bit with 1, 3 or 4 channels, got type ", image.type());
    require(mime == "image/png" || mime == "image/jpeg", who, ": mime '", mime, "' is not image/png or image/jpeg");
    require(jpeg_quality >= 1 && jpeg_quality <= 100, who, ": jpeg_quality must be in 1..100, got ", jpeg_quality);
    ReportImage out;
    out.caption = caption;
    out.mime = mime;
    const bool ok = mime == "image/png"
                        ? cv::imencode(".png", image, out.bytes)
                        : cv::imencode(".jpg", image, out.bytes, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality});
    if (!ok) throw IoError(who + ": OpenCV could not encode the image as " + mime);
    return out;
}

}  // namespace drape::recover

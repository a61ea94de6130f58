// report_html / write_report_html: self-contained (no http(s):// reference, no script),
// every image decodes back to its bytes, every text escaped, bad input named; rendered by
// headless Chromium (when installed) it is not blank and shows the embedded image.
#include <drape/core/errors.hpp>
#include <drape/garment/pattern_svg.hpp>
#include <drape/garment/tshirt.hpp>
#include <drape/recover/report.hpp>

#include "run_command.hpp"
#include "test_paths.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <fstream>
#include <regex>
#include <sstream>

using namespace drape;

namespace {

std::vector<std::uint8_t> base64_decode(const std::string& text) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+') return 62;
        if (c == '/') return 63;
        return -1;
    };
    std::vector<std::uint8_t> out;
    unsigned acc = 0;
    int bits = 0;
    for (const char c : text) {
        if (c == '=') break;
        const int v = value(c);
        REQUIRE(v >= 0);
        acc = (acc << 6) | unsigned(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(static_cast<std::uint8_t>((acc >> bits) & 0xFF));
        }
    }
    return out;
}

/// A red 240 x 160 block (PNG) and a gradient (JPEG), a t-shirt pattern, a table and notes,
/// with characters that must be escaped.
recover::ReportContent sample_content() {
    recover::ReportContent c;
    c.title = "Tom & \"Jerry\" <b>recovered</b>";
    c.images.push_back(recover::report_image("photo <red>", cv::Mat(160, 240, CV_8UC3, cv::Scalar(0, 0, 255))));
    cv::Mat gradient(120, 200, CV_8UC3);
    for (int y = 0; y < gradient.rows; ++y)
        for (int x = 0; x < gradient.cols; ++x)
            gradient.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(2 * y), 90);
    c.images.push_back(recover::report_image("overlay 'jpeg'", gradient, "image/jpeg", 85));
    c.svgs.push_back({"pattern 0: t-shirt", garment::pattern_to_svg(garment::make_tshirt(garment::TShirtSizing{}))});
    c.tables.push_back({"material", {"quantity", "value"}, {{"bending scale", "12.5 (x1 .. x100)"},
                                                            {"<script>alert(1)</script>", "a & b"}}});
    c.notes.push_back("IoU < 0.8 & time > 60 s");
    return c;
}

}  // namespace

TEST_CASE("report: base64 of the RFC 4648 test vectors", "[recover][report]") {
    auto b64 = [](const std::string& s) { return recover::base64_encode(std::vector<std::uint8_t>(s.begin(), s.end())); };
    CHECK(b64("") == "");
    CHECK(b64("f") == "Zg==");
    CHECK(b64("fo") == "Zm8=");
    CHECK(b64("foo") == "Zm9v");
    CHECK(b64("foob") == "Zm9vYg==");
    CHECK(b64("fooba") == "Zm9vYmE=");
    CHECK(b64("foobar") == "Zm9vYmFy");
}

TEST_CASE("report: self-contained, images decode to their bytes, text escaped", "[recover][report]") {
    const recover::ReportContent content = sample_content();
    const std::string html = recover::report_html(content);
    CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
    CHECK(html.find("http://") == std::string::npos);
    CHECK(html.find("https://") == std::string::npos);
    CHECK(html.find("<script") == std::string::npos);
    CHECK(html.find("<link") == std::string::npos);

    // Every image is a data URI whose base64 decodes to the bytes given, in order.
    const std::regex data_uri(R"re(src="data:(image/(png|jpeg));base64,([A-Za-z0-9+/=]+)")re");
    std::size_t n = 0;
    for (auto it = std::sregex_iterator(html.begin(), html.end(), data_uri); it != std::sregex_iterator(); ++it, ++n) {
        REQUIRE(n < content.images.size());
        CHECK((*it)[1].str() == content.images[n].mime);
        CHECK(base64_decode((*it)[3].str()) == content.images[n].bytes);
    }
    CHECK(n == content.images.size());
    // The PNG decodes to the red block.
    const cv::Mat red = cv::imdecode(content.images[0].bytes, cv::IMREAD_COLOR);
    CHECK(red.size() == cv::Size(240, 160));
    CHECK(red.at<cv::Vec3b>(80, 120) == cv::Vec3b(0, 0, 255));

    // Escaping of title, captions, cells and notes.
    CHECK(html.find("<title>Tom &amp; &quot;Jerry&quot; &lt;b&gt;recovered&lt;/b&gt;</title>") != std::string::npos);
    CHECK(html.find("photo &lt;red&gt;") != std::string::npos);
    CHECK(html.find("overlay &#39;jpeg&#39;") != std::string::npos);
    CHECK(html.find("<td>&lt;script&gt;alert(1)&lt;/script&gt;</td><td>a &amp; b</td>") != std::string::npos);
    CHECK(html.find("<li>IoU &lt; 0.8 &amp; time &gt; 60 s</li>") != std::string::npos);
    // The pattern SVG is inline, without its XML prolog and namespace declaration.
    CHECK(html.find("<svg width=") != std::string::npos);
    CHECK(html.find("<?xml") == std::string::npos);
    CHECK(html.find("xmlns") == std::string::npos);

    const auto dir = test::scratch_dir("recover_report");
    recover::write_report_html(dir / "report.html", content);
    std::ifstream in(dir / "report.html", std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    CHECK(s.str() == html);
}

TEST_CASE("report: bad input is named", "[recover][report]") {
    auto throws_naming = [](const recover::ReportContent& c, const std::string& what) {
        try {
            recover::report_html(c);
            FAIL("no exception for " << what);
        } catch (const InvalidInput& e) {
            CHECK_THAT(e.what(), Catch::Contains(what));
        }
    };
    recover::ReportContent c = sample_content();
    c.images[1].mime = "image/gif";
    throws_naming(c, "image 1 'overlay 'jpeg'': mime 'image/gif'");
    c = sample_content();
    c.images[1].mime = "image/png";  // JPEG bytes
    throws_naming(c, "not a PNG file");
    c = sample_content();
    c.images[0].bytes.clear();
    throws_naming(c, "no bytes");
    c = sample_content();
    c.svgs[0].svg = "<svg><script>alert(1)</script></svg>";
    throws_naming(c, "svg 0 'pattern 0: t-shirt': holds a <script>");
    c.svgs[0].svg = "<svg><image href=\"https://example.com/a.png\"/></svg>";
    throws_naming(c, "http(s)://");
    c.svgs[0].svg = "<svg><image href=\"//example.com/a.png\"/></svg>";
    throws_naming(c, "protocol-relative");
    c.svgs[0].svg = "<p>not svg</p>";
    throws_naming(c, "does not start with an <svg>");
    c = sample_content();
    c.tables[0].rows.push_back({"a", "b", "c"});
    throws_naming(c, "table 0 'material': row 2 has 3 cells");
    CHECK_THROWS_AS(recover::report_image("x", cv::Mat(), "image/png"), InvalidInput);
    CHECK_THROWS_AS(recover::report_image("x", cv::Mat(4, 4, CV_32FC1), "image/png"), InvalidInput);
    CHECK_THROWS_AS(recover::report_image("x", cv::Mat(4, 4, CV_8UC3), "image/webp"), InvalidInput);
    const auto dir = test::scratch_dir("recover_report_bad");
    c = sample_content();
    c.images[0].mime = "text/html";
    CHECK_THROWS_AS(recover::write_report_html(dir / "report.html", c), InvalidInput);
    CHECK_FALSE(std::filesystem::exists(dir / "report.html"));
}

TEST_CASE("report: headless Chromium renders it, not blank, with the embedded image", "[recover][report]") {
    if (test::run_command("command -v chromium").exit_code != 0) {
        WARN("skipped: chromium is not installed (Debian package 'chromium'; optional, only this test uses it)");
        return;
    }
    const auto dir = test::scratch_dir("recover_report_chromium");
    recover::write_report_html(dir / "report.html", sample_content());
    const auto shot = dir / "screenshot.png";
    const test::CommandResult r = test::run_command(
        "timeout 120 chromium --headless --disable-gpu --no-sandbox --hide-scrollbars --user-data-dir=\"" +
        (dir / "profile").string() + "\" --screenshot=\"" + shot.string() +
        "\" --window-size=1200,2000 \"file://" + (dir / "report.html").string() + "\"");
    INFO(r.out);
    REQUIRE(std::filesystem::exists(shot));
    const cv::Mat img = cv::imread(shot.string(), cv::IMREAD_COLOR);
    REQUIRE(img.cols == 1200);
    REQUIRE(img.rows == 2000);
    cv::Mat gray;
    cv::cvtColor(img, gray, cv::COLOR_BGR2GRAY);
    cv::Scalar mean, stddev;
    cv::meanStdDev(gray, mean, stddev);
    CHECK(stddev[0] > 15.0);
    // The red block (240 x 160 = 38 400 px) is drawn at its size.
    long long red = 0;
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x) {
            const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
            red += p[2] > 200 && p[1] < 60 && p[0] < 60;
        }
    CHECK(red > 30000);
    CHECK(red < 45000);
}

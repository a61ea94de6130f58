#include "encoded_image_check.hpp"

#include <algorithm>
#include <array>

namespace drape::vision::detail {

namespace {

std::string at(std::size_t pos) { return " at byte " + std::to_string(pos); }

std::string jpeg_defect(const std::uint8_t* b, std::size_t n) {
    const std::string cut = "truncated JPEG: the file ends (" + std::to_string(n) +
                            " bytes) before the end-of-image marker";
    std::size_t pos = 2;  // after SOI
    for (;;) {
        if (pos >= n) return cut;
        if (b[pos] != 0xFF) return "corrupt JPEG: expected a marker" + at(pos);
        while (pos < n && b[pos] == 0xFF) ++pos;  // fill bytes
        if (pos >= n) return cut;
        const std::uint8_t marker = b[pos++];
        if (marker == 0xD9) return "";                                   // EOI
        if ((marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) continue;  // no length
        if (marker == 0x00 || marker == 0xD8) return "corrupt JPEG: invalid marker" + at(pos - 1);
        if (pos + 2 > n) return cut;
        const std::size_t length = (std::size_t(b[pos]) << 8) | b[pos + 1];
        if (length < 2) return "corrupt JPEG: segment length " + std::to_string(length) + at(pos);
        if (pos + length > n) return cut;
        pos += length;
        if (marker != 0xDA) continue;
        // Start of scan: entropy-coded data up to the next marker (FF followed by neither
        // a stuffed 00, a restart marker nor a fill byte).
        for (;;) {
            if (pos + 1 >= n) return cut;
            if (b[pos] != 0xFF) {
                ++pos;
                continue;
            }
            const std::uint8_t next = b[pos + 1];
            if (next == 0x00 || (next >= 0xD0 && next <= 0xD7)) {
                pos += 2;
            } else if (next == 0xFF) {
                ++pos;
            } else {
                break;  // a marker starts at pos
            }
        }
    }
}

std::uint32_t crc32(const std::uint8_t* b, std::size_t n) {
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t i = 0; i < 256; ++i) {
            std::uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < n; ++i) c = table[(c ^ b[i]) & 0xFFu] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

std::uint32_t be32(const std::uint8_t* b) {
    return (std::uint32_t(b[0]) << 24) | (std::uint32_t(b[1]) << 16) | (std::uint32_t(b[2]) << 8) | b[3];
}

std::string png_defect(const std::uint8_t* b, std::size_t n) {
    std::size_t pos = 8;  // after the signature
    for (;;) {
        if (pos + 12 > n)
            return "truncated PNG: the file ends (" + std::to_string(n) + " bytes) before the IEND chunk";
        const std::uint32_t length = be32(b + pos);
        if (length > 0x7FFFFFFFu) return "corrupt PNG: chunk length " + std::to_string(length) + at(pos);
        const std::string type(reinterpret_cast<const char*>(b + pos + 4), 4);
        if (pos + 12 + std::size_t(length) > n)
            return "truncated PNG: chunk '" + type + "'" + at(pos) + " needs " + std::to_string(length) +
                   " data bytes but the file ends at byte " + std::to_string(n);
        if (crc32(b + pos + 4, 4 + std::size_t(length)) != be32(b + pos + 8 + length))
            return "corrupt PNG: CRC mismatch in chunk '" + type + "'" + at(pos);
        pos += 12 + std::size_t(length);
        if (type == "IEND") return "";
    }
}

EncodedImageHeader jpeg_header(const std::uint8_t* b, std::size_t n) {
    EncodedImageHeader h;
    h.format = "JPEG";
    std::size_t pos = 2;  // after SOI
    while (pos + 4 <= n) {
        if (b[pos] != 0xFF) return h;
        while (pos < n && b[pos] == 0xFF) ++pos;
        if (pos + 3 > n) return h;
        const std::uint8_t marker = b[pos++];
        if ((marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) continue;
        if (marker == 0xDA || marker == 0xD9) return h;  // a scan before any frame header
        const std::size_t length = (std::size_t(b[pos]) << 8) | b[pos + 1];
        const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (sof) {
            // length(2) precision(1) height(2) width(2)
            if (length < 7 || pos + 7 > n) return h;
            h.height = (std::int64_t(b[pos + 3]) << 8) | b[pos + 4];
            h.width = (std::int64_t(b[pos + 5]) << 8) | b[pos + 6];
            return h;
        }
        if (length < 2) return h;
        pos += length;
    }
    return h;
}

}  // namespace

EncodedImageHeader encoded_image_header(const std::uint8_t* bytes, std::size_t size) {
    static const std::uint8_t png_signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return jpeg_header(bytes, size);
    EncodedImageHeader h;
    if (size >= 8 && std::equal(png_signature, png_signature + 8, bytes)) {
        h.format = "PNG";
        if (size >= 24 && be32(bytes + 8) == 13 && std::equal(bytes + 12, bytes + 16, "IHDR")) {
            h.width = be32(bytes + 16);
            h.height = be32(bytes + 20);
        }
    }
    return h;
}

std::string encoded_image_defect(const std::uint8_t* bytes, std::size_t size) {
    static const std::uint8_t png_signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return jpeg_defect(bytes, size);
    if (size >= 8 && std::equal(png_signature, png_signature + 8, bytes)) return png_defect(bytes, size);
    return "";
}

}  // namespace drape::vision::detail

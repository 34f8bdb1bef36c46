#include "watergen/eval/image/image_io.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <system_error>

#include <fmt/core.h>
#include <png.h>
#include <unistd.h>

namespace watergen {

namespace fs = std::filesystem;

namespace {

void set_error(std::string* error, std::string message) {
    if (error) *error = std::move(message);
}

std::string errno_text(int err) {
    return std::generic_category().message(err);
}

struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
};
using UniqueFile = std::unique_ptr<std::FILE, FileCloser>;

// Writes `target` through a temporary file in the same directory (same file system, so the
// final rename is atomic). `body` writes the content and returns "" or the cause of failure.
// Returns "" or the cause of any failure; on failure the temporary file is removed.
std::string write_atomically(const fs::path& target,
                             const std::function<std::string(std::FILE*)>& body) {
    if (!target.has_filename()) return "path has no file name";

    // Unique per process and call; "x" (C11 exclusive create) refuses to reuse a stray file.
    static std::atomic<unsigned long> counter{0};
    fs::path tmp = target;
    tmp.replace_filename(fmt::format(".{}.tmp-{}-{}", target.filename().string(),
                                     static_cast<long>(::getpid()), counter++));

    std::FILE* raw = std::fopen(tmp.c_str(), "wbx");
    if (!raw) {
        return fmt::format("cannot create temporary file '{}': {}", tmp.string(),
                           errno_text(errno));
    }
    UniqueFile file(raw);
    std::string cause = body(file.get());
    if (cause.empty() && (std::fflush(file.get()) != 0 || std::ferror(file.get()))) {
        cause = fmt::format("write failed: {}", errno_text(errno));
    }
    if (std::fclose(file.release()) != 0 && cause.empty()) {
        cause = fmt::format("close failed: {}", errno_text(errno));
    }
    if (cause.empty()) {
        std::error_code ec;
        fs::rename(tmp, target, ec);
        if (!ec) return {};
        cause =
            fmt::format("cannot rename temporary file '{}' to it: {}", tmp.string(), ec.message());
    }
    std::error_code ignored;
    fs::remove(tmp, ignored);
    return cause;
}

// "<action> '<path>': <cause>", the form of every error message in this file.
std::string message(const char* action, const fs::path& path, const std::string& cause) {
    return fmt::format("{} '{}': {}", action, path.string(), cause);
}

// Runs `fn`, turning any exception (in practice std::bad_alloc) into an error message.
template <class Fn>
auto guarded(const char* action, const fs::path& path, std::string* error, Fn&& fn) noexcept
    -> decltype(fn()) {
    try {
        return fn();
    } catch (const std::exception& e) {
        set_error(error, message(action, path, e.what()));
    } catch (...) {
        set_error(error, message(action, path, "unknown exception"));
    }
    return {};
}

void put_u32_le(unsigned char* out, uint32_t v) {
    for (int i = 0; i < 4; ++i)
        out[i] = static_cast<unsigned char>(v >> (8 * i));
}

uint32_t get_u32(const unsigned char* in, bool little_endian) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) {
        const uint32_t byte = in[little_endian ? i : 3 - i];
        v |= byte << (8 * i);
    }
    return v;
}

bool is_pfm_space(unsigned char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

} // namespace

double linear_to_srgb(double linear) {
    // IEC 61966-2-1:1999 (sRGB) encoding, with the standard's own threshold 0.0031308.
    if (linear <= 0.0031308) return 12.92 * linear;
    return 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double srgb_to_linear(double encoded) {
    // IEC 61966-2-1:1999 (sRGB) decoding.
    if (encoded <= 0.04045) return encoded / 12.92;
    return std::pow((encoded + 0.055) / 1.055, 2.4);
}

std::vector<uint8_t> tone_map_to_srgb8(const ImageRGBA32F& image, float exposure) {
    if (!image.well_formed()) return {};
    std::vector<uint8_t> out(image.pixel_count() * 4);
    for (std::size_t p = 0; p < image.pixel_count(); ++p) {
        const float* in = &image.rgba[p * 4];
        uint8_t* px = &out[p * 4];
        px[3] = 255;
        bool bad = false;
        for (int c = 0; c < 3; ++c) {
            // double: a finite float times a finite exposure cannot overflow here.
            const double v = static_cast<double>(in[c]) * exposure;
            if (!std::isfinite(in[c]) || std::isnan(v)) {
                bad = true;
                break;
            }
            const double e = linear_to_srgb(std::clamp(v, 0.0, 1.0));
            px[c] = static_cast<uint8_t>(std::floor(e * 255.0 + 0.5));
        }
        if (bad) {
            px[0] = 255; // magenta marker, see the header
            px[1] = 0;
            px[2] = 255;
        }
    }
    return out;
}

std::string encode_png(uint32_t width, uint32_t height, std::span<const uint8_t> rgba8,
                       std::string* error) noexcept {
    try {
        const uint64_t expected = uint64_t{width} * height * 4;
        if (width == 0 || height == 0 || rgba8.size() != expected) {
            set_error(error, fmt::format("{}x{} RGBA8 needs {} bytes, got {}", width, height,
                                         expected, rgba8.size()));
            return {};
        }
        // libpng's simplified API keeps its setjmp/longjmp error handling inside libpng, so no
        // longjmp crosses C++ frames here. The first call measures, the second writes.
        png_image image;
        std::memset(&image, 0, sizeof image);
        image.version = PNG_IMAGE_VERSION;
        image.width = width;
        image.height = height;
        image.format = PNG_FORMAT_RGBA; // 8-bit, sRGB-encoded: libpng tags it sRGB
        png_alloc_size_t size = 0;
        std::string bytes;
        if (png_image_write_to_memory(&image, nullptr, &size, 0, rgba8.data(), 0, nullptr)) {
            bytes.resize(size);
            if (!png_image_write_to_memory(&image, bytes.data(), &size, 0, rgba8.data(), 0,
                                           nullptr))
                bytes.clear();
            bytes.resize(size);
        }
        if (bytes.empty()) set_error(error, fmt::format("libpng: {}", image.message));
        png_image_free(&image);
        return bytes;
    } catch (const std::exception& e) {
        set_error(error, e.what());
    }
    return {};
}

std::optional<ImageRGBA8> decode_png(std::string_view bytes, std::string* error) noexcept {
    try {
        png_image image;
        std::memset(&image, 0, sizeof image);
        image.version = PNG_IMAGE_VERSION;
        ImageRGBA8 out;
        if (png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
            image.format = PNG_FORMAT_RGBA;
            out.width = image.width;
            out.height = image.height;
            out.rgba.resize(PNG_IMAGE_SIZE(image));
            if (png_image_finish_read(&image, nullptr, out.rgba.data(), 0, nullptr)) return out;
        }
        set_error(error, fmt::format("libpng: {}", image.message));
        png_image_free(&image);
    } catch (const std::exception& e) {
        set_error(error, e.what());
    }
    return std::nullopt;
}

bool write_png(const fs::path& path, uint32_t width, uint32_t height,
               std::span<const uint8_t> rgba8, std::string* error) noexcept {
    constexpr const char* action = "cannot write PNG";
    return guarded(action, path, error, [&]() -> bool {
        std::string cause;
        const std::string bytes = encode_png(width, height, rgba8, &cause);
        if (cause.empty()) {
            cause = write_atomically(path, [&](std::FILE* f) -> std::string {
                if (std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size()) return {};
                return fmt::format("write failed: {}", errno_text(errno));
            });
        }
        if (!cause.empty()) {
            set_error(error, message(action, path, cause));
            return false;
        }
        return true;
    });
}

bool write_pfm(const fs::path& path, const ImageRGBA32F& image, std::string* error) noexcept {
    constexpr const char* action = "cannot write PFM";
    return guarded(action, path, error, [&]() -> bool {
        if (!image.well_formed() || image.pixel_count() == 0) {
            set_error(error, message(action, path,
                                     fmt::format("image is {}x{} with {} floats", image.width,
                                                 image.height, image.rgba.size())));
            return false;
        }
        const std::string cause = write_atomically(path, [&](std::FILE* f) -> std::string {
            const std::string header = fmt::format("PF\n{} {}\n-1.0\n", image.width, image.height);
            if (std::fwrite(header.data(), 1, header.size(), f) != header.size()) {
                return fmt::format("write failed: {}", errno_text(errno));
            }
            std::vector<unsigned char> row(std::size_t{image.width} * 12);
            // PFM stores the bottom row first.
            for (uint32_t y = image.height; y-- > 0;) {
                const float* src = &image.rgba[std::size_t{y} * image.width * 4];
                for (uint32_t x = 0; x < image.width; ++x) {
                    for (int c = 0; c < 3; ++c) {
                        put_u32_le(&row[x * 12 + c * 4], std::bit_cast<uint32_t>(src[x * 4 + c]));
                    }
                }
                if (std::fwrite(row.data(), 1, row.size(), f) != row.size()) {
                    return fmt::format("write failed: {}", errno_text(errno));
                }
            }
            return {};
        });
        if (!cause.empty()) {
            set_error(error, message(action, path, cause));
            return false;
        }
        return true;
    });
}

namespace {

struct PfmHeader {
    int channels = 3;
    uint32_t width = 0, height = 0;
    double scale = 0;            // negative: little-endian pixel data
    std::size_t data_offset = 0; // where the pixel data starts
};

// Header: magic, whitespace, width, whitespace, height, whitespace, scale, exactly one
// whitespace byte, then the pixel data, which must be exactly width x height pixels.
// Returns "" or what is wrong.
std::string parse_pfm_header(const std::vector<unsigned char>& bytes, PfmHeader& h) {
    if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != 'F' && bytes[1] != 'f'))
        return "not a PFM file (magic is not \"PF\" or \"Pf\")";
    h.channels = bytes[1] == 'F' ? 3 : 1;
    const char* const begin = reinterpret_cast<const char*>(bytes.data());
    const char* const end = begin + bytes.size();
    const char* p = begin + 2;
    auto skip_space = [&] {
        const char* start = p;
        while (p < end && is_pfm_space(static_cast<unsigned char>(*p)))
            ++p;
        return p != start;
    };
    // Each field must be preceded by whitespace and parse completely up to the next one.
    auto field = [&](auto& value) -> bool {
        const bool spaced = skip_space();
        const auto r = std::from_chars(p, end, value);
        if (!spaced || r.ec != std::errc{}) return false;
        p = r.ptr;
        return true;
    };
    if (!field(h.width)) return "bad width in header";
    if (!field(h.height)) return "bad height in header";
    if (!field(h.scale)) return "bad scale in header";
    if (!std::isfinite(h.scale) || h.scale == 0) return "scale must be finite and non-zero";
    if (p == end || !is_pfm_space(static_cast<unsigned char>(*p)))
        return "header does not end with a whitespace byte after the scale";
    ++p;
    if (h.width == 0 || h.height == 0) return fmt::format("empty image {}x{}", h.width, h.height);
    h.data_offset = static_cast<std::size_t>(p - begin);

    const auto data_bytes = static_cast<uint64_t>(end - p);
    const uint64_t pixel_bytes = uint64_t(h.channels) * 4;
    const uint64_t pixels = uint64_t{h.width} * h.height; // < 2^64, no overflow
    if (data_bytes % pixel_bytes != 0 || data_bytes / pixel_bytes != pixels)
        return fmt::format("{}x{} with {} channel(s) needs {} pixels x {} bytes of "
                           "pixel data, found {} bytes",
                           h.width, h.height, h.channels, pixels, pixel_bytes, data_bytes);
    return "";
}

ImageRGBA32F decode_pfm_pixels(const unsigned char* data, const PfmHeader& h) {
    const bool little_endian = h.scale < 0;
    const uint64_t pixel_bytes = uint64_t(h.channels) * 4;
    ImageRGBA32F image;
    image.width = h.width;
    image.height = h.height;
    image.rgba.resize(uint64_t{h.width} * h.height * 4);
    for (uint32_t row = 0; row < h.height; ++row) {
        const uint32_t y = h.height - 1 - row; // file row 0 is the bottom
        for (uint32_t x = 0; x < h.width; ++x) {
            const unsigned char* src = data + (uint64_t{row} * h.width + x) * pixel_bytes;
            float* dst = &image.rgba[(uint64_t{y} * h.width + x) * 4];
            for (int c = 0; c < 3; ++c) {
                const int sc = h.channels == 3 ? c : 0;
                dst[c] = std::bit_cast<float>(get_u32(src + sc * 4, little_endian));
            }
            dst[3] = 1.0f;
        }
    }
    return image;
}

} // namespace

std::optional<ImageRGBA32F> read_pfm(const fs::path& path, std::string* error) noexcept {
    constexpr const char* action = "cannot read PFM";
    return guarded(action, path, error, [&]() -> std::optional<ImageRGBA32F> {
        auto fail = [&](const std::string& cause) -> std::optional<ImageRGBA32F> {
            set_error(error, message(action, path, cause));
            return std::nullopt;
        };
        UniqueFile file(std::fopen(path.c_str(), "rb"));
        if (!file) return fail(errno_text(errno));
        std::vector<unsigned char> bytes;
        unsigned char chunk[1 << 16];
        std::size_t n = 0;
        while ((n = std::fread(chunk, 1, sizeof chunk, file.get())) > 0) {
            bytes.insert(bytes.end(), chunk, chunk + n);
        }
        if (std::ferror(file.get())) return fail(fmt::format("read failed: {}", errno_text(errno)));
        PfmHeader header;
        if (const std::string cause = parse_pfm_header(bytes, header); !cause.empty())
            return fail(cause);
        return decode_pfm_pixels(bytes.data() + header.data_offset, header);
    });
}

} // namespace watergen

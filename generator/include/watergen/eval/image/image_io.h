// Float images as the Vulkan runner reads them back, and the ways watergen stores them:
// PNG (tone-mapped sRGB, for people) and PFM (raw linear floats, for exact comparisons).
//
// Error handling: the file functions report failure through their return value plus an
// optional `std::string* error` (may be null) of the form "cannot write PNG '<path>': <cause>".
// Nothing here prints or exits, and the file functions never throw (they are noexcept; even
// std::bad_alloc becomes an error message).
//
// Writers are atomic with respect to readers: they write a temporary file in the target's
// directory and rename it over the target, so the target is either the old file or the
// complete new one; on failure the temporary file is removed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace watergen {

// Linear RGBA, 4 floats per pixel, rows top to bottom (row 0 = top), no padding.
struct ImageRGBA32F {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;

    std::size_t pixel_count() const noexcept { return std::size_t{width} * height; }
    // rgba holds exactly width * height * 4 floats.
    bool well_formed() const noexcept { return rgba.size() == pixel_count() * 4; }
};

// 8-bit RGBA, sRGB-encoded, 4 bytes per pixel, rows top to bottom, no padding.
struct ImageRGBA8 {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;

    std::size_t pixel_count() const noexcept { return std::size_t{width} * height; }
    bool well_formed() const noexcept { return rgba.size() == pixel_count() * 4; }
};

// The exact sRGB transfer functions of IEC 61966-2-1 (piecewise: linear segment of slope
// 12.92 up to 0.0031308 linear / 0.04045 encoded, then 1.055 * x^(1/2.4) - 0.055).
// Defined on [0, 1]; callers clamp.
double linear_to_srgb(double linear);
double srgb_to_linear(double encoded);

// Linear RGBA float -> RGBA8 sRGB, same size and row order as `image`.
// Operator (deliberately the simplest, so tests can predict it exactly):
//   1. c' = c * exposure          (per RGB channel, in double)
//   2. clamp c' to [0, 1]         (no tone curve: values above 1 clip to white)
//   3. encode with linear_to_srgb, then round to nearest: floor(v * 255 + 0.5)
// Alpha is ignored and written as 255.
// Marker: a pixel whose source RGB has any NaN or +-Inf (or whose exposed value is NaN) is
// written as opaque magenta (255, 0, 255, 255), so bad pixels stand out in a PNG.
// Returns an empty vector if `image` is not well_formed().
std::vector<uint8_t> tone_map_to_srgb8(const ImageRGBA32F& image, float exposure = 1.0f);

// 8-bit RGBA (sRGB, row 0 = top) as the bytes of a PNG file, encoded in memory by libpng.
// rgba8.size() must be width * height * 4 and both dimensions non-zero; otherwise, or if libpng
// fails, returns "" and sets *error (if non-null) to the cause.
std::string encode_png(uint32_t width, uint32_t height, std::span<const uint8_t> rgba8,
                       std::string* error) noexcept;

// The PNG file in `bytes` (any colour type and bit depth libpng reads) as 8-bit RGBA; nullopt and
// the cause in *error (if non-null) if it is not a PNG libpng can read.
std::optional<ImageRGBA8> decode_png(std::string_view bytes, std::string* error) noexcept;

// Writes encode_png's bytes to `path`.
bool write_png(const std::filesystem::path& path, uint32_t width, uint32_t height,
               std::span<const uint8_t> rgba8, std::string* error) noexcept;

// Portable Float Map: "PF\n<w> <h>\n-1.0\n" then 3 little-endian float32 per pixel, rows
// bottom to top as the format requires. Alpha is not stored. Values are written bit for bit,
// NaN and Inf included. The image must be well_formed() and non-empty.
bool write_pfm(const std::filesystem::path& path, const ImageRGBA32F& image,
               std::string* error) noexcept;

// Reads "PF" (RGB) and "Pf" (grey, copied to R, G and B) in either byte order (scale < 0:
// little-endian, > 0: big-endian; the scale's magnitude is ignored). Alpha is set to 1.
// The pixel data must be exactly width * height * channels * 4 bytes.
std::optional<ImageRGBA32F> read_pfm(const std::filesystem::path& path,
                                     std::string* error) noexcept;

} // namespace watergen

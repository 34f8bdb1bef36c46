// PNG and PFM writing/reading, including atomic writes and error reporting.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>

#include <png.h>

#include "watergen/eval/image/image_io.h"

using namespace watergen;
namespace fs = std::filesystem;

namespace {

// A fresh, empty directory under the test's working directory (the build tree), removed again
// at the end of the test case.
struct ScratchDir {
    fs::path path;
    explicit ScratchDir(const std::string& name) : path(fs::current_path() / ("scratch-" + name)) {
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(path))
            names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }
};

ImageRGBA32F sample_image(uint32_t w, uint32_t h) {
    ImageRGBA32F img{w, h, std::vector<float>(std::size_t{w} * h * 4)};
    for (std::size_t i = 0; i < img.rgba.size(); ++i) {
        // Irregular values, so a flipped or transposed read cannot match by accident.
        img.rgba[i] = (i % 4 == 3) ? 1.0f : static_cast<float>(std::sin(double(i) * 1.7) * 3.0);
    }
    return img;
}

// n bytes i * step + offset (mod 256): every value differs from its neighbours.
std::vector<uint8_t> byte_pattern(std::size_t n, unsigned step, unsigned offset) {
    std::vector<uint8_t> bytes(n);
    for (std::size_t i = 0; i < n; ++i)
        bytes[i] = static_cast<uint8_t>(i * step + offset);
    return bytes;
}

std::string read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary);
    out << bytes;
}

bool same_bits(float a, float b) {
    return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

} // namespace

TEST_CASE("PFM write then read round-trips RGB bit for bit, including NaN and Inf", "[unit][pfm]") {
    ScratchDir dir("pfm-roundtrip");
    ImageRGBA32F img = sample_image(7, 5);
    img.rgba[0] = std::numeric_limits<float>::quiet_NaN();
    img.rgba[5] = -std::numeric_limits<float>::infinity();
    img.rgba[9] = std::numeric_limits<float>::denorm_min();
    img.rgba[10] = -0.0f;
    const fs::path file = dir.path / "img.pfm";

    std::string error;
    REQUIRE(write_pfm(file, img, &error));
    CHECK(error.empty());
    CHECK(dir.entries() == std::vector<std::string>{"img.pfm"}); // no temporary left behind

    const auto back = read_pfm(file, &error);
    REQUIRE(back.has_value());
    REQUIRE(back->width == img.width);
    REQUIRE(back->height == img.height);
    REQUIRE(back->rgba.size() == img.rgba.size());
    for (std::size_t i = 0; i < img.rgba.size(); ++i) {
        INFO("float " << i);
        CHECK(same_bits(back->rgba[i], i % 4 == 3 ? 1.0f : img.rgba[i]));
    }
}

TEST_CASE("PFM file has the standard header and stores the bottom row first, little-endian",
          "[unit][pfm]") {
    ScratchDir dir("pfm-layout");
    // 1x2: top pixel (1, 2, 3), bottom pixel (4, 5, 6).
    const ImageRGBA32F img{1, 2, {1, 2, 3, 1, 4, 5, 6, 1}};
    const fs::path file = dir.path / "layout.pfm";
    REQUIRE(write_pfm(file, img, nullptr));

    const std::string bytes = read_bytes(file);
    const std::string header = "PF\n1 2\n-1.0\n";
    REQUIRE(bytes.size() == header.size() + 2 * 12);
    CHECK(bytes.substr(0, header.size()) == header);
    const float expected[] = {4, 5, 6, 1, 2, 3};
    for (int k = 0; k < 6; ++k) {
        const uint32_t bits = std::bit_cast<uint32_t>(expected[k]);
        for (int b = 0; b < 4; ++b) {
            CHECK(static_cast<unsigned char>(bytes[header.size() + k * 4 + b]) ==
                  ((bits >> (8 * b)) & 0xff));
        }
    }
}

TEST_CASE("read_pfm accepts big-endian greyscale Pf files", "[unit][pfm]") {
    ScratchDir dir("pfm-grey");
    const fs::path file = dir.path / "grey.pfm";
    std::string bytes = "Pf\n2 1\n1.0\n";
    for (float v : {0.5f, -2.0f}) {
        const uint32_t bits = std::bit_cast<uint32_t>(v);
        for (int b = 3; b >= 0; --b)
            bytes.push_back(static_cast<char>((bits >> (8 * b)) & 0xff));
    }
    write_bytes(file, bytes);
    const auto img = read_pfm(file, nullptr);
    REQUIRE(img.has_value());
    CHECK(img->rgba == std::vector<float>{0.5f, 0.5f, 0.5f, 1.0f, -2.0f, -2.0f, -2.0f, 1.0f});
}

TEST_CASE("read_pfm reports missing files, bad headers and truncated data with the path",
          "[unit][pfm]") {
    ScratchDir dir("pfm-errors");
    std::string error;
    CHECK_FALSE(read_pfm(dir.path / "missing.pfm", &error).has_value());
    CHECK(error.find("missing.pfm") != std::string::npos);
    CHECK(error.find("No such file") != std::string::npos);

    const fs::path file = dir.path / "bad.pfm";
    for (const std::string& bad :
         {std::string("P6\n1 1\n255\n..."), std::string("PF\n1 x\n-1\n"),
          std::string("PF\n1 1\n0\n123456789012"), std::string("PF\n2 2\n-1.0\n12345678901")}) {
        INFO(bad);
        write_bytes(file, bad);
        error.clear();
        CHECK_FALSE(read_pfm(file, &error).has_value());
        CHECK(error.find("bad.pfm") != std::string::npos);
    }
}

TEST_CASE("write_png produces a PNG that libpng reads back with the same size and pixels",
          "[unit][png]") {
    ScratchDir dir("png-write");
    const uint32_t w = 5, h = 3;
    const std::vector<uint8_t> rgba = byte_pattern(w * h * 4, 37, 11);
    const fs::path file = dir.path / "out.png";

    std::string error;
    REQUIRE(write_png(file, w, h, rgba, &error));
    CHECK(error.empty());
    CHECK(dir.entries() == std::vector<std::string>{"out.png"});

    png_image image;
    std::memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    REQUIRE(png_image_begin_read_from_file(&image, file.c_str()) != 0);
    CHECK(image.width == w);
    CHECK(image.height == h);
    image.format = PNG_FORMAT_RGBA;
    std::vector<uint8_t> back(PNG_IMAGE_SIZE(image));
    REQUIRE(png_image_finish_read(&image, nullptr, back.data(), 0, nullptr) != 0);
    CHECK(back == rgba);
}

TEST_CASE("encode_png bytes are the file write_png writes and decode to the same pixels",
          "[unit][png]") {
    ScratchDir dir("png-memory");
    const uint32_t w = 7, h = 4;
    const std::vector<uint8_t> rgba = byte_pattern(w * h * 4, 53, 3);
    std::string error;
    const std::string bytes = encode_png(w, h, rgba, &error);
    CHECK(error.empty());
    REQUIRE(bytes.size() > 8);
    CHECK(bytes.substr(0, 8) == "\x89PNG\r\n\x1a\n");
    REQUIRE(write_png(dir.path / "same.png", w, h, rgba, &error));
    CHECK(read_bytes(dir.path / "same.png") == bytes);

    // The test above reads write_png's file with libpng directly; these are its bytes.
    const std::optional<ImageRGBA8> decoded = decode_png(bytes, &error);
    REQUIRE(decoded);
    CHECK(decoded->width == w);
    CHECK(decoded->height == h);
    CHECK(decoded->rgba == rgba);
}

TEST_CASE("encode_png and decode_png report bad input instead of producing bytes", "[unit][png]") {
    std::string error;
    CHECK(encode_png(4, 4, std::vector<uint8_t>(10), &error).empty());
    CHECK(error == "4x4 RGBA8 needs 64 bytes, got 10");
    error.clear();
    CHECK(encode_png(0, 4, {}, &error).empty());
    CHECK(error == "0x4 RGBA8 needs 0 bytes, got 0");
    error.clear();
    CHECK_FALSE(decode_png("not a png at all", &error));
    CHECK(error.find("libpng") == 0);
    // A truncated file: the signature and part of the header only.
    const std::string bytes = encode_png(2, 2, std::vector<uint8_t>(16, 200), nullptr);
    error.clear();
    CHECK_FALSE(decode_png(std::string_view(bytes).substr(0, 20), &error));
    CHECK_FALSE(error.empty());
}

TEST_CASE("write_png of a tone-mapped image overwrites an existing file", "[unit][png]") {
    ScratchDir dir("png-overwrite");
    const fs::path file = dir.path / "img.png";
    write_bytes(file, "old contents");
    const ImageRGBA32F img = sample_image(4, 4);
    REQUIRE(write_png(file, img.width, img.height, tone_map_to_srgb8(img), nullptr));
    CHECK(read_bytes(file).substr(1, 3) == "PNG");
    CHECK(dir.entries() == std::vector<std::string>{"img.png"});
}

TEST_CASE("writing into a non-existent directory fails with the path and leaves no file",
          "[unit][png][pfm]") {
    ScratchDir dir("missing-dir");
    const fs::path missing = dir.path / "no-such-dir";
    const ImageRGBA32F img = sample_image(2, 2);

    std::string error;
    CHECK_FALSE(write_png(missing / "a.png", 2, 2, tone_map_to_srgb8(img), &error));
    CHECK(error.find((missing / "a.png").string()) != std::string::npos);
    CHECK(error.find("No such file or directory") != std::string::npos);
    error.clear();
    CHECK_FALSE(write_pfm(missing / "a.pfm", img, &error));
    CHECK(error.find((missing / "a.pfm").string()) != std::string::npos);
    CHECK_FALSE(fs::exists(missing));
    CHECK(dir.entries().empty());
}

TEST_CASE("a failed write leaves neither the target nor a temporary file", "[unit][png][pfm]") {
    ScratchDir dir("failed-write");
    std::string error;

    // Wrong buffer size: rejected before anything is created.
    CHECK_FALSE(write_png(dir.path / "short.png", 4, 4, std::vector<uint8_t>(10), &error));
    CHECK(error.find("short.png") != std::string::npos);
    CHECK_FALSE(write_pfm(dir.path / "empty.pfm", ImageRGBA32F{}, &error));

    // The target is a directory: the final rename fails and the temporary must be removed.
    fs::create_directory(dir.path / "target.pfm");
    error.clear();
    CHECK_FALSE(write_pfm(dir.path / "target.pfm", sample_image(2, 2), &error));
    CHECK(error.find("target.pfm") != std::string::npos);
    CHECK(dir.entries() == std::vector<std::string>{"target.pfm"});
    CHECK(fs::is_directory(dir.path / "target.pfm"));
}

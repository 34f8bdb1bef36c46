#include "watergen/eval/report/report_html.h"

#include <algorithm>

#include <fmt/core.h>

namespace watergen {

std::string base64_encode(std::string_view bytes) {
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 3 <= bytes.size(); i += 3) {
        const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 |
                           uint32_t(uint8_t(bytes[i + 1])) << 8 | uint32_t(uint8_t(bytes[i + 2]));
        out += kAlphabet[v >> 18];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += kAlphabet[v & 63];
    }
    const std::size_t rest = bytes.size() - i;
    if (rest > 0) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (rest == 2) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        out += kAlphabet[v >> 18];
        out += kAlphabet[(v >> 12) & 63];
        out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

std::string html_escape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        case '\'':
            out += "&#39;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

std::string png_data_uri(const ImageRGBA8& image) {
    const std::string png = encode_png(image.width, image.height, image.rgba, nullptr);
    if (png.empty()) return {};
    return "data:image/png;base64," + base64_encode(png);
}

std::string html_image(const ImageRGBA8& image, std::string_view alt, std::string_view css_class,
                       uint32_t display_width) {
    const uint32_t width = display_width ? display_width : image.width;
    const uint32_t height =
        image.width ? static_cast<uint32_t>(uint64_t{image.height} * width / image.width) : 0;
    return fmt::format(R"(<img src="{}" alt="{}" width="{}" height="{}"{}>)", png_data_uri(image),
                       html_escape(alt), width, height,
                       css_class.empty() ? std::string()
                                         : fmt::format(R"( class="{}")", css_class));
}

std::string html_figure(const ImageRGBA8& image, const std::string& caption) {
    constexpr uint32_t kMinimumDisplayWidth = 192;
    const uint32_t factor =
        image.width == 0 ? 1 : std::max(1u, (kMinimumDisplayWidth + image.width - 1) / image.width);
    return "<figure>" + html_image(image, caption, "pixelated", image.width * factor) +
           "<figcaption>" + html_escape(caption) + "</figcaption></figure>";
}

std::string html_color_bar(const HeatScale& scale) {
    std::string s = "<div class=\"bar\">" +
                    html_image(color_bar(scale, 256, 12), scale.label + " colour bar", "") +
                    "<div class=\"ticks\">";
    for (double t : scale.ticks)
        s += fmt::format(R"(<span style="left: {:.2f}%">{:g}</span>)",
                         100.0 * scale_position(scale, t), t);
    return s + "</div></div>";
}

} // namespace watergen

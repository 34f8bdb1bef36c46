// Small pieces of a self-contained HTML page: text escaping, base64 (RFC 4648) and images
// embedded as data URIs, so a report opens anywhere without a network or files beside it.
#pragma once

#include <string>
#include <string_view>

#include "watergen/eval/image/heat_map.h"
#include "watergen/eval/image/image_io.h"

namespace watergen {

// RFC 4648 section 4 base64 with '=' padding, no line breaks.
std::string base64_encode(std::string_view bytes);

// Escapes & < > " ' for use in HTML text and quoted attribute values.
std::string html_escape(std::string_view text);

// "data:image/png;base64,..." of encode_png(image); "" if the image cannot be encoded (empty).
std::string png_data_uri(const ImageRGBA8& image);

// An <img> of `image` embedded as a data URI, with alt text and its natural size; `css_class`
// may be empty. The "pixelated" class scales it without smoothing.
std::string html_image(const ImageRGBA8& image, std::string_view alt, std::string_view css_class,
                       uint32_t display_width = 0);

// A <figure> of `image` with `caption`, scaled up by a whole factor (pixelated) to at least
// 192 pixels wide, so small images and crops stay legible.
std::string html_figure(const ImageRGBA8& image, const std::string& caption);

// The colour bar of `scale` (256 pixels wide) with its ticks labelled (CSS class "bar").
std::string html_color_bar(const HeatScale& scale);

} // namespace watergen

#include "watergen/eval/report/caustics_report.h"

#include <cmath>

#include <fmt/core.h>

#include "watergen/eval/draw/caustics_pass_draw.h"
#include "watergen/eval/report/report_html.h"

namespace watergen {

namespace {

// |pass - reference| on [0, 0.5]: the area ratio's sharpest peaks differ by about that much
// from the reference's texel averages; larger differences clip.
HeatScale difference_scale() {
    return {"|pass - reference|", 0.0, 0.5, {0.0, 0.1, 0.25, 0.5}};
}

ImageRGBA8 difference_image(const CausticsPassFigures& p) {
    std::vector<float> d(p.pass.size());
    for (size_t i = 0; i < d.size() && i < p.reference.size(); ++i)
        d[i] = float(std::abs(p.pass[i] - p.reference[i]));
    return heat_map(d, p.texels, p.texels, difference_scale());
}

} // namespace

std::string caustics_passes_html(const std::vector<CausticsPassFigures>& passes,
                                 const std::string& note) {
    if (passes.empty()) return "";
    std::string s = "<section><h2>Caustics passes</h2>\n<p class=\"note\">" + html_escape(note) +
                    " Textures: " + html_escape(kCausticsToneMap) + ".</p>\n";
    s += "<table><tr><th class=\"key\">pass</th><th>texels</th><th>draw ms, median "
         "[min, max] of rounds</th><th>time / first pass [95% CI]</th><th>max abs</th>"
         "<th>RMSE</th><th>mean</th><th>reference mean</th><th>GLSL-HLSL</th></tr>\n";
    for (const CausticsPassFigures& p : passes)
        s += fmt::format("<tr><td class=\"key\">{}</td><td>{}</td><td>{:.3f} [{:.3f}, {:.3f}] "
                         "({} rounds)</td><td>{:.3f}&times; [{:.3f}, {:.3f}]</td><td>{:.4f}</td>"
                         "<td>{:.4f}</td><td>{:.4f}</td><td>{:.4f}</td><td>{:.3g}</td></tr>\n",
                         html_escape(p.name), p.texels, p.median_ms, p.min_ms, p.max_ms, p.rounds,
                         p.ratio, p.ratio_lo, p.ratio_hi, p.max_abs, p.rmse, p.mean,
                         p.reference_mean, p.glsl_vs_hlsl);
    s += "</table>\n";
    for (const CausticsPassFigures& p : passes)
        s += "<h3>" + html_escape(p.name) + "</h3>\n<div class=\"row\">" +
             html_figure(caustics_image(p.pass, p.texels), "pass: " + p.name) +
             html_figure(caustics_image(p.reference, p.texels), "CPU photon reference") +
             html_figure(difference_image(p), "|pass - reference|") + "</div>\n";
    return s + html_color_bar(difference_scale()) + "</section>\n";
}

nlohmann::ordered_json caustics_passes_json(const std::vector<CausticsPassFigures>& passes,
                                            const std::string& note) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const CausticsPassFigures& p : passes)
        list.push_back(
            {{"name", p.name},
             {"texels", p.texels},
             {"draw_ms",
              {{"median", p.median_ms},
               {"min", p.min_ms},
               {"max", p.max_ms},
               {"rounds", p.rounds}}},
             {"time_vs_first_pass", {{"ratio", p.ratio}, {"lo", p.ratio_lo}, {"hi", p.ratio_hi}}},
             {"vs_reference",
              {{"max_abs", p.max_abs}, {"rmse", p.rmse}, {"mean_difference", p.mean_difference}}},
             {"mean", p.mean},
             {"reference_mean", p.reference_mean},
             {"glsl_vs_hlsl_max_abs", p.glsl_vs_hlsl}});
    return {{"note", note}, {"tone_map", kCausticsToneMap}, {"passes", list}};
}

} // namespace watergen

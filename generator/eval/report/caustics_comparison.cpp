#include "watergen/eval/report/caustics_comparison.h"

#include <nlohmann/json.hpp>

#include "watergen/pipeline/output/output_writer.h"

namespace watergen {

namespace {

// The texture as a grey PNG (caustics_image's tone map).
std::string png(const std::vector<double>& intensity, uint32_t size, std::string* error) {
    const ImageRGBA8 image = caustics_image(intensity, size);
    return encode_png(size, size, image.rgba, error);
}

CausticsComparison failed(std::string error) {
    CausticsComparison out;
    out.error = std::move(error);
    out.status = RunStatus::Failed;
    return out;
}

// Draws one method; its figures and texture, or the failure in *error.
CausticsMethodFigures draw_method(VulkanRunner& runner, const CausticsComparisonSetup& setup,
                                  const CausticsPassBuild& build, std::vector<double>& texture,
                                  std::string* error) {
    const CausticsComparisonRequest& o = setup.request;
    CausticsMethodFigures out;
    out.method = build.pass.method;
    CausticsRenderSettings settings;
    settings.texels = o.size;
    settings.margin = setup.margin;
    settings.cells_per_texel = o.cells ? o.cells : default_cells_per_texel(out.method);
    settings.timed_draws = o.draws;
    auto values = caustics_values(build, setup.given);
    const CausticsRender r = render_caustics(runner, build, values, settings);
    if (!r.ok()) {
        *error = std::string(to_string(out.method)) + ": " + r.error;
        return out;
    }
    out.steady_ms = r.gpu[0].steady_draw_ms;
    texture = r.intensity[0];
    out.mean = out.mean_unclamped = mean_intensity(texture);
    out.glsl_vs_hlsl = r.glsl_vs_hlsl.max_abs;
    const CausticsError e = caustics_error(texture, setup.reference.intensity);
    out.max_abs = e.max_abs;
    out.rmse = e.rmse;
    if (out.method == CausticsMethod::AreaRatio) {
        values["caustics_clamp"] = {1e30};
        settings.timed_draws = 0;
        const CausticsRender u = render_caustics(runner, build, values, settings);
        if (!u.ok()) {
            *error = std::string(to_string(out.method)) + ": " + u.error;
            return out;
        }
        out.mean_unclamped = mean_intensity(u.intensity[0]);
    }
    return out;
}

nlohmann::ordered_json method_json(const CausticsMethodFigures& r) {
    return {{"method", to_string(r.method)},
            {"steady_draw_ms", r.steady_ms},
            {"mean", r.mean},
            {"mean_unclamped", r.mean_unclamped},
            {"clamp_lost", r.clamp_lost()},
            {"max_abs_vs_reference", r.max_abs},
            {"rmse_vs_reference", r.rmse},
            {"glsl_vs_hlsl", r.glsl_vs_hlsl}};
}

} // namespace

CausticsComparisonSetup prepare_caustics_comparison(const CausticsComparisonRequest& request) {
    CausticsComparisonSetup s;
    s.request = request;
    if (request.preset) s.given = request.preset->values;
    s.given["caustics_depth"] = {request.depth};
    s.given["caustics_clamp"] = {request.clamp};
    s.given["caustics_window"] = {-5, -5, 10};
    // Light drifts sideways by up to ~1.1 x depth (refraction of a low sun plus the waves'
    // slopes): the grid and the reference's photons reach that far beyond the window.
    s.margin = caustics_margin(request.depth);
    for (CausticsMethod m : {CausticsMethod::AreaRatio, CausticsMethod::PhotonSplat}) {
        if (request.method != "both" && request.method != to_string(m)) continue;
        s.builds.push_back(
            build_caustics_pass_files(preset_material(request.preset), {m, request.waves}));
        if (s.builds.back().ok()) continue;
        s.diagnostics = s.builds.back().diagnostics;
        s.status = RunStatus::Failed;
        return s;
    }
    // Both passes read the same wave, sun and window parameters with the same defaults.
    s.reference_setup = caustics_reference_setup(
        request.waves, caustics_values(s.builds.front(), s.given), request.size, s.margin);
    s.reference_setup.photons_per_side = 8;
    std::string error;
    s.reference = caustics_reference(s.reference_setup, &error);
    if (!error.empty()) {
        s.error = "reference: " + error;
        s.status = RunStatus::BadInput;
    }
    return s;
}

CausticsComparison run_caustics_comparison(VulkanRunner& runner,
                                           const CausticsComparisonSetup& setup) {
    const CausticsComparisonRequest& o = setup.request;
    CausticsComparison out;
    std::map<std::string, std::string> files;
    nlohmann::ordered_json methods = nlohmann::ordered_json::array();
    std::string error;
    for (const CausticsPassBuild& build : setup.builds) {
        std::vector<double> texture;
        out.methods.push_back(draw_method(runner, setup, build, texture, &error));
        if (!error.empty()) return failed(error);
        methods.push_back(method_json(out.methods.back()));
        files[std::string(to_string(build.pass.method)) + ".png"] = png(texture, o.size, &error);
        if (!error.empty()) return failed(error);
    }
    files["reference.png"] = png(setup.reference.intensity, o.size, &error);
    if (!error.empty()) return failed(error);
    const nlohmann::ordered_json doc = {{"waves", o.waves},
                                        {"depth", o.depth},
                                        {"clamp", o.clamp},
                                        {"texels", o.size},
                                        {"window", {-5, -5, 10}},
                                        {"reference_mean", setup.reference.mean()},
                                        {"device", runner.device_info().name},
                                        {"methods", methods}};
    files["caustics.json"] = doc.dump(2) + "\n";
    out.dir = o.out / ("caustics-" + o.waves);
    if (auto e = write_directory_atomically(out.dir, files)) return failed(*e);
    return out;
}

} // namespace watergen

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/eval/report/render_run.h"
#include "watergen/plan/binding_map_file.h"
#include "watergen/water/binding_profiles.h"

namespace watergen::cli {

namespace {

// ", world offset (x, y, z) m" for a moved scene, else "".
std::string offset_text(const RenderReportInfo& info) {
    const auto& o = info.world_offset;
    if (o[0] == 0 && o[1] == 0 && o[2] == 0) return "";
    return fmt::format(", world offset ({:g}, {:g}, {:g}) m", o[0], o[1], o[2]);
}

void print_render(const VariantRender& r, const RenderReportInfo& info, uint32_t draws,
                  const std::filesystem::path& dir) {
    const DeviceInfo& dev = info.device;
    std::printf("%s on %s (%s), %ux%u, view %s%s, Mesa shader cache %s\n", r.key.c_str(),
                dev.name.c_str(), dev.driver_info.c_str(), info.width, info.height,
                info.view.c_str(), offset_text(info).c_str(), info.shader_cache.c_str());
    std::printf("  %-5s pipeline %7.2f ms   first draw %8.2f ms   steady draw %7.3f ms (median "
                "of %u)\n",
                "glsl", r.gpu[0].pipeline_ms, r.gpu[0].first_draw_ms, r.gpu[0].steady_draw_ms,
                draws);
    std::printf("  %-5s pipeline %7.2f ms   first draw %8.2f ms   steady draw %7.3f ms (median "
                "of %u)\n",
                "hlsl", r.gpu[1].pipeline_ms, r.gpu[1].first_draw_ms, r.gpu[1].steady_draw_ms,
                draws);
    std::printf("  max abs: glsl-hlsl %.3g, gpu-cpu(float) %.3g, gpu-cpu(double) %.3g (over "
                "pixels finite on "
                "both sides)\n",
                r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs, r.glsl_vs_cpu_double.max_abs);
    std::printf("  NaN/Inf pixels: glsl %llu, hlsl %llu, cpu float %llu\n",
                static_cast<unsigned long long>(r.glsl_vs_cpu_float.nan_inf_pixels),
                static_cast<unsigned long long>(r.hlsl_vs_cpu_float.nan_inf_pixels),
                static_cast<unsigned long long>(r.glsl_vs_cpu_float.reference_nan_inf_pixels));
    std::printf("  wrote %s/{glsl,hlsl}.png, .pfm, cpu_float.pfm, float_bound.pfm, render.json\n",
                dir.string().c_str());
}

void print_caustics(const RenderCaustics& c, uint32_t draws, const std::filesystem::path& dir) {
    if (const auto& p = c.pass)
        std::printf("  caustics %s pass (%s waves), %ux%u texels, %g m deep: steady draw %.3f ms "
                    "(median of %u); vs the CPU photon reference (%u per texel): max abs %.4f, "
                    "RMSE %.4f, mean %.4f against %.4f; glsl-hlsl %.3g\n",
                    to_string(p->method), p->wave_model.c_str(), p->texels, p->texels,
                    kSceneCausticsDepth, p->glsl.steady_draw_ms, draws,
                    kSceneCausticsReferencePhotons * kSceneCausticsReferencePhotons,
                    p->vs_reference.max_abs, p->vs_reference.rmse, p->mean, p->reference_mean,
                    p->glsl_vs_hlsl);
    else
        std::printf("  caustics %s: the %ux%u tile (no pass)\n", c.choice.c_str(), c.texels,
                    c.texels);
    std::printf("  wrote %s/caustics.png (%s), bottom_lit.png\n", dir.string().c_str(),
                kCausticsToneMap);
}

void print_stats_line(const char* label, const ImageErrorStats& s) {
    std::printf("  %-22s max abs %10.3g   dE00 mean %7.4f   p99 %7.4f   NaN/Inf pixels %llu\n",
                label, s.max_abs, s.ciede2000_mean, s.ciede2000_p99,
                static_cast<unsigned long long>(s.nan_inf_pixels));
}

void print_half_render(const HalfRender& h, const RenderReportInfo& info,
                       const std::filesystem::path& dir) {
    const DeviceInfo& dev = info.device;
    std::printf("%s, strict half (16-bit arithmetic) on %s (%s), %ux%u, view %s%s\n", h.key.c_str(),
                dev.name.c_str(), dev.driver_info.c_str(), info.width, info.height,
                info.view.c_str(), offset_text(info).c_str());
    const char* names[2] = {"glsl", "hlsl"};
    for (int i = 0; i < 2; ++i)
        std::printf("  %-5s first draw %8.2f ms   steady draw %7.3f ms\n", names[i],
                    h.strict.gpu[i].first_draw_ms, h.strict.gpu[i].steady_draw_ms);
    std::printf("  %-5s first draw %8.2f ms   steady draw %7.3f ms (precision=full)\n", "glsl",
                h.full.gpu[0].first_draw_ms, h.full.gpu[0].steady_draw_ms);
    print_stats_line("glsl vs hlsl", h.strict.glsl_vs_hlsl);
    for (int i = 0; i < 2; ++i) {
        const HalfAgreement& u = h.ulps_vs_cpu_half[i];
        const double n = static_cast<double>(std::max<uint64_t>(u.values, 1));
        std::printf("  %s vs cpu half: %.2f%% of channels equal, %.2f%% within 1 ulp, max %lld "
                    "ulps at (%zu, %zu), max abs %.3g\n",
                    names[i], 100.0 * u.equal / n, 100.0 * u.within_1 / n,
                    static_cast<long long>(u.max_ulps), u.max_index % info.width,
                    u.max_index / info.width, h.vs_cpu_half[i].max_abs);
    }
    print_stats_line("glsl vs full precision", h.vs_full[0]);
    print_stats_line("hlsl vs full precision", h.vs_full[1]);
    print_stats_line("cpu half vs full", h.cpu_half_vs_full);
    std::printf("  wrote %s/{glsl,hlsl}.png, .pfm, cpu_half.pfm, full_precision.pfm, "
                "render.json\n",
                dir.string().c_str());
}

// kOk, or kFailed after saying how many pixels are NaN/Inf `where`.
int check_gpu_finite(const std::string& key, uint64_t broken, const char* where) {
    if (broken == 0) return kOk;
    std::fprintf(stderr, "watergen: error: %s: %llu pixel%s NaN/Inf %s\n", key.c_str(),
                 static_cast<unsigned long long>(broken), broken == 1 ? " is" : "s are", where);
    return kFailed;
}

// The worst pixel's line: where, how far apart, its bound, and the operation whose float
// rounding moves it most.
std::string worst_pixel_text(const RenderRun& run) {
    const Agreement& a = run.render.agreement[0];
    std::string text = fmt::format("({}, {}): |gpu - cpu float| {:.3g}, bound {:.3g}", a.worst.x,
                                   a.worst.y, a.worst_difference, a.worst_bound);
    if (run.worst && run.worst->ok() && !run.worst->effects.empty()) {
        const SiteEffect& e = run.worst->effects.front();
        text += fmt::format("; most from {} {}({}) ({:.3g} in double when rounded to float)",
                            e.what.origin, op_name(e.what.op), e.what.operands, e.change);
    }
    return text;
}

void print_agreement(const RenderRun& run) {
    if (run.render.against_surface) {
        const ImageErrorStats& e = run.render.glsl_vs_cpu_double;
        std::printf("  against the exact surface (the screen pass, its search converged, in "
                    "double): max abs %.3g, CIEDE2000 mean %.3g, p99 %.3g: the grid's geometric "
                    "error, no float bound\n",
                    e.max_abs, e.ciede2000_mean, e.ciede2000_p99);
        return;
    }
    const char* names[2] = {"glsl", "hlsl"};
    for (size_t i = 0; i < 2; ++i) {
        const Agreement& a = run.render.agreement[i];
        std::printf("  %s vs cpu float: %llu pixel%s over %.3g, %llu of them over it plus their "
                    "float error bound (largest bound %.3g)\n",
                    names[i], static_cast<unsigned long long>(a.over_tolerance),
                    a.over_tolerance == 1 ? "" : "s", a.tolerance,
                    static_cast<unsigned long long>(a.over_bound), a.max_bound);
    }
    if (run.render.agreement[0].over_tolerance > 0)
        std::printf("  worst pixel %s\n", worst_pixel_text(run).c_str());
}

// kOk, or kFailed after naming the pixels over the tolerance and their bound.
int check_agreement(const RenderRun& run) {
    const Agreement &g = run.render.agreement[0], &h = run.render.agreement[1];
    if (g.holds() && h.holds()) return kOk;
    std::fprintf(stderr,
                 "watergen: error: %s: %llu pixel%s differ from the CPU float image by more than "
                 "%.3g plus the float error expected there (glsl %llu, hlsl %llu); worst %s\n",
                 run.render.key.c_str(),
                 static_cast<unsigned long long>(std::max(g.over_bound, h.over_bound)),
                 std::max(g.over_bound, h.over_bound) == 1 ? "" : "s", g.tolerance,
                 static_cast<unsigned long long>(g.over_bound),
                 static_cast<unsigned long long>(h.over_bound), worst_pixel_text(run).c_str());
    return kFailed;
}

// "name=v[,v...]" into values; false after saying what is wrong.
bool parse_set(const std::string& item, std::map<std::string, std::vector<double>>& values) {
    const size_t eq = item.find('=');
    std::vector<double> value;
    bool ok = eq != std::string::npos && eq > 0 && eq + 1 < item.size();
    for (size_t at = eq + 1; ok && at <= item.size();) {
        size_t end = item.find(',', at);
        if (end == std::string::npos) end = item.size();
        const std::string number = item.substr(at, end - at);
        char* stop = nullptr;
        const double x = std::strtod(number.c_str(), &stop);
        ok = !number.empty() && stop == number.c_str() + number.size() && std::isfinite(x);
        value.push_back(x);
        at = end + 1;
    }
    if (!ok) {
        std::fprintf(stderr,
                     "watergen: error: --set '%s': expected name=value or name=v1,v2,... with "
                     "finite numbers\n",
                     item.c_str());
        return false;
    }
    values[item.substr(0, eq)] = std::move(value);
    return true;
}

// The largest |component| of --world-offset (m): 10,000 km, beyond the stability bench's
// farthest offset (1,000 km) and within float's range with room to spare.
constexpr double kMaxWorldOffset = 1e7;

// "X,Y,Z" into offset; false after saying what is wrong.
bool parse_world_offset(const std::string& text, std::array<double, 3>& offset) {
    std::vector<double> v;
    bool ok = !text.empty();
    for (size_t at = 0; ok && at <= text.size();) {
        size_t end = text.find(',', at);
        if (end == std::string::npos) end = text.size();
        const std::string number = text.substr(at, end - at);
        char* stop = nullptr;
        const double x = std::strtod(number.c_str(), &stop);
        ok = !number.empty() && stop == number.c_str() + number.size() && std::isfinite(x) &&
             std::abs(x) <= kMaxWorldOffset;
        v.push_back(x);
        at = end + 1;
    }
    if (!ok || v.size() != 3) {
        std::fprintf(stderr,
                     "watergen: error: --world-offset '%s': expected X,Y,Z, three finite numbers "
                     "in metres, each within [-1e7, 1e7]\n",
                     text.c_str());
        return false;
    }
    offset = {v[0], v[1], v[2]};
    return true;
}

struct RenderOptions {
    std::string world_offset;
    const CLI::Option* world_offset_flag = nullptr;
    std::vector<std::string> sets;
    std::string bindings;
    std::optional<BindingMap> map;
    RenderRequest request;
    std::string preset, out = "out/render";
    bool strict_half = false;
    RunnerSetup runner;
};

int run_strict_half(const RenderOptions& o, const Common& common) {
    if (o.request.variant.choice("precision") != "half") {
        std::fprintf(stderr, "watergen: error: --strict-half renders a precision=half variant; "
                             "add --precision half\n");
        return kUsage;
    }
    RenderRequest request = o.request;
    auto runner = create_runner(o.runner, &request.shader_cache);
    if (!runner) return kNoDevice;
    if (!has_float16(*runner, "; strict half needs it")) return kNoDevice;
    const HalfRenderRun run = run_strict_half_render(*runner, request);
    print_diagnostics(run.half.diagnostics, common);
    if (run.status != RunStatus::Ok) return stop({}, run.error, run.status, common);
    print_half_render(run.half, run.info, run.dir);
    return check_gpu_finite(run.half.key, run.gpu_only_non_finite,
                            "in 16-bit arithmetic on the GPU where the CPU half image is finite");
}

int run_render_command(const RenderOptions& o, const Common& common) {
    RenderRequest request = o.request;
    auto runner = create_runner(o.runner, &request.shader_cache);
    if (!runner) return kNoDevice;
    const RenderRun run = run_render(*runner, request);
    if (run.status != RunStatus::Ok) return stop(run.diagnostics, run.error, run.status, common);
    print_diagnostics(run.diagnostics, common);
    print_render(run.render, run.info, request.draws, run.dir);
    if (run.caustics) print_caustics(*run.caustics, request.draws, run.dir);
    print_agreement(run);
    if (const int rc = check_gpu_finite(run.render.key, run.gpu_only_non_finite,
                                        "on the GPU where the CPU float image is finite");
        rc != kOk)
        return rc;
    return check_agreement(run);
}
} // namespace

Runner add_render_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<RenderOptions>();
    RenderRequest& r = o->request;
    add_variant_options(app, r.variant, o->preset);
    app.add_option("--width", r.width, "image width in pixels (default 256)")
        ->check(CLI::Range(8, 4096));
    app.add_option("--height", r.height, "image height in pixels (default 256)")
        ->check(CLI::Range(8, 4096));
    app.add_option("--tolerance", r.tolerance,
                   "GPU against CPU float: the largest difference of a pixel beyond the float "
                   "error expected there (default 5e-5); a pixel over it fails the render")
        ->check(finite_range(0, 1e6));
    app.add_option("--draws", r.draws,
                   "timed draws after the first (JIT) draw; the median is reported (default 10)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--exposure", r.exposure,
                   "exposure applied before the sRGB PNG encoding (default 1)")
        ->check(finite_range(1e-6, 1e6));
    app.add_flag("--strict-half", o->strict_half,
                 "render a precision=half variant in 16-bit arithmetic (GLSL float16_t, HLSL "
                 "half) and compare it with the CPU half evaluator and with the variant at "
                 "precision=full");
    add_unroll_option(app, r.unroll);
    add_view_option(app, r.view);
    o->world_offset_flag = app.add_option(
        "--world-offset", o->world_offset,
        "X,Y,Z: move the whole synthetic scene, eye, seabed, spheres, water plane and "
        "depth buffer included, by this many metres (each within [-1e7, 1e7]; "
        "default 0,0,0), to see the water far from the world origin; a --set of a "
        "scene position (eye_position, water_level, caustics_window, "
        "fourier_map_origin) is relative to it: the offset is added");
    add_grid_options(app, r.grid);
    app.add_option("--set", o->sets,
                   "NAME=V[,V...]: a parameter's value for the GPU and the CPU alike, over the "
                   "preset's and the view's (repeatable); e.g. --scene_input depth_buffer --set "
                   "scene_depth_reversed=0 draws a standard-Z depth buffer");
    app.add_option("--bindings", o->bindings,
                   "where the variant binds its resources, as in watergen build: a profile (" +
                       binding_profile_list() +
                       ") or a binding map file; a map that pushes the parameter block draws "
                       "it as a push constant");
    app.add_option(
        "--out", o->out,
        "output directory; files go to <out>/<variant>/, or <out>/<variant>_view-<view>/ "
        "for a view other than beach (default out/render)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        if (!resolve_variant(o->request.variant, o->preset, &o->request.preset, common))
            return kUsage;
        o->request.out = o->out;
        if (!check_grid(o->request.grid)) return kUsage;
        if (o->world_offset_flag->count() > 0 &&
            !parse_world_offset(o->world_offset, o->request.world_offset))
            return kUsage;
        for (const std::string& item : o->sets)
            if (!parse_set(item, o->request.values)) return kUsage;
        if (!o->bindings.empty()) {
            Diagnostics ds;
            o->map = load_binding_map(o->bindings, ds);
            print_diagnostics(ds, common);
            if (!o->map) return kUsage;
            o->request.bindings = &*o->map;
        }
        if (o->strict_half && !o->sets.empty()) {
            std::fprintf(stderr, "watergen: error: --strict-half draws the view's values; "
                                 "leave out --set\n");
            return kUsage;
        }
        if (o->strict_half && o->request.unroll != LoopUnroll::AsHinted) {
            std::fprintf(stderr, "watergen: error: --strict-half renders with each loop's own "
                                 "unroll hint; leave out --unroll\n");
            return kUsage;
        }
        return o->strict_half ? run_strict_half(*o, common) : run_render_command(*o, common);
    };
}

} // namespace watergen::cli

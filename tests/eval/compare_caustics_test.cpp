// `watergen compare` of caustics variants (render/compare_caustics.h): each variant renders over
// its own pass's map, and the report's "Caustics passes" figures are those of the pass drawn
// directly for the same view.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "compare_report_support.h"
#include "shared_runner.h"
#include "watergen/eval/compare/compare_caustics.h"
#include "watergen/eval/compare/compare_run.h"
#include "watergen/eval/draw/variant_render.h"

using namespace watergen;
using namespace watergen::test;

TEST_CASE("compare_reports_the_caustics_pass_its_variants_read", "[render][caustics]") {
    std::vector<Variant> variants(2, default_variant());
    REQUIRE_FALSE(set_choice(variants[0], "waves", "gerstner"));
    variants[1] = variants[0];
    REQUIRE_FALSE(set_choice(variants[1], "caustics", "area_ratio"));
    CompareRequest request;
    request.variants = variants;
    request.views = {{"beach", make_synthetic_scene(32, 32)}};
    request.rounds = 3;
    request.draws = 1;
    CompareCaustics caustics(shared_runner(), request.views);
    request.textures_for = [&](const VariantBuild& water, size_t view, std::string* error) {
        return caustics.textures_for(water, view, error);
    };
    const CompareRun run = run_compare(shared_runner(), request);
    INFO(run.error);
    REQUIRE(run.ok());
    RatioInterval aa;
    std::string error;
    const auto passes = caustics.time(3, 1, &aa, &error);
    INFO(error);
    REQUIRE(error.empty());
    REQUIRE(passes.size() == 1); // caustics=none reads no pass
    const ComparedCausticsPass& c = passes[0];
    CHECK(c.name == "area_ratio, gerstner waves");
    CHECK(c.round_ms.size() == 3);
    CHECK(c.min_ms > 0);
    CHECK(c.min_ms <= c.median_ms);
    CHECK(c.median_ms <= c.max_ms);
    CHECK(c.vs_first_pass.ratio == 1);

    // Drawn directly for the same view: the same texture and error figures (lavapipe is
    // deterministic), and the variant's image is its render over that texture.
    const SceneCausticsPass direct = draw_scene_caustics_pass(
        shared_runner(),
        build_caustics_pass_files(Material{}, {CausticsMethod::AreaRatio, "gerstner"}),
        request.views[0].second, 64, 0);
    REQUIRE(direct.ok());
    CHECK(c.first.intensity == direct.intensity);
    CHECK(c.first.vs_reference.rmse == direct.vs_reference.rmse);
    CHECK(c.first.vs_reference.max_abs == direct.vs_reference.max_abs);
    SyntheticScene scene = request.views[0].second;
    use_caustics_pass(scene, direct);
    const VariantRender own = render_variant(shared_runner(), build_variant(variants[1], nullptr),
                                             scene, {32, 32, 0, false, false});
    REQUIRE(own.ok());
    REQUIRE(run.entries.size() == 2);
    CHECK(run.entries[1].views[0].image.rgba == own.gpu_image[0].rgba);
    CHECK(run.entries[0].views[0].image.rgba != own.gpu_image[0].rgba);

    // The report carries the figures: the section in the HTML, the values in compare.json.
    CompareReport report = synthetic_compare_report();
    report.caustics_passes = caustics_pass_figures(passes);
    report.caustics_note = "timed interleaved";
    const auto files = compare_report_files(report, &error);
    REQUIRE(files);
    const std::string& html = files->at(kCompareReportHtml);
    CHECK(count_occurrences(html, "<h2>Caustics passes</h2>") == 1);
    CHECK(count_occurrences(html, "alt=\"CPU photon reference\"") == 1);
    const auto json = nlohmann::json::parse(files->at(kCompareJson));
    const auto& p = json.at("caustics_passes").at("passes").at(0);
    CHECK(p.at("name") == "area_ratio, gerstner waves");
    CHECK(p.at("texels") == 64);
    CHECK(p.at("vs_reference").at("rmse").get<double>() == direct.vs_reference.rmse);
    CHECK(p.at("vs_reference").at("max_abs").get<double>() == direct.vs_reference.max_abs);
    CHECK(p.at("draw_ms").at("median").get<double>() == c.median_ms);
    CHECK(p.at("draw_ms").at("rounds") == 3);
    CHECK(p.at("glsl_vs_hlsl_max_abs").get<double>() == 0);
    // Without passes neither appears.
    const auto plain = compare_report_files(synthetic_compare_report(), &error);
    REQUIRE(plain);
    CHECK(plain->at(kCompareReportHtml).find("Caustics passes") == std::string::npos);
    CHECK(plain->at(kCompareJson).find("caustics_passes") == std::string::npos);
}

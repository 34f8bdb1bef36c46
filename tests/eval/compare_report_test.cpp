// The comparison report's files from a made-up comparison: self-contained HTML, the CSV and JSON
// tables with the figures of compute_error_maps, atomic writing, and its pieces (base64, escaping).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "compare_report_support.h"
#include "watergen/eval/report/compare_table.h"
#include "watergen/eval/report/report_html.h"

using namespace watergen;
namespace fs = std::filesystem;

namespace {

// RFC 4648 decoding, written independently of the encoder under test.
std::string base64_decode(const std::string& text) {
    const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    uint32_t bits = 0;
    int count_bits = 0;
    for (char c : text) {
        if (c == '=') break;
        bits = (bits << 6) | uint32_t(alphabet.find(c));
        count_bits += 6;
        if (count_bits >= 8) {
            count_bits -= 8;
            out += char((bits >> count_bits) & 0xff);
        }
    }
    return out;
}

} // namespace

TEST_CASE("base64_matches_the_rfc_4648_test_vectors", "[unit][report]") {
    CHECK(base64_encode("") == "");
    CHECK(base64_encode("f") == "Zg==");
    CHECK(base64_encode("fo") == "Zm8=");
    CHECK(base64_encode("foo") == "Zm9v");
    CHECK(base64_encode("foob") == "Zm9vYg==");
    CHECK(base64_encode("fooba") == "Zm9vYmE=");
    CHECK(base64_encode("foobar") == "Zm9vYmFy");
    CHECK(base64_encode(std::string("\xff\x00\xfe", 3)) == "/wD+");
    CHECK(html_escape(R"(<a href="x">Tom & Jerry's</a>)") ==
          "&lt;a href=&quot;x&quot;&gt;Tom &amp; Jerry&#39;s&lt;/a&gt;");
}

TEST_CASE("the_report_html_is_self_contained_and_embeds_decodable_images", "[unit][report]") {
    const CompareReport report = test::synthetic_compare_report();
    std::string error;
    const auto files = compare_report_files(report, &error);
    REQUIRE(files);
    CHECK(error.empty());
    REQUIRE(files->size() == 3);
    const std::string& html = files->at(kCompareReportHtml);
    CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
    CHECK(html.find("http") == std::string::npos); // no external URL, not even a namespace
    CHECK(html.find("<script") == std::string::npos);
    CHECK(html.find("<link") == std::string::npos);
    CHECK(html.find("Synthetic comparison &lt;fresnel &amp; foam&gt;") != std::string::npos);
    // Per view: reference + 3 variants, 3 dE00 + 3 FLIP maps, 2 colour bars, 3 x 3 crops.
    const std::size_t per_view = 4 + 3 + 3 + 2 + 9;
    const std::regex uri_re("data:image/png;base64,([A-Za-z0-9+/=]+)\"");
    std::size_t images = 0;
    for (std::sregex_iterator it(html.begin(), html.end(), uri_re), end; it != end; ++it) {
        std::string why;
        const auto png = decode_png(base64_decode((*it)[1]), &why);
        INFO(why);
        CHECK(png);
        ++images;
    }
    CHECK(images == 2 * per_view);
    // Plots: all variants, by fresnel, by foam.
    CHECK(test::count_occurrences(html, "<svg ") == 3);
    CHECK(html.find(">by fresnel<") != std::string::npos);
    CHECK(html.find(">by foam<") != std::string::npos);
    CHECK(html.find("View: grazing") != std::string::npos);
    CHECK(html.find("1.200&times; [1.164, 1.236]") != std::string::npos);
    CHECK(html.find("(untrusted)") == std::string::npos);
}

TEST_CASE("the_csv_and_json_tables_carry_the_error_figures", "[unit][report]") {
    CompareReport report = test::synthetic_compare_report();
    report.variants[1].cost = 0;               // not measured
    report.variants[3].spirv_instructions = 0; // unknown
    const auto files = compare_report_files(report, nullptr);
    REQUIRE(files);
    const ErrorMaps sprites_grazing = compute_error_maps(
        report.variants[2].views[1].image, report.views[1].reference, report.exposure);
    const ErrorMaps sprites_overview = compute_error_maps(
        report.variants[2].views[0].image, report.views[0].reference, report.exposure);

    const nlohmann::json j = nlohmann::json::parse(files->at(kCompareJson));
    REQUIRE(j["variants"].size() == 4);
    const auto& sprites = j["variants"][2];
    CHECK(sprites["key"] == "fresnel=exact,foam=sprites");
    CHECK(sprites["relation"] == "different model");
    CHECK(sprites["choices"]["foam"] == "sprites");
    CHECK(sprites["views"][1]["nan_inf_pixels"] == 1);
    CHECK(sprites["summary"]["nan_inf_pixels"] == 1);
    CHECK(sprites["views"][1]["ciede2000_p99"].get<double>() ==
          sprites_grazing.stats.ciede2000_p99);
    CHECK(sprites["summary"]["ciede2000_p99"].get<double>() ==
          std::max(sprites_grazing.stats.ciede2000_p99, sprites_overview.stats.ciede2000_p99));
    CHECK(sprites["views"][0]["flip_mean"].get<double>() == sprites_overview.flip.mean);
    CHECK(sprites["views"][0]["share_above_jnd"].get<double>() == sprites_overview.share_above_jnd);
    CHECK(sprites["views"][0]["worst_region"]["width"] == 8);
    CHECK(sprites["time_ratio"]["ratio"] == 1.2);
    CHECK(j["variants"][0]["summary"]["ciede2000_p99"] == 0.0); // the reference against itself
    CHECK(j["variants"][1]["cost_per_pixel"].is_null());
    CHECK(j["variants"][3]["spirv_instructions"].is_null());
    CHECK(j["timing"]["trustworthy"] == true);

    const std::string& csv = files->at(kCompareCsv);
    CHECK(test::count_occurrences(csv, "\r\n") == 1 + 4 * 2);
    CHECK(csv.rfind("variant,view,reference,relation,choices,time_ratio,", 0) == 0);
    CHECK(csv.find("\"fresnel=exact,foam=sprites\",grazing,false,different model,"
                   "foam=sprites;fresnel=exact,1.2,") != std::string::npos);
    // The unmeasured cost is an empty cell.
    const CompareVariant& schlick = report.variants[1];
    CHECK(csv.find(fmt::format(",{},{},{},true,,800,", schlick.time_ratio, schlick.time_ratio_lo,
                               schlick.time_ratio_hi)) != std::string::npos);
}

TEST_CASE("untrusted_timing_is_marked_in_the_html", "[unit][report]") {
    CompareReport report = test::synthetic_compare_report();
    report.timing_trustworthy = false;
    const auto files = compare_report_files(report, nullptr);
    REQUIRE(files);
    const std::string& html = files->at(kCompareReportHtml);
    CHECK(test::count_occurrences(html, "(untrusted)") == 4);
    CHECK(html.find("<p class=\"warning\">Timing: median of 5 runs") != std::string::npos);
}

TEST_CASE("an_inconsistent_report_is_refused_with_the_reason", "[unit][report]") {
    CompareReport report = test::synthetic_compare_report();
    report.variants[1].views.pop_back();
    std::string error;
    CHECK_FALSE(compare_report_files(report, &error));
    CHECK(error == "variant 'fresnel=schlick,foam=none' has 1 view results for 2 views");
    report = test::synthetic_compare_report();
    report.variants[2].views[0].image.width = 32;
    CHECK_FALSE(compare_report_files(report, &error));
    CHECK(error == "variant 'fresnel=exact,foam=sprites', view 'overview': image is 32x64, the "
                   "reference 64x64");
    report.views.clear();
    CHECK_FALSE(compare_report_files(report, &error));
    CHECK(error == "the comparison has no view");
    report = test::synthetic_compare_report();
    test::add_synthetic_caustics_pass(report);
    report.caustics_passes[0].reference.pop_back();
    CHECK_FALSE(compare_report_files(report, &error));
    CHECK(error == "caustics pass 'area_ratio, gerstner waves': 4096 and 4095 texels for a 64x64 "
                   "texture");
}

TEST_CASE("write_compare_report_replaces_the_directory_whole_or_not_at_all", "[unit][report]") {
    const fs::path dir = fs::current_path() / "scratch-compare-report";
    fs::remove_all(dir);
    fs::create_directories(dir);
    { std::ofstream(dir / "stale.txt") << "from an earlier run"; }
    const CompareReport report = test::synthetic_compare_report(32);
    REQUIRE_FALSE(write_compare_report(dir, report, {{"notes/extra.txt", "more"}}));
    CHECK(fs::exists(dir / kCompareReportHtml));
    CHECK(fs::exists(dir / kCompareCsv));
    CHECK(fs::exists(dir / kCompareJson));
    CHECK(test::read_file_text(dir / "notes/extra.txt") == "more");
    CHECK_FALSE(fs::exists(dir / "stale.txt"));
    const std::string html = test::read_file_text(dir / kCompareReportHtml);

    // A failing write (an extra file named like a report file) leaves the directory as it was.
    const auto error = write_compare_report(dir, report, {{kCompareCsv, "clash"}});
    REQUIRE(error);
    CHECK(*error == "extra file 'compare.csv' has the name of a report file");
    CHECK(test::read_file_text(dir / kCompareReportHtml) == html);
    for (const auto& e : fs::directory_iterator(dir.parent_path()))
        CHECK(e.path().filename().string().find("scratch-compare-report.") == std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("a_streamed_report_is_the_report_made_from_kept_images", "[unit][report]") {
    // compare streams: each image becomes its figures (spooled to disk) and error figures as it
    // is rendered and is dropped. The files come out byte for byte as from the kept images.
    const CompareReport kept = test::synthetic_compare_report(32);
    CompareReport streamed = kept;
    streamed.spool = std::make_shared<FigureSpool>();
    REQUIRE(streamed.spool->ok());
    for (std::size_t i = 0; i < kept.views.size(); ++i) {
        streamed.views[i].reference = {};
        streamed.views[i].reference_figure = reference_figure(kept, kept.views[i].reference);
    }
    for (std::size_t v = 0; v < kept.variants.size(); ++v)
        for (std::size_t i = 0; i < kept.views.size(); ++i)
            streamed.variants[v].views[i] = figured_view_result(
                streamed, v, kept.variants[v].views[i].image, kept.views[i].reference);
    for (const CompareVariant& v : streamed.variants)
        for (const CompareViewResult& r : v.views) {
            CHECK(r.image.rgba.empty());
            REQUIRE(r.errors);
            CHECK(r.errors->ciede2000.empty()); // the per-pixel maps are not kept
            CHECK(r.errors->flip.values.empty());
            REQUIRE(r.figures);
            CHECK(r.figures->spooled.has_value()); // on disk, not in memory
            CHECK(r.figures->image.empty());
        }
    const fs::path a = fs::current_path() / "scratch-report-kept";
    const fs::path b = fs::current_path() / "scratch-report-streamed";
    fs::remove_all(a);
    fs::remove_all(b);
    REQUIRE_FALSE(write_compare_report(a, kept));
    REQUIRE_FALSE(write_compare_report(b, streamed));
    for (const char* name : {kCompareReportHtml, kCompareCsv, kCompareJson})
        CHECK(test::read_file_text(a / name) == test::read_file_text(b / name));
    const auto files = compare_report_files(kept, nullptr);
    REQUIRE(files);
    CHECK(files->at(kCompareReportHtml) == test::read_file_text(b / kCompareReportHtml));
    fs::remove_all(a);
    fs::remove_all(b);
}

TEST_CASE("the_float_bound_of_a_cpu_reference_is_in_the_csv_and_the_html", "[unit][report]") {
    CompareReport report = test::synthetic_compare_report();
    // Without a CPU reference the columns are empty in the CSV and absent from the HTML.
    auto files = compare_report_files(report, nullptr);
    REQUIRE(files);
    CHECK(files->at(kCompareCsv).find(",pixels_beyond_float_bound,float_bound_max\r\n") !=
          std::string::npos);
    CHECK(test::count_occurrences(files->at(kCompareCsv), ",,\r\n") == 4 * 2);
    CHECK(files->at(kCompareReportHtml).find("px beyond float bound") == std::string::npos);

    for (CompareVariant& v : report.variants)
        for (CompareViewResult& r : v.views) {
            r.beyond_float_bound = v.choices["foam"] == "sprites" ? 81 : 0;
            r.float_bound_max = 2.5e-6;
        }
    files = compare_report_files(report, nullptr);
    REQUIRE(files);
    const std::string& csv = files->at(kCompareCsv);
    // The last two cells of each row: 4 variants x 2 views.
    CHECK(test::count_occurrences(csv, ",0,2.5e-06\r\n") == 4);
    CHECK(test::count_occurrences(csv, ",81,2.5e-06\r\n") == 4);
    const std::string& html = files->at(kCompareReportHtml);
    CHECK(test::count_occurrences(html, "<th>px beyond float bound</th>") == 2); // one per view
    CHECK(test::count_occurrences(html, "<td>81</td><td>2.5e-06</td>") == 4);
    const nlohmann::json j = nlohmann::json::parse(files->at(kCompareJson));
    CHECK(j["variants"][2]["views"][0]["pixels_beyond_float_bound"] == 81);
}

TEST_CASE("each_cost_target_gets_a_column_and_a_front_and_their_disagreements_are_marked",
          "[unit][report]") {
    CompareReport report = test::synthetic_compare_report();
    // lavapipe: schlick (100) is cheaper than the reference (120), on its front; rdna2: the
    // reference (80) is cheaper than schlick (90) and exact, so schlick is dominated there.
    report.cost_targets = {"rdna2"};
    const double rdna2[] = {80, 90, 150, 130};
    for (size_t v = 0; v < 4; ++v)
        report.variants[v].target_costs["rdna2"] = rdna2[v];
    const auto files = compare_report_files(report, nullptr);
    REQUIRE(files);
    const std::string& csv = files->at(kCompareCsv);
    CHECK(
        csv.find(",float_bound_max,cost_rdna2,pareto_lavapipe,pareto_rdna2,targets_disagree\r\n") !=
        std::string::npos);
    // Per view: the reference on both fronts, schlick on lavapipe's only, the others on none.
    CHECK(test::count_occurrences(csv, ",80,true,true,false\r\n") == 2);
    CHECK(test::count_occurrences(csv, ",90,true,false,true\r\n") == 2);
    CHECK(test::count_occurrences(csv, ",150,false,false,false\r\n") == 2);
    CHECK(test::count_occurrences(csv, ",130,false,false,false\r\n") == 2);
    const std::string& html = files->at(kCompareReportHtml);
    CHECK(test::count_occurrences(html, "<th>rdna2 (ACO instr/px)</th>") == 1);
    CHECK(test::count_occurrences(html, "on the front of lavapipe; dominated on rdna2") == 1);
    CHECK(test::count_occurrences(html, "<h2>Cost on each target</h2>") == 1);
    CHECK(html.find("The targets disagree") != std::string::npos);
    CHECK(test::count_occurrences(html, "cost on rdna2") == 1); // the target's plot
    const nlohmann::json j = nlohmann::json::parse(files->at(kCompareJson));
    CHECK(j["cost_targets"] == nlohmann::json::array({"rdna2"}));
    CHECK(j["variants"][1]["target_costs"]["rdna2"] == 90);
    CHECK(j["variants"][1]["pareto_fronts"]["lavapipe"] == true);
    CHECK(j["variants"][1]["pareto_fronts"]["rdna2"] == false);
    CHECK(j["variants"][1]["targets_disagree"] == true);
    CHECK(j["variants"][0]["targets_disagree"] == false);
}

TEST_CASE("without_targets_the_tables_keep_their_columns", "[unit][report]") {
    const auto files = compare_report_files(test::synthetic_compare_report(), nullptr);
    REQUIRE(files);
    CHECK(files->at(kCompareCsv).find("cost_rdna2") == std::string::npos);
    CHECK(files->at(kCompareReportHtml).find("Cost on each target") == std::string::npos);
    CHECK_FALSE(nlohmann::json::parse(files->at(kCompareJson)).contains("cost_targets"));
}

#include <catch2/catch.hpp>

#include <algorithm>
#include <thread>

#include "watergen/ir/emit/vertex_emitter.h"
#include "watergen/pipeline/variant/stage_memo.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/runtime/reflection.h"

using namespace watergen;

namespace {

const std::string kKeyA = default_variant().key();
std::string other_key() {
    Variant v = default_variant();
    v.choices[0] = v.choices[0] == "schlick" ? "exact" : "schlick";
    return v.key();
}

CompileRequest vertex_request(Language lang, const std::string& key) {
    return stage_request(emit_fullscreen_vertex(lang, "glsl/water.vert.glsl", key));
}

size_t lines(const std::string& s) {
    return static_cast<size_t>(std::count(s.begin(), s.end(), '\n'));
}

// Everything a build writes from a stage's outputs, and what it reports.
void check_same(const ToolchainOutputs& a, const ToolchainOutputs& b) {
    CHECK(a.ok());
    CHECK(a.spirv == b.spirv);
    CHECK(a.spirv_optimized == b.spirv_optimized);
    CHECK(a.glsl330 == b.glsl330);
    CHECK(a.essl300 == b.essl300);
    CHECK(a.msl == b.msl);
    CHECK(reflection_to_json(a.reflection) == reflection_to_json(b.reflection));
    CHECK(a.diagnostics.size() == b.diagnostics.size());
    CHECK(a.cross_compiled == b.cross_compiled);
}

} // namespace

TEST_CASE("a_blank_stamp_keeps_every_line_where_it_was", "[memo]") {
    const std::string source = vertex_request(Language::Glsl, kKeyA).source;
    REQUIRE(source.find(kKeyA) != std::string::npos);
    const std::string blank = blank_stamp(source, kKeyA);
    CHECK(blank.find(kKeyA) == std::string::npos);
    CHECK(blank.find(stamp_text("")) != std::string::npos);
    CHECK(lines(blank) == lines(source));
    CHECK(blank == vertex_request(Language::Glsl, "").source);
    CHECK(blank_stamp(source, "") == source);          // no key: nothing to blank
    CHECK(blank_stamp(source, other_key()) == source); // another variant's stamp is not there
}

TEST_CASE("stages_that_differ_only_in_their_stamp_have_one_key", "[memo]") {
    const std::string b = other_key();
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        CHECK(stage_key(vertex_request(lang, kKeyA), CrossCompile::Yes, kKeyA) ==
              stage_key(vertex_request(lang, b), CrossCompile::Yes, b));
        // How far the chain runs is part of the key: the outputs differ.
        CHECK(stage_key(vertex_request(lang, kKeyA), CrossCompile::Yes, kKeyA) !=
              stage_key(vertex_request(lang, kKeyA), CrossCompile::No, kKeyA));
    }
    CHECK(stage_key(vertex_request(Language::Glsl, kKeyA), CrossCompile::Yes, kKeyA) !=
          stage_key(vertex_request(Language::Hlsl, kKeyA), CrossCompile::Yes, kKeyA));
    // Fragments of different variants are different programs.
    const VariantBuild fa = build_variant(default_variant());
    Variant vb = default_variant();
    vb.choices[0] = vb.choices[0] == "schlick" ? "exact" : "schlick";
    const VariantBuild fb = build_variant(vb);
    REQUIRE(fa.ok());
    REQUIRE(fb.ok());
    CHECK(stage_key(stage_request(fa.languages[0].fragment.source), CrossCompile::Yes, kKeyA) !=
          stage_key(stage_request(fb.languages[0].fragment.source), CrossCompile::Yes, b));
}

// What the memo rests on: no compiler output depends on the stamp comment.
TEST_CASE("a_stage_compiled_once_serves_every_variant_that_expects_it", "[memo]") {
    const std::string b = other_key();
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        const CompileRequest ra = vertex_request(lang, kKeyA), rb = vertex_request(lang, b);
        const ToolchainOutputs alone = run_toolchain(ra);
        StageMemo memo;
        memo.expect({stage_key(ra, CrossCompile::Yes, kKeyA), stage_key(rb, CrossCompile::Yes, b)});
        const ToolchainOutputs first = memo.run(ra, CrossCompile::Yes, kKeyA);
        const ToolchainOutputs second = memo.run(rb, CrossCompile::Yes, b);
        check_same(first, alone);
        check_same(second, alone);
        CHECK(memo.counts().compiled == 1);
        CHECK(memo.counts().reused == 1);
        // Its last expected use took it: a third asks the toolchain again.
        const ToolchainOutputs third = memo.run(ra, CrossCompile::Yes, kKeyA);
        check_same(third, alone);
        CHECK(memo.counts().compiled == 2);
    }
}

TEST_CASE("a_stage_nobody_else_expects_or_past_the_budget_is_compiled_each_time", "[memo]") {
    const CompileRequest r = vertex_request(Language::Glsl, kKeyA);
    const StageKey key = stage_key(r, CrossCompile::Yes, kKeyA);
    StageMemo unplanned;
    unplanned.run(r, CrossCompile::Yes, kKeyA);
    unplanned.run(r, CrossCompile::Yes, kKeyA);
    CHECK(unplanned.counts().compiled == 2);
    CHECK(unplanned.counts().reused == 0);

    StageMemo tiny(0); // keeps nothing
    tiny.expect({key, key});
    const ToolchainOutputs a = tiny.run(r, CrossCompile::Yes, kKeyA);
    const ToolchainOutputs b = tiny.run(r, CrossCompile::Yes, kKeyA);
    check_same(a, b);
    CHECK(tiny.counts().compiled == 2);
    CHECK(tiny.counts().reused == 0);
}

TEST_CASE("a_plan_given_at_once_holds_only_the_stages_given_more_than_once", "[memo]") {
    const std::string b = other_key();
    const CompileRequest shared = vertex_request(Language::Glsl, kKeyA);
    const CompileRequest own = vertex_request(Language::Hlsl, kKeyA);
    const StageKey k = stage_key(shared, CrossCompile::Yes, kKeyA);
    StageMemo memo;
    memo.expect({stage_key(own, CrossCompile::No, kKeyA), k,
                 stage_key(vertex_request(Language::Glsl, b), CrossCompile::Yes, b), k});
    CHECK(memo.entries() == 1); // the stage three variants share; the HLSL one is its own
    memo.run(own, CrossCompile::No, kKeyA);
    for (int i = 0; i < 3; ++i)
        memo.run(shared, CrossCompile::Yes, kKeyA);
    CHECK(memo.counts().compiled == 2);
    CHECK(memo.counts().reused == 2);
    CHECK(memo.entries() == 0); // the last use let it go
}

TEST_CASE("threads_asking_for_one_stage_at_once_compile_it_once", "[memo]") {
    const CompileRequest r = vertex_request(Language::Hlsl, kKeyA);
    const StageKey key = stage_key(r, CrossCompile::No, kKeyA);
    constexpr int kThreads = 8;
    StageMemo memo;
    memo.expect(std::vector<StageKey>(kThreads, key));
    std::vector<ToolchainOutputs> got(kThreads);
    std::vector<std::thread> threads;
    for (int i = 0; i < kThreads; ++i)
        threads.emplace_back([&, i] { got[i] = memo.run(r, CrossCompile::No, kKeyA); });
    for (auto& t : threads)
        t.join();
    CHECK(memo.counts().compiled == 1);
    CHECK(memo.counts().reused == kThreads - 1);
    for (const ToolchainOutputs& t : got) {
        check_same(t, got[0]);
        CHECK_FALSE(t.cross_compiled); // the HLSL path as a build runs it
        CHECK(t.msl.empty());
    }
}

// runtime/manifest_schema.h against what is written and what is read. Its table names every key
// path of the checked-in build's manifest (generated/manifest.json), of the scene facts and of
// the binding maps the writer copies in, with their types. And its readers read what it says:
// without one occurrence of a key the table says the runtime (ShaderBuild::open), the build's C++
// header (shaders_header) or the output checks (is_watergen_manifest, manifest_named_files) read,
// that reader refuses the manifest or reads it differently; without a key it leaves to others, it
// reads the manifest as before. (watergen merge's reads are not run here: the merge needs real
// shards, tests/pipeline/sharded_build_test.cpp.)
//
// The readers run on two manifests made of generated/manifest.json: its head with the variants
// that between them hold every key path it has, one given a tessellated mesh's "geometry"; and
// the same variants as a specialized build lists them (a switched shader per variant, the variant
// drawn by it with its selectors placed both ways and frozen modules, a photon pass, a
// push-constant slot), whose keys no checked-in build holds.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "build_test_support.h"
#include "manifest_schema_walk.h"
#include "watergen/pipeline/manifest/manifest.h"
#include "watergen/pipeline/manifest/manifest_files.h"
#include "watergen/pipeline/output/output_target.h"
#include "watergen/pipeline/record/shaders_header.h"
#include "watergen/plan/binding_map_file.h"
#include "watergen/plan/material.h"
#include "watergen/plan/scene_file.h"
#include "watergen/runtime/manifest_schema.h"
#include "watergen/runtime/shader_build.h"

using namespace watergen;
namespace fs = std::filesystem;
namespace ms = watergen::manifest_schema;
using OJson = nlohmann::ordered_json;
using Pointer = OJson::json_pointer;

namespace {

fs::path generated_dir() {
    return fs::path(test::source_dir()) / "generated";
}

OJson generated_manifest() {
    std::ifstream in(generated_dir() / "manifest.json", std::ios::binary);
    REQUIRE(in);
    return OJson::parse(in);
}

// A file of generated/ (the header writer reads the variants' descriptions), held once read.
std::optional<std::string> generated_file(const std::string& path) {
    static std::map<std::string, std::optional<std::string>> held;
    if (const auto it = held.find(path); it != held.end()) return it->second;
    std::optional<std::string> bytes;
    if (std::ifstream in(generated_dir() / path, std::ios::binary); in) {
        std::ostringstream s;
        s << in.rdbuf();
        bytes = s.str();
    }
    return held[path] = bytes;
}

// --- The manifests the readers run on.

// A tessellated mesh's "geometry", as variant.json gives it.
OJson tessellated_geometry() {
    namespace g = ms::geometry;
    OJson inputs = OJson::array();
    inputs.push_back({{ms::vertex_input::kName, "grid_xz"},
                      {ms::vertex_input::kLocation, 0},
                      {ms::vertex_input::kFloats, 2},
                      {ms::vertex_input::kOffset, 0}});
    inputs.push_back({{ms::vertex_input::kName, "grid_lod"},
                      {ms::vertex_input::kLocation, 1},
                      {ms::vertex_input::kFloats, 3},
                      {ms::vertex_input::kOffset, 8}});
    return {{g::kName, "tessellated"},
            {g::kStages, {"vertex", "tess_control", "tess_evaluation", "fragment"}},
            {g::kTopology, "patch_list"},
            {g::kVertexStride, 20},
            {g::kVertexInputs, inputs},
            {g::kGrid,
             {{ms::grid::kKind, "clipmap"},
              {ms::grid::kMadeBy, "watergen::water_grid (runtime/water_grid.h)"},
              {ms::grid::kParameters, {"grid_morph_start", "grid_morph_end"}}}},
            {g::kFrontFace, "counter_clockwise"},
            {g::kPatchControlPoints, 4},
            {g::kTessellation,
             {{ms::tessellation::kMaxFactor, 64.0},
              {ms::tessellation::kParameters, {"tess_scale", "tess_max"}}}}};
}

// generated/manifest.json with the variants that hold between them every key path it has (each
// one that adds a path), the first given a tessellated mesh's geometry.
OJson permutations_manifest(const OJson& generated) {
    OJson m = generated;
    OJson& variants = m[ms::top::kVariants];
    variants = OJson::array();
    std::set<std::string> held;
    for (const OJson& v : generated[ms::top::kVariants]) {
        const std::set<std::string> paths = test::key_paths(v, "/variants/*");
        if (std::includes(held.begin(), held.end(), paths.begin(), paths.end())) continue;
        held.insert(paths.begin(), paths.end());
        variants.push_back(v);
    }
    REQUIRE(variants.size() >= 2);
    variants[0][ms::output::kGeometry] = tessellated_geometry();
    return m;
}

// Every file kind in a "files" object: the kinds it lacks given one path below `directory`.
void with_every_kind(OJson& files, const std::string& directory) {
    OJson all = OJson::object();
    for (const char* kind :
         {ms::files::kDescription, ms::files::kGlsl, ms::files::kHlsl, ms::files::kSpirv,
          ms::files::kGlsl330, ms::files::kEssl300, ms::files::kMsl, ms::files::kReflection})
        all[kind] = files.contains(kind)
                        ? files[kind]
                        : OJson::array({directory + "/" + kind + "/made_up." + kind});
    files = all;
}

// `permutations` as a specialized build lists its variants: each drawn by a switched shader of its
// own (the variant's files, reflection and fold), with its selectors placed as constants and as
// block members, and frozen modules; the first variant with a pass draws it with points; the
// bindings add a texture on set 2 (first) and the block as a push constant.
OJson specialized_manifest(const OJson& permutations) {
    OJson m;
    for (const char* head :
         {ms::top::kGenerator, ms::top::kMaterial, ms::top::kSpace, ms::top::kScenes})
        m[head] = permutations[head];
    OJson resources = OJson::object();
    resources["extra_texture"] = {{ms::resource::kKind, "texture"},
                                  {ms::resource::kSet, 2},
                                  {ms::resource::kBinding, 7},
                                  {ms::resource::kHlslRegister, 5},
                                  {ms::resource::kHlslSpace, 2},
                                  {ms::resource::kMsl, 6},
                                  {ms::resource::kGl, 6}};
    for (const auto& [name, slot] :
         permutations[ms::top::kBindings][ms::bindings::kResources].items())
        resources[name] = slot;
    resources["WaterPush"] = {
        {ms::resource::kKind, "push_constant"}, {ms::resource::kMsl, 5}, {ms::resource::kGl, 4}};
    m[ms::top::kBindings] = {
        {ms::bindings::kMap, permutations[ms::top::kBindings][ms::bindings::kMap]},
        {ms::bindings::kResources, resources},
        {ms::bindings::kPushConstantBytes, 128}};
    m[ms::top::kMode] = "specialized";
    OJson shaders = OJson::array(), served = OJson::array();
    std::set<std::string> directories;
    bool points = false; // the first variant with a pass draws it with points
    for (const OJson& v : permutations[ms::top::kVariants]) {
        const std::string dir = v[ms::output::kDirectory].get<std::string>();
        if (!directories.insert(dir).second) continue;
        OJson s;
        s[ms::shader::kScene] = v[ms::variant::kScene];
        s[ms::shader::kKey] = v[ms::variant::kKey];
        s[ms::shader::kContentHash] = v[ms::variant::kContentHash];
        s[ms::shader::kAxes] = permutations[ms::top::kMaterial][ms::material::kAxes];
        for (const char* part :
             {ms::output::kSameAs, ms::output::kDirectory, ms::output::kFiles,
              ms::output::kReflection, ms::output::kSpirvInstructions, ms::output::kGeometry})
            if (v.contains(part)) s[part] = v[part];
        with_every_kind(s[ms::output::kFiles], dir);
        s[ms::shader::kSelectors] =
            OJson::array({{{ms::selector::kAxis, "fresnel"},
                           {ms::selector::kParameter, "axis_fresnel"},
                           {ms::selector::kChoices, {"schlick", "exact"}},
                           {ms::selector::kConstantId, 0}},
                          {{ms::selector::kAxis, "specular"},
                           {ms::selector::kParameter, "axis_specular"},
                           {ms::selector::kChoices, {"none", "blinn_phong"}},
                           {ms::selector::kOffset, 16}}});
        s[ms::shader::kVariants] = 1;
        for (const char* part :
             {ms::fold::kFoldedParameters, ms::fold::kRemovedParameters, ms::fold::kRemovedTextures,
              ms::fold::kRemovedTerms, ms::fold::kLiveIrNodes})
            if (v.contains(part)) s[part] = v[part];
        shaders.push_back(s);

        OJson e;
        e[ms::variant::kScene] = v[ms::variant::kScene];
        e[ms::variant::kKey] = v[ms::variant::kKey];
        e[ms::variant::kHash] = v[ms::variant::kHash];
        e[ms::variant::kShader] = dir;
        e[ms::variant::kNodes] = v[ms::variant::kNodes];
        e[ms::variant::kSelectors] = {{"axis_fresnel", 1.0}, {"axis_specular", 1.0}};
        e[ms::variant::kSpecializationConstants] =
            OJson::array({{{ms::placed::kId, 0},
                           {ms::placed::kName, "axis_fresnel"},
                           {ms::placed::kValue, 1.0}}});
        e[ms::variant::kUniforms] = OJson::array({{{ms::placed::kName, "axis_specular"},
                                                   {ms::placed::kOffset, 16},
                                                   {ms::placed::kValue, 1.0}}});
        const std::string stem = std::to_string(served.size());
        e[ms::variant::kFrozen] = {{"glsl", dir + "/glsl/frozen/" + stem + ".frag.spv"},
                                   {"hlsl", dir + "/hlsl/frozen/" + stem + ".frag.spv"}};
        if (v.contains(ms::variant::kPasses)) {
            e[ms::variant::kPasses] = v[ms::variant::kPasses];
            OJson& pass = e[ms::variant::kPasses][ms::passes::kCaustics];
            if (!points) {
                with_every_kind(pass[ms::pass::kFiles],
                                pass[ms::pass::kDirectory].get<std::string>());
                pass[ms::pass::kDraw][ms::draw::kPrimitive] = "points";
                pass[ms::pass::kDraw][ms::draw::kPhotonShare] = "caustics_photon_share";
            }
            points = true;
        }
        served.push_back(e);
    }
    REQUIRE(points);
    m[ms::top::kShaders] = shaders;
    m[ms::top::kVariants] = served;
    return m;
}

// --- The readers: what each makes of a manifest's text, or "refused: ...".

OJson variant_reading(const BuildVariant& v) {
    OJson parameters = OJson::array(), textures = OJson::array(), passes = OJson::object();
    for (const BlockParameter& p : v.parameters)
        parameters.push_back(
            OJson::array({p.name, p.type, p.array_size, p.offset, p.default_value, p.min, p.max,
                          host_rule_name(p.host.rule), p.host.inputs}));
    for (const TextureSlot& t : v.textures)
        textures.push_back(OJson::array({t.name, t.binding, t.type}));
    OJson specialization = OJson::object();
    for (const auto& [id, value] : v.specialization)
        specialization[std::to_string(id)] = value;
    for (const auto& [name, pass] : v.passes) {
        const PassDraw& d = pass.draw;
        passes[name] = OJson::array(
            {pass.method, pass.wave_model, pass.directory, pass.files, pass.values,
             OJson::array({d.primitive, d.attribute, d.cells_per_texel, d.margin_parameter,
                           d.margin_scale, d.margin_add, d.window_parameter, d.texels, d.format,
                           d.channel, d.clear, d.blend, d.photon_share_parameter})});
    }
    OJson geometry;
    if (v.geometry) {
        OJson inputs = OJson::array();
        for (const VertexInput& in : v.geometry->vertex_inputs)
            inputs.push_back(OJson::array({in.name, in.location, in.floats, in.offset}));
        geometry = OJson::array({v.geometry->name, v.geometry->stages, inputs,
                                 v.geometry->vertex_stride, v.geometry->patch_control_points});
    }
    return OJson::array({v.scene, v.key, v.hash, v.choices, v.shader_directory, v.files,
                         v.block_name, parameters, textures, v.folded_parameters,
                         v.removed_parameters, specialization, v.selector_uniforms, v.frozen,
                         passes, v.file_stem, geometry});
}

std::string build_reading(const ShaderBuild& b) {
    OJson slots = OJson::array(), variants = OJson::array();
    for (const MapSlot& s : b.bindings().slots)
        slots.push_back(OJson::array({s.name, static_cast<int>(s.kind), s.set, s.binding,
                                      s.hlsl_register, s.hlsl_space, s.msl, s.gl}));
    for (const BuildVariant& v : b.variants())
        variants.push_back(variant_reading(v));
    return OJson::array({b.generator(), b.mode(), b.scenes(), b.axes(), b.bindings().map, slots,
                         b.bindings().push_constant_bytes, variants})
        .dump();
}

struct Reader {
    const char* name;
    unsigned bit; // its manifest_schema reader bit
    std::function<std::string(const std::string& manifest)> read;
};

std::vector<Reader> readers(const fs::path& scratch) {
    return {
        {"the runtime (ShaderBuild::open)", ms::kRuntime,
         [scratch](const std::string& manifest) {
             {
                 std::ofstream out(scratch / "manifest.json", std::ios::binary | std::ios::trunc);
                 out << manifest;
             }
             std::string error;
             const auto build = ShaderBuild::open(scratch, &error);
             return build ? build_reading(*build) : "refused: " + error;
         }},
        {"the build's header (shaders_header)", ms::kHeader,
         [](const std::string& manifest) {
             std::string error;
             const auto header = shaders_header(
                 [&](const std::string& path) -> std::optional<std::string> {
                     if (path == "manifest.json") return manifest;
                     return generated_file(path);
                 },
                 &error);
             return header ? *header : "refused: " + error;
         }},
        {"the output checks (is_watergen_manifest, manifest_named_files)", ms::kOutput,
         [](const std::string& manifest) {
             if (!is_watergen_manifest(manifest))
                 return std::string("refused: not a manifest (no \"generator\")");
             std::vector<std::string> paths;
             if (const std::string why = manifest_named_files(manifest, paths); !why.empty())
                 return "refused: " + why;
             std::string s = "the files a manifest names:\n";
             for (const std::string& p : paths)
                 s += p + "\n";
             return s;
         }},
    };
}

// --- One key taken out.

std::vector<std::string> segments(std::string_view path) {
    std::vector<std::string> out;
    for (size_t at = 1; at <= path.size();) {
        const size_t next = std::min(path.find('/', at), path.size());
        out.emplace_back(path.substr(at, next - at));
        at = next + 1;
    }
    return out;
}

void find_occurrences(const OJson& v, const std::vector<std::string>& path, size_t depth,
                      const Pointer& at, size_t limit, std::vector<Pointer>& out) {
    if (out.size() >= limit) return;
    if (depth == path.size()) {
        out.push_back(at);
        return;
    }
    const std::string& key = path[depth];
    if (key == "*" && v.is_array()) {
        for (size_t i = 0; i < v.size(); ++i)
            find_occurrences(v[i], path, depth + 1, at / i, limit, out);
    } else if (key == "*" && v.is_object()) {
        for (auto it = v.begin(); it != v.end(); ++it)
            find_occurrences(it.value(), path, depth + 1, at / it.key(), limit, out);
    } else if (v.is_object() && v.contains(key)) {
        find_occurrences(v[key], path, depth + 1, at / key, limit, out);
    }
}

// Where `path` (a schema path) occurs in `doc`, the first `limit` places in document order.
std::vector<Pointer> occurrences(const OJson& doc, std::string_view path, size_t limit) {
    std::vector<Pointer> out;
    find_occurrences(doc, segments(path), 0, Pointer(), limit, out);
    return out;
}

// `doc` without the member or element at `at`, as text.
std::string without(const OJson& doc, const Pointer& at) {
    OJson copy = doc;
    OJson& parent = copy[at.parent_pointer()];
    if (parent.is_object())
        parent.erase(at.back());
    else
        parent.erase(static_cast<size_t>(std::stoul(at.back())));
    return copy.dump();
}

std::string shown(const std::set<std::string>& faults) {
    std::string s;
    for (const std::string& f : faults)
        s += f + "\n";
    return s;
}

} // namespace

TEST_CASE("the_manifest_schema_names_each_key_path_once_below_its_object", "[manifest][schema]") {
    std::map<std::string_view, size_t> index;
    for (const ms::ManifestKey& key : ms::kManifestKeys) {
        INFO(key.path);
        CHECK(index.emplace(key.path, index.size()).second); // once
        REQUIRE(key.path.size() > 1);
        CHECK(key.path.front() == '/');
        CHECK(key.path.back() != '/');
        CHECK(key.path.find("//") == std::string_view::npos);
        CHECK((key.readers & ~(ms::kRuntime | ms::kMerge | ms::kHeader | ms::kOutput)) == 0u);
        const size_t slash = key.path.rfind('/');
        const std::string_view name = key.path.substr(slash + 1);
        if (slash == 0) {
            CHECK(name != "*");
            continue;
        }
        // Its object comes first in the table: a member of an object by its name, an element of
        // an array or a member of a Map as "*".
        const auto parent = index.find(key.path.substr(0, slash));
        REQUIRE(parent != index.end());
        const ms::JsonType type = ms::kManifestKeys[parent->second].type;
        if (name == "*")
            CHECK((type == ms::JsonType::Array || type == ms::JsonType::Map));
        else
            CHECK(type == ms::JsonType::Object);
    }
    // The constants spell the table's keys.
    const std::string variant = std::string("/") + ms::top::kVariants + "/*/";
    CHECK(test::schema_key(variant + ms::variant::kKey) != nullptr);
    CHECK(test::schema_key(variant + ms::output::kReflection + "/" + ms::reflection::kUniformBlock +
                           "/" + ms::uniform_block::kMembers + "/*/" + ms::member::kOffset) !=
          nullptr);
    CHECK(test::schema_key(variant + ms::variant::kPasses + "/" + ms::passes::kCaustics + "/" +
                           ms::pass::kDraw + "/" + ms::draw::kMargin + "/" + ms::margin::kAdd) !=
          nullptr);
    CHECK(test::schema_key(std::string("/") + ms::top::kShaders + "/*/" + ms::shader::kSelectors +
                           "/*/" + ms::selector::kConstantId) != nullptr);
    CHECK(test::schema_key(std::string("/") + ms::top::kBindings + "/" + ms::bindings::kResources +
                           "/*/" + ms::resource::kHlslSpace) != nullptr);
}

TEST_CASE("every_key_path_of_the_checked_in_manifest_is_in_the_schema_with_its_type",
          "[manifest][schema]") {
    const OJson generated = generated_manifest();
    INFO(shown(test::unschemed_paths(generated)));
    CHECK(test::unschemed_paths(generated).empty());
    CHECK(test::key_paths(generated).size() > 150);
}

TEST_CASE("the_scene_facts_and_binding_maps_the_manifest_copies_are_in_the_schema",
          "[manifest][schema]") {
    // The facts a pruned scene records: the scene file's keys that have a manifest form, and no
    // others.
    std::set<std::string> facts;
    for (const SceneKey& k : scene_keys())
        if (k.manifest) facts.insert(std::string(k.key));
    const std::string prefix =
        std::string("/") + ms::top::kScenes + "/*/" + ms::scene::kFacts + "/";
    std::set<std::string> listed;
    for (const ms::ManifestKey& key : ms::kManifestKeys)
        if (key.path.rfind(prefix, 0) == 0 &&
            key.path.find('/', prefix.size()) == std::string::npos)
            listed.emplace(key.path.substr(prefix.size()));
    CHECK(listed == facts);

    // The head the writer gives every manifest, with each binding profile and a map that makes
    // the block a push constant.
    std::vector<BindingMap> maps;
    Diagnostics ds;
    for (const char* profile : {"watergen", "frequency_sets", "register_spaces"}) {
        auto map = load_binding_map(profile, ds);
        REQUIRE(map);
        maps.push_back(*map);
    }
    Diagnostic error;
    const auto pushed = JsonSource::parse(
        R"({"watergen_bindings": 1, "base": "register_spaces", "push_constant_bytes": 256,
            "resources": {"WaterParams": {"kind": "push_constant", "msl": 3, "gl": 2}}})",
        "pushed.json", &error);
    REQUIRE(pushed);
    auto map = read_binding_map(*pushed, ds);
    REQUIRE(map);
    maps.push_back(*map);
    for (const BindingMap& m : maps) {
        const OJson head = OJson::parse(
            manifest_json(default_material(), {{"unpruned", nullptr, 0}}, {}, {}, {}, &m));
        INFO(m.name << ": " << shown(test::unschemed_paths(head)));
        CHECK(test::unschemed_paths(head).empty());
        CHECK(head[ms::top::kBindings].contains(ms::bindings::kPushConstantBytes) ==
              (&m == &maps.back()));
    }
}

TEST_CASE("the_readers_read_the_keys_the_schema_says_they_read_and_no_others",
          "[manifest][schema]") {
    const test::TempDir scratch("manifest-schema");
    const std::vector<Reader> all = readers(scratch.path);
    struct Manifest {
        const char* name;
        OJson doc;
        std::vector<std::string> readings; // per reader, of the whole manifest
    };
    const OJson generated = generated_manifest();
    std::vector<Manifest> manifests(2);
    manifests[0] = {
        "generated/manifest.json cut to a few variants", permutations_manifest(generated), {}};
    manifests[1] = {"its specialized form", specialized_manifest(manifests[0].doc), {}};
    for (Manifest& m : manifests) {
        INFO(m.name << ": " << shown(test::unschemed_paths(m.doc)));
        REQUIRE(test::unschemed_paths(m.doc).empty());
        for (const Reader& r : all) {
            m.readings.push_back(r.read(m.doc.dump()));
            INFO(r.name << ": " << m.readings.back().substr(0, 400));
            REQUIRE(m.readings.back().rfind("refused", 0) == std::string::npos);
        }
    }

    for (const ms::ManifestKey& key : ms::kManifestKeys) {
        std::vector<bool> found(all.size()), differs(all.size());
        for (const Manifest& m : manifests) {
            const std::vector<Pointer> at = occurrences(m.doc, key.path, 16);
            for (size_t k = 0; k < at.size(); ++k) {
                bool pending = k == 0; // each reader that does not read it: the first only
                for (size_t r = 0; r < all.size(); ++r)
                    pending = pending || ((key.readers & all[r].bit) && !differs[r]);
                if (!pending) break;
                const std::string text = without(m.doc, at[k]);
                for (size_t r = 0; r < all.size(); ++r) {
                    const bool reads = (key.readers & all[r].bit) != 0;
                    if (reads ? differs[r] : k > 0) continue;
                    found[r] = true;
                    const std::string reading = all[r].read(text);
                    if (reads) {
                        differs[r] = reading != m.readings[r];
                    } else {
                        INFO(all[r].name << " reads " << key.path
                                         << ", which the schema leaves to others: without "
                                         << at[k].to_string() << " in " << m.name << " it reads "
                                         << reading.substr(0, 400));
                        const bool reads_the_same = reading == m.readings[r];
                        CHECK(reads_the_same);
                    }
                }
            }
        }
        for (size_t r = 0; r < all.size(); ++r) {
            if ((key.readers & all[r].bit) == 0) continue;
            INFO(key.path << " is read by " << all[r].name
                          << " says the schema; neither manifest here holds it (give one of "
                             "this test's manifests the key) or neither reads differently "
                             "without it (the schema says too much)");
            CHECK(found[r]);
            CHECK(differs[r]);
        }
    }
}

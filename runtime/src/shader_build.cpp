// Reads a build's manifest.json (every build mode) into BuildVariants, and selects among them.
#include "watergen/runtime/shader_build.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "json_limits.h"
#include "manifest_reader.h"
#include "watergen/runtime/spirv_check.h"

namespace watergen {

namespace fs = std::filesystem;
using manifest::at;
using manifest::ManifestReader;
using manifest::read_bytes;
using nlohmann::json;
namespace mk = manifest_schema;

namespace {

void read_files(ManifestReader& r, const json& entry, const std::string& path, BuildVariant& v) {
    manifest::read_file_lists(r, entry, path, v.files);
}

void read_reflection(ManifestReader& r, const json& entry, const std::string& path,
                     BuildVariant& v) {
    const json* refl =
        r.get(entry, path, mk::output::kReflection, json::value_t::object, "an object");
    if (!refl) return;
    const std::string rp = path + "." + mk::output::kReflection;
    manifest::read_uniform_block(r, *refl, rp, v);
    if (const json* tex =
            r.get(*refl, rp, mk::reflection::kTextures, json::value_t::array, "an array", false))
        for (size_t i = 0; i < tex->size(); ++i) {
            const std::string tp = at(rp + "." + mk::reflection::kTextures, i);
            TextureSlot t;
            t.name = r.text((*tex)[i], tp, mk::texture::kName);
            t.binding = r.u32((*tex)[i], tp, mk::texture::kBinding);
            t.type = r.text((*tex)[i], tp, mk::texture::kType);
            v.textures.push_back(std::move(t));
        }
}

void read_fold(ManifestReader& r, const json& entry, const std::string& path, BuildVariant& v) {
    if (const json* folded = r.get(entry, path, mk::fold::kFoldedParameters, json::value_t::object,
                                   "an object", false))
        for (const auto& [name, value] : folded->items())
            v.folded_parameters[name] =
                r.numbers(*folded, path + "." + mk::fold::kFoldedParameters, name.c_str());
    if (const json* removed = r.get(entry, path, mk::fold::kRemovedParameters, json::value_t::array,
                                    "an array", false))
        for (size_t i = 0; i < removed->size(); ++i)
            v.removed_parameters.push_back(r.text((*removed)[i],
                                                  at(path + "." + mk::fold::kRemovedParameters, i),
                                                  mk::removed::kName));
}

// The variant's own part: scene, key, hash, choices (from "nodes": axis -> "axis.choice").
void read_identity(ManifestReader& r, const json& entry, const std::string& path, BuildVariant& v) {
    v.scene = r.text(entry, path, mk::variant::kScene);
    v.key = r.text(entry, path, mk::variant::kKey);
    v.hash = r.text(entry, path, mk::variant::kHash);
    const json* nodes = r.get(entry, path, mk::variant::kNodes, json::value_t::object, "an object");
    if (!nodes) return;
    for (const auto& [axis, node] : nodes->items()) {
        const std::string prefix = axis + ".";
        if (!node.is_string() || node.get<std::string>().rfind(prefix, 0) != 0)
            return r.fail(path + "." + mk::variant::kNodes + "." + axis,
                          "expected \"" + prefix + "<choice>\"");
        v.choices[axis] = node.get<std::string>().substr(prefix.size());
    }
}

// Specialized / branching: the shader a variant is drawn with, and its selector values.
void read_served(ManifestReader& r, const json& entry, const std::string& path, BuildVariant& v,
                 const std::map<std::string, BuildVariant>& shaders) {
    const std::string shader = r.text(entry, path, mk::variant::kShader);
    if (r.failed()) return;
    const auto it = shaders.find(shader);
    if (it == shaders.end())
        return r.fail(path + "." + mk::variant::kShader,
                      "'" + shader + "' is not a directory of \"shaders\"");
    const BuildVariant& s = it->second;
    v.shader_directory = s.shader_directory;
    v.files = s.files;
    v.block_name = s.block_name;
    v.parameters = s.parameters;
    v.textures = s.textures;
    v.folded_parameters = s.folded_parameters;
    v.removed_parameters = s.removed_parameters;
    if (const json* sc = r.get(entry, path, mk::variant::kSpecializationConstants,
                               json::value_t::array, "an array", false))
        for (size_t i = 0; i < sc->size(); ++i) {
            const std::string cp = at(path + "." + mk::variant::kSpecializationConstants, i);
            const uint32_t id = r.u32((*sc)[i], cp, mk::placed::kId);
            if (const json* value = r.get((*sc)[i], cp, mk::placed::kValue,
                                          json::value_t::number_float, "a number"))
                v.specialization[id] = value->get<double>();
        }
    if (const json* un =
            r.get(entry, path, mk::variant::kUniforms, json::value_t::array, "an array", false))
        for (size_t i = 0; i < un->size(); ++i) {
            const std::string up = at(path + "." + mk::variant::kUniforms, i);
            const std::string name = r.text((*un)[i], up, mk::placed::kName);
            if (const json* value = r.get((*un)[i], up, mk::placed::kValue,
                                          json::value_t::number_float, "a number"))
                v.selector_uniforms[name] = value->get<double>();
        }
    if (const json* frozen =
            r.get(entry, path, mk::variant::kFrozen, json::value_t::object, "an object", false))
        for (const auto& [lang, file] : frozen->items())
            v.frozen[lang] = r.text(*frozen, path + "." + mk::variant::kFrozen, lang.c_str());
}

// A mesh variant's "geometry" (variant.json's, copied into the manifest).
void read_geometry(ManifestReader& r, const json& entry, const std::string& path, BuildVariant& v) {
    const json* g =
        r.get(entry, path, mk::output::kGeometry, json::value_t::object, "an object", false);
    if (!g) return;
    const std::string gp = path + "." + mk::output::kGeometry;
    VariantGeometry geo;
    geo.name = r.text(*g, gp, mk::geometry::kName);
    if (const json* stages = r.get(*g, gp, mk::geometry::kStages, json::value_t::array, "an array"))
        for (size_t i = 0; i < stages->size(); ++i) {
            if (!(*stages)[i].is_string() || stages->size() > 4) {
                r.fail(at(gp + "." + mk::geometry::kStages, i), "expected a stage name");
                return;
            }
            geo.stages.push_back((*stages)[i].get<std::string>());
        }
    geo.vertex_stride = r.u32(*g, gp, mk::geometry::kVertexStride);
    if (const json* inputs =
            r.get(*g, gp, mk::geometry::kVertexInputs, json::value_t::array, "an array"))
        for (size_t i = 0; i < inputs->size() && i < 16; ++i) {
            const std::string ip = at(gp + "." + mk::geometry::kVertexInputs, i);
            VertexInput in{r.text((*inputs)[i], ip, mk::vertex_input::kName),
                           r.u32((*inputs)[i], ip, mk::vertex_input::kLocation),
                           r.u32((*inputs)[i], ip, mk::vertex_input::kFloats),
                           r.u32((*inputs)[i], ip, mk::vertex_input::kOffset)};
            if (in.location != i || in.floats < 1 || in.floats > 4) {
                r.fail(ip, "expected location " + std::to_string(i) + " and 1 to 4 floats");
                return;
            }
            geo.vertex_inputs.push_back(std::move(in));
        }
    if (g->contains(mk::geometry::kPatchControlPoints)) {
        geo.patch_control_points = r.u32(*g, gp, mk::geometry::kPatchControlPoints);
        if (geo.patch_control_points != 4) {
            r.fail(gp + "." + mk::geometry::kPatchControlPoints, "expected 4 (quad patches)");
            return;
        }
    }
    v.geometry = std::move(geo);
}

void read_shader_part(ManifestReader& r, const json& entry, const std::string& path,
                      BuildVariant& v) {
    v.shader_directory = r.text(entry, path, mk::output::kDirectory);
    read_files(r, entry, path, v);
    read_reflection(r, entry, path, v);
    read_fold(r, entry, path, v);
    read_geometry(r, entry, path, v);
}

bool unsafe_relative(const std::string& p) {
    const fs::path path(p);
    if (p.empty() || path.is_absolute()) return true;
    for (const auto& part : path)
        if (part == "..") return true;
    return false;
}

std::string joined(const std::vector<std::string>& items, const char* sep = ", ") {
    std::string out;
    for (const auto& s : items)
        out += (out.empty() ? "" : sep) + s;
    return out;
}

std::map<std::string, std::string> parse_key(const std::string& key, std::string* error) {
    std::map<std::string, std::string> choices;
    std::stringstream in(key);
    std::string part;
    while (std::getline(in, part, ',')) {
        const size_t eq = part.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == part.size()) {
            *error = "runtime key '" + key + "': '" + part +
                     "' is not axis=choice; expected a variant key or short hash";
            return {};
        }
        choices[part.substr(0, eq)] = part.substr(eq + 1);
    }
    if (choices.empty()) *error = "runtime key is empty; expected a variant key or short hash";
    return choices;
}

} // namespace

std::vector<uint32_t> VariantGeometry::attribute_sizes() const {
    std::vector<uint32_t> sizes;
    for (const VertexInput& in : vertex_inputs)
        sizes.push_back(in.floats);
    return sizes;
}

std::optional<ShaderBuild> ShaderBuild::open(const fs::path& directory, std::string* error) {
    const fs::path file = directory / "manifest.json";
    auto bytes = read_bytes(file, error, manifest::kMaxManifestBytes);
    if (!bytes) return std::nullopt;
    bool syntax_error = false;
    if (const std::string over =
            json_limits::check(*bytes,
                               {manifest::kMaxManifestValues, manifest::kMaxManifestDepth,
                                manifest::kMaxManifestString},
                               &syntax_error);
        !over.empty()) {
        *error = file.string() + ": " + over + "; expected the manifest of a watergen build";
        return std::nullopt;
    }
    const json doc = json::parse(*bytes, nullptr, false);
    bytes.reset(); // the DOM holds it all now
    if (doc.is_discarded() || !doc.is_object()) {
        *error = file.string() + ": not a JSON object; expected the manifest of a watergen build";
        return std::nullopt;
    }
    ManifestReader r(file.string(), error);
    ShaderBuild b;
    b.directory_ = directory;
    b.generator_ = r.text(doc, "", mk::top::kGenerator);
    if (!r.failed() && b.generator_.rfind(mk::top::kGeneratorPrefix, 0) != 0)
        r.fail(mk::top::kGenerator, "'" + b.generator_ + "'; expected \"watergen <version>\"");
    if (doc.contains(mk::top::kMode)) b.mode_ = r.text(doc, "", mk::top::kMode);
    const json* material = r.get(doc, "", mk::top::kMaterial, json::value_t::object, "an object");
    const json* axes = material ? r.get(*material, mk::top::kMaterial, mk::material::kAxes,
                                        json::value_t::object, "an object")
                                : nullptr;
    const std::string at_axes = std::string(mk::top::kMaterial) + "." + mk::material::kAxes + ".";
    if (axes)
        for (const auto& [axis, list] : axes->items()) {
            if (!list.is_array()) r.fail(at_axes + axis, "expected an array of strings");
            for (const json& c : list) {
                if (!c.is_string()) {
                    r.fail(at_axes + axis, "expected an array of strings");
                    break;
                }
                b.axes_[axis].push_back(c.get<std::string>());
            }
        }
    if (const json* map =
            r.get(doc, "", mk::top::kBindings, json::value_t::object, "an object", false))
        b.bindings_ = manifest::read_bindings(r, *map);
    if (const json* scenes = r.get(doc, "", mk::top::kScenes, json::value_t::array, "an array"))
        for (size_t i = 0; i < scenes->size(); ++i)
            b.scenes_.push_back(r.text((*scenes)[i], at(mk::top::kScenes, i), mk::scene::kName));
    std::map<std::string, BuildVariant> shaders; // by directory (modes)
    if (b.mode_ != "permutations")
        if (const json* list = r.get(doc, "", mk::top::kShaders, json::value_t::array, "an array"))
            for (size_t i = 0; i < list->size(); ++i) {
                BuildVariant s;
                read_shader_part(r, (*list)[i], at(mk::top::kShaders, i), s);
                shaders[s.shader_directory] = std::move(s);
            }
    size_t held = 0; // estimated bytes of the variants read (kMaxVariantBytes)
    if (const json* list = r.get(doc, "", mk::top::kVariants, json::value_t::array, "an array"))
        for (size_t i = 0; i < list->size() && !r.failed(); ++i) {
            BuildVariant v;
            const std::string vp = at(mk::top::kVariants, i);
            read_identity(r, (*list)[i], vp, v);
            if (b.mode_ == "permutations")
                read_shader_part(r, (*list)[i], vp, v);
            else
                read_served(r, (*list)[i], vp, v, shaders);
            manifest::read_passes(r, (*list)[i], vp, v.passes);
            held += manifest::estimated_bytes(v);
            if (!r.failed() && held > manifest::kMaxVariantBytes)
                r.fail(vp, "the variants so far hold over " +
                               std::to_string(manifest::kMaxVariantBytes >> 20) +
                               " MiB in memory; expected a build of fewer or smaller variants");
            b.variants_.push_back(std::move(v));
        }
    if (r.failed()) return std::nullopt;
    return b;
}

std::optional<std::string> ShaderBuild::read(const std::string& relative_path,
                                             std::string* error) const {
    return read_at_most(relative_path, manifest::kMaxManifestBytes, error);
}

std::optional<std::string> ShaderBuild::read_at_most(const std::string& relative_path,
                                                     std::uintmax_t max_bytes,
                                                     std::string* error) const {
    if (unsafe_relative(relative_path)) {
        *error = "'" + relative_path + "': expected a path inside the build directory";
        return std::nullopt;
    }
    bool known = false;
    for (const BuildVariant& v : variants_) {
        for (const auto& [kind, list] : v.files)
            known = known || std::find(list.begin(), list.end(), relative_path) != list.end();
        for (const auto& [lang, file] : v.frozen)
            known = known || file == relative_path;
        for (const auto& [name, pass] : v.passes)
            for (const auto& [kind, list] : pass.files)
                known = known || std::find(list.begin(), list.end(), relative_path) != list.end();
        if (known) break;
    }
    if (!known) {
        *error =
            (directory_ / "manifest.json").string() + ": does not list '" + relative_path + "'";
        return std::nullopt;
    }
    return read_bytes(directory_ / relative_path, error, max_bytes);
}

std::optional<std::string> ShaderBuild::listed(const BuildVariant& v, const std::string& kind,
                                               const std::string& suffix, std::uintmax_t max_bytes,
                                               std::string* error) const {
    const auto it = v.files.find(kind);
    if (it != v.files.end())
        for (const std::string& p : it->second)
            if (p.size() >= suffix.size() &&
                p.compare(p.size() - suffix.size(), suffix.size(), suffix) == 0)
                return read_at_most(p, max_bytes, error);
    *error = "variant " + v.key + " (scene " + v.scene + "): the build has no " + kind + " file '" +
             suffix + "' (its targets decide which files it writes)";
    return std::nullopt;
}

std::optional<std::vector<uint32_t>> ShaderBuild::spirv(const BuildVariant& v,
                                                        const std::string& language,
                                                        ShaderStage stage,
                                                        std::string* error) const {
    std::optional<std::string> bytes;
    std::string file;
    const auto frozen = v.frozen.find(language);
    if (stage == ShaderStage::Fragment && frozen != v.frozen.end()) {
        file = frozen->second;
        bytes = read_at_most(file, kMaxSpirvBytes, error);
    } else {
        const std::string suffix =
            "/" + language + "/" + v.file_stem + "." + stage_tag(stage) + ".opt.spv";
        bytes = listed(v, mk::files::kSpirv, suffix, kMaxSpirvBytes, error);
        if (const auto it = v.files.find(mk::files::kSpirv); it != v.files.end())
            for (const std::string& p : it->second)
                if (p.size() >= suffix.size() &&
                    p.compare(p.size() - suffix.size(), suffix.size(), suffix) == 0) {
                    file = p;
                    break;
                }
    }
    if (!bytes) return std::nullopt;
    const std::string where = (directory_ / file).string() + ": ";
    if (bytes->size() % 4 != 0) {
        *error = where + std::to_string(bytes->size()) +
                 " bytes; expected a whole number of 32-bit words (SPIR-V)";
        return std::nullopt;
    }
    std::vector<uint32_t> words(bytes->size() / 4);
    if (!words.empty()) std::memcpy(words.data(), bytes->data(), bytes->size());
    std::string why;
    if (!check_spirv(words, stage, "", &why) || !validate_spirv(words, &why)) {
        *error = where + why;
        return std::nullopt;
    }
    return words;
}

std::optional<std::string> ShaderBuild::source(const BuildVariant& v, const std::string& kind,
                                               ShaderStage stage, std::string* error) const {
    const std::string tag = v.file_stem + "." + stage_tag(stage);
    // The manifest's file kinds (BuildVariant::files) and the ends of their paths.
    const std::map<std::string, std::string> suffix = {
        {mk::files::kGlsl, "/glsl/" + tag + ".glsl"},
        {mk::files::kHlsl, "/hlsl/" + tag + ".hlsl"},
        {mk::files::kGlsl330, "/" + tag + ".330.glsl"},
        {mk::files::kEssl300, "/" + tag + ".300es.glsl"},
        {mk::files::kMsl, "/" + tag + ".metal"}};
    const auto it = suffix.find(kind);
    if (it == suffix.end()) {
        *error = "source kind '" + kind + "'; expected glsl, hlsl, glsl330, essl300 or msl";
        return std::nullopt;
    }
    return listed(v, kind, it->second, manifest::kMaxManifestBytes, error);
}

std::optional<Reflection> ShaderBuild::reflection(const BuildVariant& v,
                                                  const std::string& language, ShaderStage stage,
                                                  std::string* error) const {
    const std::string suffix =
        "/" + language + "/" + v.file_stem + "." + stage_tag(stage) + ".reflect.json";
    const auto text =
        listed(v, mk::files::kReflection, suffix, manifest::kMaxDescriptionBytes, error);
    if (!text) return std::nullopt;
    std::string why;
    auto r = reflection_from_json(*text, &why);
    if (!r) *error = (directory_ / v.shader_directory).string() + suffix + ": " + why;
    return r;
}

Selection ShaderBuild::select(const std::string& scene_name,
                              const std::map<std::string, std::string>& choices,
                              Fallback fallback) const {
    Selection s;
    std::string scene = scene_name;
    if (scene.empty() && scenes_.size() == 1) scene = scenes_[0];
    if (std::find(scenes_.begin(), scenes_.end(), scene) == scenes_.end()) {
        s.error = "no scene '" + scene + "' in " + directory_.string() +
                  "; its scenes: " + joined(scenes_);
        return s;
    }
    for (const auto& [axis, choice] : choices) {
        const auto a = axes_.find(axis);
        if (a == axes_.end()) {
            std::vector<std::string> names;
            for (const auto& [n, c] : axes_)
                names.push_back(n);
            s.error = "no axis '" + axis + "' in the material; its axes: " + joined(names);
            return s;
        }
        if (std::find(a->second.begin(), a->second.end(), choice) == a->second.end()) {
            s.error = "axis " + axis + " has no choice '" + choice + "' in the material; its " +
                      "choices: " + joined(a->second);
            return s;
        }
    }
    std::vector<const BuildVariant*> in_scene, exact;
    for (const BuildVariant& v : variants_) {
        if (v.scene != scene) continue;
        in_scene.push_back(&v);
        const bool match = std::all_of(choices.begin(), choices.end(), [&](const auto& c) {
            const auto it = v.choices.find(c.first);
            return it != v.choices.end() && it->second == c.second;
        });
        if (match) exact.push_back(&v);
    }
    if (exact.size() == 1 || (exact.size() > 1 && fallback == Fallback::NearestKept)) {
        s.variant = exact.front();
        return s;
    }
    if (exact.size() > 1) {
        std::set<std::string> open_axes;
        for (const BuildVariant* v : exact)
            for (const auto& [axis, choice] : v->choices)
                if (exact.front()->choices.count(axis) == 0 ||
                    choice != exact.front()->choices.find(axis)->second)
                    open_axes.insert(axis);
        s.error = std::to_string(exact.size()) + " variants of scene " + scene +
                  " match; name a choice for " +
                  joined(std::vector<std::string>(open_axes.begin(), open_axes.end()));
        return s;
    }
    if (fallback == Fallback::Error) {
        std::vector<std::string> missing;
        for (const auto& asked_choice : choices) {     // (no structured binding: clang 14 cannot
            const auto& [axis, choice] = asked_choice; // capture one in the lambda below)
            const bool kept = std::any_of(in_scene.begin(), in_scene.end(), [&](const auto* v) {
                const auto it = v->choices.find(asked_choice.first);
                return it != v->choices.end() && it->second == asked_choice.second;
            });
            if (!kept) missing.push_back(axis + "=" + choice);
        }
        std::vector<std::string> asked;
        for (const auto& [axis, choice] : choices)
            asked.push_back(axis + "=" + choice);
        s.error = "scene " + scene + " pruned " +
                  (missing.empty() ? "the combination " + joined(asked, ",")
                                   : "every variant with " + joined(missing, " or ")) +
                  "; ask for a kept combination or select with Fallback::NearestKept";
        return s;
    }
    size_t best = SIZE_MAX;
    for (const BuildVariant* v : in_scene) {
        size_t differs = 0;
        for (const auto& [axis, choice] : choices) {
            const auto it = v->choices.find(axis);
            differs += it == v->choices.end() || it->second != choice;
        }
        if (differs < best) {
            best = differs;
            s.variant = v;
        }
    }
    if (!s.variant) {
        s.error = "scene " + scene + " has no variants";
        return s;
    }
    for (const auto& [axis, choice] : choices)
        if (const auto it = s.variant->choices.find(axis);
            it != s.variant->choices.end() && it->second != choice)
            s.changed.push_back(axis + ": " + choice + " -> " + it->second);
    return s;
}

Selection ShaderBuild::select_key(const std::string& scene, const std::string& key,
                                  Fallback fallback) const {
    const std::string in = scene.empty() && scenes_.size() == 1 ? scenes_[0] : scene;
    for (const BuildVariant& v : variants_)
        if (v.scene == in && v.hash == key && !key.empty()) {
            Selection s;
            s.variant = &v;
            return s;
        }
    Selection s;
    const auto choices = parse_key(key, &s.error);
    if (choices.empty()) return s;
    return select(scene, choices, fallback);
}

} // namespace watergen

// Companion passes: a variant's "passes" entry read from the manifest, the pass opened from its
// pass.json (ShaderBuild::pass), and the grid it is drawn over.
#include "watergen/runtime/build_pass.h"

#include <cmath>

#include "json_limits.h"
#include "manifest_reader.h"
#include "watergen/runtime/shader_build.h"

namespace watergen {

using manifest::json;
using manifest::ManifestReader;
namespace mk = manifest_schema;

namespace {

double number(ManifestReader& r, const json& o, const std::string& path, const char* key) {
    const json* v = r.get(o, path, key, json::value_t::number_float, "a number");
    return v ? v->get<double>() : 0.0;
}

void read_draw(ManifestReader& r, const json& entry, const std::string& path, PassDraw& d) {
    const json* draw = r.get(entry, path, mk::pass::kDraw, json::value_t::object, "an object");
    if (!draw) return;
    const std::string dp = path + "." + mk::pass::kDraw;
    d.primitive = r.text(*draw, dp, mk::draw::kPrimitive);
    if (!r.failed() && d.primitive != "triangles" && d.primitive != "points")
        r.fail(dp + "." + mk::draw::kPrimitive,
               "'" + d.primitive + "'; expected \"triangles\" or \"points\"");
    d.attribute = r.text(*draw, dp, mk::draw::kAttribute);
    d.cells_per_texel = r.u32(*draw, dp, mk::draw::kCellsPerTexel);
    if (const json* m = r.get(*draw, dp, mk::draw::kMargin, json::value_t::object, "an object")) {
        const std::string mp = dp + "." + mk::draw::kMargin;
        d.margin_parameter = r.text(*m, mp, mk::margin::kParameter);
        d.margin_scale = number(r, *m, mp, mk::margin::kScale);
        d.margin_add = number(r, *m, mp, mk::margin::kAdd);
    }
    d.window_parameter = r.text(*draw, dp, mk::draw::kWindow);
    d.texels = r.u32(*draw, dp, mk::draw::kTexels);
    if (!r.failed() && (d.texels == 0 || d.cells_per_texel == 0))
        r.fail(dp, "texels and cells_per_texel must be at least 1");
    d.format = r.text(*draw, dp, mk::draw::kFormat);
    d.channel = r.text(*draw, dp, mk::draw::kChannel);
    d.clear = number(r, *draw, dp, mk::draw::kClear);
    d.blend = r.text(*draw, dp, mk::draw::kBlend);
    if (d.primitive == "points")
        d.photon_share_parameter = r.text(*draw, dp, mk::draw::kPhotonShare);
}

std::string pass_json_path(const PassReference& ref) {
    for (const std::string& p : ref.files.count(mk::files::kDescription)
                                    ? ref.files.at(mk::files::kDescription)
                                    : std::vector<std::string>{})
        if (p == ref.directory + "/pass.json") return p;
    return "";
}

} // namespace

void manifest::read_passes(ManifestReader& r, const json& entry, const std::string& path,
                           std::map<std::string, PassReference>& passes) {
    const json* list =
        r.get(entry, path, mk::variant::kPasses, json::value_t::object, "an object", false);
    if (!list) return;
    for (const auto& [name, e] : list->items()) {
        const std::string pp = path + "." + mk::variant::kPasses + "." + name;
        if (!e.is_object()) return r.fail(pp, "expected an object");
        PassReference ref;
        ref.method = r.text(e, pp, mk::pass::kMethod);
        ref.wave_model = r.text(e, pp, mk::pass::kWaveModel);
        ref.directory = r.text(e, pp, mk::pass::kDirectory);
        read_file_lists(r, e, pp, ref.files);
        read_draw(r, e, pp, ref.draw);
        if (const json* values =
                r.get(e, pp, mk::pass::kValues, json::value_t::object, "an object"))
            for (const auto& [parameter, value] : values->items())
                ref.values[parameter] =
                    r.numbers(*values, pp + "." + mk::pass::kValues, parameter.c_str());
        if (!r.failed() && pass_json_path(ref).empty())
            r.fail(pp + "." + mk::pass::kFiles + "." + mk::files::kDescription,
                   "expected \"" + ref.directory + "/pass.json\"");
        passes[name] = std::move(ref);
    }
}

std::optional<BuildPass> ShaderBuild::pass(const BuildVariant& v, const std::string& name,
                                           std::string* error) const {
    const auto it = v.passes.find(name);
    if (it == v.passes.end()) {
        *error = "variant " + v.key + " (scene " + v.scene + ") has no " + name +
                 " pass (only caustics=area_ratio and photon_splat have a caustics pass)";
        return std::nullopt;
    }
    BuildPass p{name, it->second, {}};
    const std::string file = pass_json_path(p.reference);
    const auto bytes = read_at_most(file, manifest::kMaxDescriptionBytes, error);
    if (!bytes) return std::nullopt;
    const std::string where = (directory_ / file).string();
    // A pass.json is one uniform block (manifest_reader.h: kMaxDescriptionBytes).
    bool syntax_error = false;
    if (const std::string over =
            json_limits::check(*bytes, {size_t(1) << 16, 8, 4096}, &syntax_error);
        !over.empty()) {
        *error = where + ": " + over + "; expected a pass description of a watergen build";
        return std::nullopt;
    }
    const json doc = json::parse(*bytes, nullptr, false);
    if (!doc.is_object()) {
        *error = where + ": not a JSON object; expected a pass description of a watergen build";
        return std::nullopt;
    }
    ManifestReader r(where, error);
    BuildVariant& s = p.shader;
    s.scene = v.scene;
    s.key = r.text(doc, "", "key");
    s.shader_directory = p.reference.directory;
    s.files = p.reference.files;
    s.file_stem = name;
    manifest::read_uniform_block(r, doc, "", s);
    if (!r.failed() && s.parameters.empty())
        r.fail(mk::reflection::kUniformBlock, "missing; expected an object");
    if (r.failed()) return std::nullopt;
    // The scene's values: where the pass starts, and (as for the water variant, which folded
    // them) the only values it takes.
    for (BlockParameter& b : s.parameters)
        if (const auto f = p.reference.values.find(b.name); f != p.reference.values.end()) {
            b.default_value = f->second;
            s.folded_parameters[b.name] = f->second;
        }
    return p;
}

std::optional<PassGrid> pass_grid(const PassDraw& draw, std::span<const double> window,
                                  double margin_value, std::string* error) {
    if (window.size() != 3 || !(window[2] > 0) || !std::isfinite(window[2])) {
        *error = draw.window_parameter + " must be (x0, z0, size) with a finite size > 0";
        return std::nullopt;
    }
    const double margin = draw.margin_scale * margin_value + draw.margin_add;
    if (!(margin >= 0) || !std::isfinite(margin)) {
        *error = "the margin (" + draw.margin_parameter + ") must be finite and >= 0";
        return std::nullopt;
    }
    if (draw.primitive != "triangles" && draw.primitive != "points") {
        *error = "primitive '" + draw.primitive + "'; expected triangles or points";
        return std::nullopt;
    }
    if (draw.texels == 0 || draw.cells_per_texel == 0) {
        *error = "texels and cells_per_texel must be at least 1";
        return std::nullopt;
    }
    PassGrid g;
    g.points = draw.primitive == "points";
    g.texels = draw.texels;
    const double texel = window[2] / draw.texels;
    const double margin_texels = std::ceil(margin / texel);
    const double cells_d = (draw.texels + 2 * margin_texels) * draw.cells_per_texel;
    const double side = g.points ? cells_d : cells_d + 1;
    if (side * side > double(kMaxPassGridVertices)) {
        *error = "the grid would have " + std::to_string(side * side) +
                 " vertices; expected at most 2^26 (a smaller margin or fewer texels)";
        return std::nullopt;
    }
    const auto cells = static_cast<uint32_t>(cells_d), n = static_cast<uint32_t>(side);
    const double x0 = window[0] - margin_texels * texel, z0 = window[1] - margin_texels * texel;
    const double extent = cells * texel / draw.cells_per_texel;
    // Points at the cell centres: under flat water none lies on a texel's edge.
    const double h = g.points ? extent / cells / 2 : 0;
    g.centre = frame_centre_of(window[0], window[1]);
    const double a = x0 + h - g.centre.x, b = x0 + extent - h - g.centre.x;
    const double c = z0 + h - g.centre.z, d = z0 + extent - h - g.centre.z;
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            g.vertices.push_back(static_cast<float>(n > 1 ? a + (b - a) * i / (n - 1) : a));
            g.vertices.push_back(static_cast<float>(n > 1 ? c + (d - c) * j / (n - 1) : c));
        }
    if (g.points) {
        g.indices.resize(size_t(n) * n);
        for (uint32_t i = 0; i < g.indices.size(); ++i)
            g.indices[i] = i;
        const double share = 1.0 / (double(draw.cells_per_texel) * draw.cells_per_texel);
        g.values[draw.photon_share_parameter] = {static_cast<float>(share)};
        return g;
    }
    for (uint32_t j = n - 1; j-- > 0;) // rows from large z down (any order adds the same)
        for (uint32_t i = 0; i + 1 < n; ++i) {
            const uint32_t p = j * n + i, q = p + 1, r = p + n, s = r + 1;
            g.indices.insert(g.indices.end(), {p, r, q, q, r, s});
        }
    return g;
}

} // namespace watergen

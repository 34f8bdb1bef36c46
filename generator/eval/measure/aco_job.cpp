#include "watergen/eval/measure/aco_job.h"

#include <cfloat>
#include <cmath>

#include <nlohmann/json.hpp>

namespace watergen {

using nlohmann::json;

std::optional<AcoJob> parse_aco_job(std::string_view text, std::string* error) {
    const json job = json::parse(text, nullptr, false);
    auto fail = [&](const std::string& why) -> std::optional<AcoJob> {
        *error = why;
        return std::nullopt;
    };
    if (job.is_discarded()) return fail("not JSON");
    if (!job.is_object() || !job.contains("pipelines") || !job["pipelines"].is_array())
        return fail("expected an object with \"pipelines\", an array");
    AcoJob out;
    if (job.contains("disassembly")) {
        if (!job["disassembly"].is_boolean()) return fail("\"disassembly\": expected a boolean");
        out.disassembly = job["disassembly"].get<bool>();
    }
    const json& list = job["pipelines"];
    if (list.size() > kMaxAcoJobPipelines)
        return fail("more than " + std::to_string(kMaxAcoJobPipelines) + " pipelines");
    auto flag = [](const json& e, const char* key, bool& out) {
        if (!e.contains(key)) return true;
        if (!e[key].is_boolean()) return false;
        out = e[key].get<bool>();
        return true;
    };
    for (size_t i = 0; i < list.size(); ++i) {
        const json& e = list[i];
        const std::string at = "pipeline " + std::to_string(i) + ": ";
        if (!e.is_object()) return fail(at + "expected an object");
        AcoJobPipeline p;
        if (!e.contains("name") || !e["name"].is_string() ||
            e["name"].get_ref<const std::string&>().size() > 4096)
            return fail(at + "\"name\": expected a string of at most 4096 bytes");
        p.name = e["name"].get<std::string>();
        if (!e.contains("specialization") || !e["specialization"].is_object())
            return fail(at + "\"specialization\": expected an object of constant ids");
        for (const auto& [id, value] : e["specialization"].items()) {
            const bool digits = !id.empty() && id.size() <= 10 &&
                                id.find_first_not_of("0123456789") == std::string::npos;
            const uint64_t n = digits ? std::stoull(id) : 0;
            if (!digits || n > UINT32_MAX)
                return fail(at + "specialization '" + id + "': expected a constant id (0 to " +
                            std::to_string(UINT32_MAX) + ")");
            if (!value.is_number() || !(std::abs(value.get<double>()) <= FLT_MAX))
                return fail(at + "specialization " + id + ": expected a finite 32-bit float");
            p.specialization[static_cast<uint32_t>(n)] = value.get<float>();
        }
        if (!e.contains("format") || !e["format"].is_number_integer() ||
            !is_colour_format(e["format"].get<int64_t>()))
            return fail(at +
                        "\"format\": expected a colour format a render pass can target "
                        "(a VkFormat; watergen's targets are " +
                        std::to_string(VK_FORMAT_R16G16B16A16_SFLOAT) + ", " +
                        std::to_string(VK_FORMAT_R32_SFLOAT) + ", " +
                        std::to_string(VK_FORMAT_R32G32_SFLOAT) + " and " +
                        std::to_string(VK_FORMAT_R32G32B32A32_SFLOAT) + ")");
        p.format = static_cast<VkFormat>(e["format"].get<int64_t>());
        if (!flag(e, "tessellated", p.tessellated))
            return fail(at + "\"tessellated\": expected a boolean");
        if (e.contains("geometry")) {
            const json& g = e["geometry"];
            PipelineGeometry geometry;
            if (!g.is_object() || !g.contains("attribute_sizes") ||
                !g["attribute_sizes"].is_array())
                return fail(at + "\"geometry\": expected an object with \"attribute_sizes\"");
            if (g["attribute_sizes"].size() > kMaxVertexAttributes)
                return fail(at + "geometry: more than " + std::to_string(kMaxVertexAttributes) +
                            " vertex attributes (the count every Vulkan device takes)");
            for (const json& a : g["attribute_sizes"]) {
                if (!a.is_number_unsigned() || a.get<uint64_t>() < 1 || a.get<uint64_t>() > 4)
                    return fail(at + "geometry: an attribute of " + a.dump() +
                                " floats; expected 1 to 4");
                geometry.attribute_sizes.push_back(a.get<uint32_t>());
            }
            if (!flag(g, "points", geometry.points) ||
                !flag(g, "additive_blend", geometry.additive_blend))
                return fail(at + "geometry: \"points\" and \"additive_blend\" are booleans");
            if (g.contains("patch_control_points")) {
                const json& n = g["patch_control_points"];
                if (!n.is_number_unsigned() || n.get<uint64_t>() > kMaxPatchControlPoints)
                    return fail(at + "geometry: patch_control_points " + n.dump() +
                                ": expected 0 to " + std::to_string(kMaxPatchControlPoints));
                geometry.patch_control_points = n.get<uint32_t>();
            }
            p.geometry = std::move(geometry);
        }
        out.pipelines.push_back(std::move(p));
    }
    return out;
}

} // namespace watergen

// The inputs a compiled program's leaves read (block_inputs.h).
#include "block_inputs.h"

namespace watergen {

const void* input_data(const Graph& top, const Graph& g, const Node& n, uint32_t comps,
                       const EvalInputs& in, const ParameterValues& host,
                       std::vector<Check>& checks) {
    auto fail = [&](std::string message) { checks.push_back({std::move(message)}); };
    switch (n.op) {
    case Op::Constant:
        if (n.type == Type::Error) fail("graph contains an ill-typed node");
        return n.values.data();
    case Op::Uniform: {
        const std::vector<double>* v = nullptr;
        if (auto it = host.find(n.name); it != host.end())
            v = &it->second;
        else if (auto it = in.uniforms.find(n.name); it != in.uniforms.end())
            v = &it->second;
        else if (const Parameter* p = top.find_parameter(n.name))
            v = &p->default_value;
        if (v && v->size() == comps) return v->data();
        fail("uniform '" + n.name + "': no value with " + std::to_string(comps) + " components");
        return nullptr;
    }
    case Op::UniformElement: {
        const Parameter* p = top.find_parameter(n.name);
        const std::vector<double>* v = p ? &p->default_value : nullptr;
        if (auto it = host.find(n.name); p && it != host.end())
            v = &it->second;
        else if (auto it = in.uniforms.find(n.name);
                 p && it != in.uniforms.end() && it->second.size() == v->size())
            v = &it->second;
        if (p && p->array_size != 0 && v->size() == p->array_size * size_t(comps)) return v->data();
        fail("array '" + n.name + "': no value with " + std::to_string(comps) +
             " components per element");
        return nullptr;
    }
    case Op::Varying: {
        const std::string message = "varying '" + n.name + "' missing or too short";
        auto it = in.varyings.find(n.name);
        if (it == in.varyings.end()) {
            fail(message);
            return nullptr;
        }
        checks.push_back({message, it->second.size(), comps});
        return it->second.data();
    }
    case Op::Sample:
    case Op::SampleLevel: {
        const Node& tex = g.node(n.args[0]);
        auto it = in.textures.find(tex.name);
        if (it == in.textures.end() || !it->second.rgba) {
            fail("texture '" + tex.name + "' not supplied");
            return nullptr;
        }
        const TextureView& view = it->second;
        const bool cube = tex.type == Type::TextureCube;
        const uint32_t layers = cube ? 6u : 1u;
        if (view.layers != 0 && view.layers != layers)
            fail("texture '" + tex.name + "' has " + std::to_string(view.layers) + " layers; the " +
                 (cube ? "cube" : "2D") + " binding needs " + std::to_string(layers));
        else if (view.width == 0 || view.height == 0 || (cube && view.width != view.height))
            fail("texture '" + tex.name + "': bad size" +
                 (cube ? " (cube faces must be square)" : ""));
        return &view;
    }
    default:
        return nullptr;
    }
}

} // namespace watergen

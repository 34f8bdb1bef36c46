// The descriptor set layouts and pipeline layout of a build's binding map.
#include "watergen/runtime/binding_layout.h"

#include <algorithm>
#include <map>

#include "watergen/runtime/variant_pipeline.h"

namespace watergen {

namespace {

std::string failed(const char* call, VkResult r) {
    return std::string(call) + " failed: VkResult " + std::to_string(static_cast<int>(r));
}

std::string place(uint32_t set, uint32_t binding) {
    return "set " + std::to_string(set) + " binding " + std::to_string(binding);
}

} // namespace

const MapSlot* BuildBindings::find(const std::string& name) const {
    const auto it =
        std::find_if(slots.begin(), slots.end(), [&](const MapSlot& s) { return s.name == name; });
    return it == slots.end() ? nullptr : &*it;
}

BindingLayout::BindingLayout(BindingLayout&& o) noexcept {
    *this = std::move(o);
}

BindingLayout& BindingLayout::operator=(BindingLayout&& o) noexcept {
    if (this == &o) return *this;
    destroy();
    device_ = o.device_;
    bindings_ = std::move(o.bindings_);
    set_layouts_ = std::move(o.set_layouts_);
    layout_ = o.layout_;
    push_range_ = o.push_range_;
    push_block_ = std::move(o.push_block_);
    o.set_layouts_.clear();
    o.layout_ = VK_NULL_HANDLE;
    return *this;
}

BindingLayout::~BindingLayout() {
    destroy();
}

void BindingLayout::destroy() {
    if (!device_) return;
    if (layout_) vkDestroyPipelineLayout(device_, layout_, nullptr);
    for (VkDescriptorSetLayout l : set_layouts_)
        vkDestroyDescriptorSetLayout(device_, l, nullptr);
    set_layouts_.clear();
    layout_ = VK_NULL_HANDLE;
}

std::optional<BindingLayout> BindingLayout::create(VkDevice device, const BuildBindings& bindings,
                                                   std::string* error,
                                                   uint32_t max_push_constants_size) {
    if (bindings.slots.empty()) {
        *error = "binding map '" + bindings.map +
                 "' has no slot; expected the \"bindings\" of a build's manifest";
        return std::nullopt;
    }
    std::map<std::pair<uint32_t, uint32_t>, const MapSlot*> taken;
    const MapSlot* push = nullptr;
    uint32_t sets = 0;
    for (const MapSlot& s : bindings.slots) {
        // A push constant is no descriptor: no set, no binding to clash with one.
        if (s.kind == DescriptorKind::PushConstant) {
            if (push) {
                *error = "binding map '" + bindings.map + "': '" + push->name + "' and '" + s.name +
                         "' are both push constants; expected one push-constant block";
                return std::nullopt;
            }
            push = &s;
            continue;
        }
        if (s.set >= kMaxDescriptorSets) {
            *error = "binding map '" + bindings.map + "': '" + s.name + "' in set " +
                     std::to_string(s.set) + "; expected a set below " +
                     std::to_string(kMaxDescriptorSets) + " (Vulkan's maxBoundDescriptorSets)";
            return std::nullopt;
        }
        if (auto [it, fresh] = taken.emplace(std::pair{s.set, s.binding}, &s); !fresh) {
            *error = "binding map '" + bindings.map + "': '" + it->second->name + "' and '" +
                     s.name + "' are both at " + place(s.set, s.binding);
            return std::nullopt;
        }
        sets = std::max(sets, s.set + 1);
    }
    const uint32_t bytes = bindings.push_constant_bytes;
    const std::string range = "push_constant_bytes " + std::to_string(bytes);
    if (push && bytes == 0) {
        *error = "binding map '" + bindings.map + "': '" + push->name +
                 "' is a push constant but the map states no push_constant_bytes";
        return std::nullopt;
    }
    // Vulkan: a range's size is a multiple of 4 (VUID-VkPushConstantRange-size-00297).
    if (bytes % 4 != 0 || bytes > kMaxPushConstantRange) {
        *error = "binding map '" + bindings.map + "': " + range +
                 "; expected a multiple of 4 up to " + std::to_string(kMaxPushConstantRange);
        return std::nullopt;
    }
    if (bytes > max_push_constants_size) {
        *error = "binding map '" + bindings.map + "': " + range +
                 " exceed the device's maxPushConstantsSize " +
                 std::to_string(max_push_constants_size);
        return std::nullopt;
    }
    BindingLayout l;
    l.device_ = device;
    l.bindings_ = bindings;
    if (bytes)
        l.push_range_ = {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, bytes};
    if (push) l.push_block_ = push->name;
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    std::vector<std::vector<VkDescriptorSetLayoutBinding>> per_set(sets);
    for (const auto& [key, s] : taken)
        per_set[key.first].push_back({key.second, descriptor_type(s->kind), 1, stages, nullptr});
    for (const auto& entries : per_set) {
        VkDescriptorSetLayoutCreateInfo ci{};
        ci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
        ci.bindingCount = static_cast<uint32_t>(entries.size());
        ci.pBindings = entries.data();
        VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
        if (VkResult r = vkCreateDescriptorSetLayout(device, &ci, nullptr, &set_layout);
            r != VK_SUCCESS) {
            *error = failed("vkCreateDescriptorSetLayout", r);
            return std::nullopt;
        }
        l.set_layouts_.push_back(set_layout);
    }
    VkPipelineLayoutCreateInfo lci{};
    lci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    lci.setLayoutCount = sets;
    lci.pSetLayouts = l.set_layouts_.data();
    lci.pushConstantRangeCount = bytes ? 1 : 0;
    lci.pPushConstantRanges = bytes ? &l.push_range_ : nullptr;
    if (VkResult r = vkCreatePipelineLayout(device, &lci, nullptr, &l.layout_); r != VK_SUCCESS) {
        *error = failed("vkCreatePipelineLayout", r);
        return std::nullopt;
    }
    return l;
}

std::vector<VkDescriptorPoolSize> BindingLayout::pool_sizes(uint32_t copies) const {
    std::vector<DescriptorKind> kinds;
    for (const MapSlot& s : bindings_.slots)
        if (s.kind != DescriptorKind::PushConstant) kinds.push_back(s.kind);
    return pool_sizes_of(kinds, copies);
}

std::string BindingLayout::check(const Reflection& r) const {
    for (const DescriptorBinding& b : r.bindings) {
        const MapSlot* s = bindings_.find(b.name);
        const std::string what = std::string(to_string(r.stage)) + " stage: " + to_string(b.kind) +
                                 " '" + b.name + "' at " + place(b.set, b.binding);
        if (!s) return what + " is no slot of the binding map '" + bindings_.map + "'";
        if (s->kind == DescriptorKind::PushConstant)
            return what + "; the binding map '" + bindings_.map +
                   "' has it as a push constant (no descriptor): the shader was not emitted "
                   "with this map";
        if (s->set != b.set || s->binding != b.binding || s->kind != b.kind)
            return what + "; the binding map '" + bindings_.map + "' has it as " +
                   to_string(s->kind) + " at " + place(s->set, s->binding);
    }
    if (!r.push_constant) return "";
    const DescriptorBinding& p = *r.push_constant;
    const std::string what = std::string(to_string(r.stage)) + " stage: push-constant block '" +
                             p.name + "' (" + std::to_string(p.block_size) + " bytes)";
    if (!push_range_.size)
        return what + "; the binding map '" + bindings_.map + "' has no push-constant range";
    if (p.name != push_block_) {
        const MapSlot* s = bindings_.find(p.name);
        return what + "; the binding map '" + bindings_.map + "' pushes " +
               (push_block_.empty() ? "no block" : "'" + push_block_ + "'") +
               (s ? " and has '" + p.name + "' as " + to_string(s->kind) + " at " +
                        place(s->set, s->binding)
                  : "");
    }
    if (p.block_size > push_range_.size)
        return what + " does not fit the push-constant range of " +
               std::to_string(push_range_.size) + " bytes of the binding map '" + bindings_.map +
               "'";
    return "";
}

} // namespace watergen

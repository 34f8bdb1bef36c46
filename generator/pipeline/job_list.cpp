#include "watergen/pipeline/job_list.h"

#include <algorithm>
#include <numeric>

#include "watergen/plan/variant_space.h"

namespace watergen {

std::string job_key(const BuildJob& job) {
    return job.shader ? job.shader->key() : job.variant.key();
}

JobList JobList::compact(const std::string& scene, const VariantSpace& space,
                         const std::vector<Target>& targets,
                         const std::function<bool(const std::string& key)>& keep) {
    Compact c{scene, space.choices, targets, 0, {}};
    const size_t axes = space.choices.size();
    Variant v = default_variant();
    auto fill = [&](Variant& into, const uint8_t* index) {
        for (size_t a = 0; a < axes; ++a)
            into.choices[a] = c.choices[a][index[a]];
    };
    enumerate_indices(space, [&](const std::vector<size_t>& index) {
        for (size_t a = 0; a < axes; ++a)
            v.choices[a] = space.choices[a][index[a]];
        if (!keep(v.key())) return;
        for (size_t a = 0; a < axes; ++a)
            c.indices.push_back(static_cast<uint8_t>(index[a])); // an axis offers < 256 choices
        ++c.count;
    });
    // Sorted by key, the keys made as the sort compares them: holding one per job would be most
    // of the list's memory while it is sorted.
    std::vector<uint32_t> order(c.count);
    std::iota(order.begin(), order.end(), 0u);
    Variant a = v, b = v;
    std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) {
        fill(a, &c.indices[x * axes]);
        fill(b, &c.indices[y * axes]);
        return a.key() < b.key();
    });
    std::vector<uint8_t> sorted(c.indices.size());
    for (size_t k = 0; k < order.size(); ++k)
        std::copy_n(&c.indices[order[k] * axes], axes, &sorted[k * axes]);
    c.indices = std::move(sorted);
    JobList list;
    list.compact_ = std::move(c);
    return list;
}

BuildJob JobList::at(size_t i) const {
    if (!compact_) return held_[i];
    const Compact& c = *compact_;
    const size_t axes = c.choices.size();
    BuildJob job{c.scene, default_variant(), nullptr, c.targets};
    for (size_t a = 0; a < axes; ++a)
        job.variant.choices[a] = c.choices[a][c.indices[i * axes + a]];
    return job;
}

std::vector<BuildJob> JobList::range(size_t begin, size_t end) const {
    std::vector<BuildJob> jobs;
    jobs.reserve(end - begin);
    for (size_t i = begin; i < end; ++i)
        jobs.push_back(at(i));
    return jobs;
}

} // namespace watergen

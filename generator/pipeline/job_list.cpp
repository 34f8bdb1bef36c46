#include "watergen/pipeline/job_list.h"

#include "watergen/plan/variant_space.h"

namespace watergen {

std::string job_key(const BuildJob& job) {
    return job.shader ? job.shader->key() : job.variant.key();
}

JobList JobList::compact(const std::string& scene, const VariantSpace& space,
                         const std::vector<Target>& targets,
                         const std::function<bool(const std::string& key)>& keep) {
    Compact c{scene, VariantList(space.choices), targets};
    Variant v = default_variant();
    enumerate_indices(space, [&](const std::vector<size_t>& index) {
        for (size_t a = 0; a < index.size(); ++a)
            v.choices[a] = space.choices[a][index[a]];
        if (keep(v.key())) c.variants.add(index);
    });
    c.variants.sort_by_key();
    JobList list;
    list.compact_ = std::move(c);
    return list;
}

BuildJob JobList::at(size_t i) const {
    if (!compact_) return held_[i];
    return {compact_->scene, compact_->variants.at(i), nullptr, compact_->targets};
}

std::vector<BuildJob> JobList::range(size_t begin, size_t end) const {
    std::vector<BuildJob> jobs;
    jobs.reserve(end - begin);
    for (size_t i = begin; i < end; ++i)
        jobs.push_back(at(i));
    return jobs;
}

} // namespace watergen

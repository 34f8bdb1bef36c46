#include "watergen/pipeline/jobs/job_list.h"

#include <algorithm>
#include <iterator>

#include "watergen/plan/variant_space.h"

namespace watergen {

std::string job_key(const BuildJob& job) {
    return job.shader ? job.shader->key() : job.variant.key();
}

JobList JobList::compact(const std::string& scene, const VariantSpace& space,
                         const std::vector<Target>& targets,
                         const std::function<bool(const std::string& key)>& keep) {
    VariantList kept(space.choices);
    Variant v = default_variant();
    enumerate_indices(space, [&](const std::vector<size_t>& index) {
        for (size_t a = 0; a < index.size(); ++a)
            v.choices[a] = space.choices[a][index[a]];
        if (keep(v.key())) kept.add(index);
    });
    kept.sort_by_key();
    JobList list;
    list.add_compact(scene, std::move(kept), nullptr, targets);
    return list;
}

void JobList::add_scene(const std::string& scene, const VariantList& variants,
                        const FoldFacts* facts, const std::vector<Target>& targets,
                        const std::function<bool(const std::string& key)>& keep) {
    VariantList kept(variants.choices());
    Variant v = default_variant();
    for (size_t i = 0; i < variants.size(); ++i) {
        variants.fill(i, v);
        if (keep(v.key())) kept.add_from(variants, i);
    }
    add_compact(scene, std::move(kept), facts, targets);
}

void JobList::add_compact(const std::string& scene, VariantList variants, const FoldFacts* facts,
                          const std::vector<Target>& targets) {
    const size_t count = variants.size();
    compact_.push_back({scene, std::move(variants), facts, targets, compact_count_});
    compact_count_ += count;
}

BuildJob JobList::at(size_t i) const {
    if (i < held_.size()) return held_[i];
    i -= held_.size();
    // The scene whose jobs hold i: the last to start at or before it.
    const auto c = std::prev(
        std::upper_bound(compact_.begin(), compact_.end(), i,
                         [](size_t job, const Compact& scene) { return job < scene.first; }));
    return {c->scene, c->variants.at(i - c->first), c->facts, c->targets};
}

std::vector<BuildJob> JobList::range(size_t begin, size_t end) const {
    std::vector<BuildJob> jobs;
    jobs.reserve(end - begin);
    for (size_t i = begin; i < end; ++i)
        jobs.push_back(at(i));
    return jobs;
}

} // namespace watergen

// The jobs of a build, by index, sorted by (scene, key). A list holds its jobs (a scene's
// variants, a modes build's shaders), or, for the material's whole space unpruned, keeps each
// variant as one byte an axis and makes its job when asked: about 20 bytes a job where a held
// one (its Variant's strings) takes about 700, so that the jobs of the whole space, 3.5
// million, are not what bounds a build's memory.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "watergen/ir/fold/ir_fold.h"
#include "watergen/plan/material.h"
#include "watergen/plan/variant_list.h"

namespace watergen {

struct BuildJob {
    std::string scene; // output directory of the scene
    Variant variant;
    const FoldFacts* facts = nullptr; // fold under these; nullptr builds the variant as composed
    std::vector<Target> targets;
    // Set in the specialized and branching modes: the job builds this shader, which draws the
    // variants of `serves` (sorted by key; shared by the job's copies); `variant` is the one
    // its selectors' defaults draw.
    std::optional<ShaderChoices> shader = std::nullopt;
    std::shared_ptr<const VariantList> serves = nullptr;
};

// The job's key: its variant's, or its shader's (ShaderChoices::key).
std::string job_key(const BuildJob& job);

class JobList {
  public:
    JobList() = default;
    // Held jobs, as given (sorted by the caller).
    explicit JobList(std::vector<BuildJob> jobs) : held_(std::move(jobs)) {}
    // Unfolded jobs of one scene for the variants of `space` that `keep` accepts (given each
    // variant's key), sorted by key, kept a byte an axis.
    static JobList compact(const std::string& scene, const VariantSpace& space,
                           const std::vector<Target>& targets,
                           const std::function<bool(const std::string& key)>& keep);
    // Appends the jobs of one scene (after those of the scenes before it): the variants of
    // `variants` (sorted by key) that `keep` accepts, folded under `facts`, kept a byte an axis.
    void add_scene(const std::string& scene, const VariantList& variants, const FoldFacts* facts,
                   const std::vector<Target>& targets,
                   const std::function<bool(const std::string& key)>& keep);

    size_t size() const { return held_.size() + compact_count_; }
    bool empty() const { return size() == 0; }
    BuildJob at(size_t i) const;
    std::vector<BuildJob> range(size_t begin, size_t end) const;
    // A held list's jobs; empty for a compact one.
    const std::vector<BuildJob>& held() const { return held_; }
    void push_back(BuildJob job) { held_.push_back(std::move(job)); }

  private:
    // Appends a scene's jobs of `variants` as they are.
    void add_compact(const std::string& scene, VariantList variants, const FoldFacts* facts,
                     const std::vector<Target>& targets);
    struct Compact {
        std::string scene;
        VariantList variants; // the jobs' variants, sorted by key
        const FoldFacts* facts = nullptr;
        std::vector<Target> targets;
        size_t first = 0; // the list's index of its first job
    };
    std::vector<BuildJob> held_;
    std::vector<Compact> compact_; // one per scene, in order
    size_t compact_count_ = 0;
};

} // namespace watergen

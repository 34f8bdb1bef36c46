// The covering set built once per test binary (each build runs the whole toolchain twice per
// stage); test cases that only read the builds share it.
#pragma once

#include <vector>

#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/covering_array.h"

namespace watergen::test {

inline const std::vector<VariantBuild>& covering_builds() {
    static const std::vector<VariantBuild> builds = [] {
        std::vector<VariantBuild> out;
        for (const Variant& v : pairwise_covering_variants())
            out.push_back(build_variant(v));
        return out;
    }();
    return builds;
}

} // namespace watergen::test

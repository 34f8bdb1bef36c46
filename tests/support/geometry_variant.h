// The default variant drawn as a geometry (mesh or tessellated) with closed-form waves and their
// analytic normals: what the geometry tests build.
#pragma once

#include <string>
#include <utility>

#include <catch2/catch.hpp>

#include "watergen/water/variant.h"

namespace watergen::test {

inline Variant geometry_variant(const std::string& geometry, const std::string& model) {
    Variant v = default_variant();
    for (const auto& [axis, choice] : {std::pair<std::string, std::string>{"geometry", geometry},
                                       {"waves", model},
                                       {"normals", "analytic"}})
        REQUIRE_FALSE(set_choice(v, axis, choice));
    return v;
}

} // namespace watergen::test

// README.md of the source tree, for tests that hold a hand-written figure of it against the
// code (WATERGEN_SOURCE_DIR is set for every test by tests/CMakeLists.txt).
#pragma once

#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace watergen::test {

inline std::string readme_text() {
    const char* root = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(root);
    std::ifstream in(std::string(root) + "/README.md");
    REQUIRE(in);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The same with every run of whitespace made one space, so a sentence matches across lines.
inline std::string readme_prose() {
    std::string out;
    for (char c : readme_text()) {
        const bool space = c == ' ' || c == '\n';
        if (space && (out.empty() || out.back() == ' ')) continue;
        out += space ? ' ' : c;
    }
    return out;
}

} // namespace watergen::test

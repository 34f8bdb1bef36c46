// A page of the manual (docs/<page>.md of the source tree), for tests that hold a hand-written
// figure or table of it against the code (WATERGEN_SOURCE_DIR is set for every test by
// tests/CMakeLists.txt).
#pragma once

#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace watergen::test {

// The text of docs/<page>, e.g. doc_text("user-guide.md").
inline std::string doc_text(const std::string& page) {
    const char* root = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(root);
    std::ifstream in(std::string(root) + "/docs/" + page);
    INFO("docs/" << page);
    REQUIRE(in);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The same with every run of whitespace made one space, so a sentence matches across lines.
inline std::string doc_prose(const std::string& page) {
    std::string out;
    for (char c : doc_text(page)) {
        const bool space = c == ' ' || c == '\n';
        if (space && (out.empty() || out.back() == ' ')) continue;
        out += space ? ' ' : c;
    }
    return out;
}

// docs/user-guide.md: the axes, the space, scenes, views, the CLI.
inline std::string user_guide_text() {
    return doc_text("user-guide.md");
}
inline std::string user_guide_prose() {
    return doc_prose("user-guide.md");
}
// README.md, the front page, one space for each run of whitespace.
inline std::string readme_prose() {
    return doc_prose("../README.md");
}

} // namespace watergen::test

// Relative output paths in 8 bytes each: a path is two interned parts, its job directory
// (<scene>/<job>/, the same for a job's twenty-odd files and most of each path) and the rest
// ("" and the whole path for a file at the top level). The staging tree keeps what it wrote
// this way, and the merge each shard's file list.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <unordered_map>

namespace watergen {

class PathParts {
  public:
    struct Path {
        uint32_t directory = 0, rest = 0;
    };
    Path intern(std::string_view relative);
    std::string text(Path p) const;
    // Path order (the order of text()), without making either text.
    bool less(Path a, Path b) const;
    // <0, 0 or >0 as text(p) is before, equal to or after `relative`.
    int compare(Path p, std::string_view relative) const;

  private:
    uint32_t part(std::string_view text);
    std::deque<std::string> parts_; // stable: ids_ views them
    std::unordered_map<std::string_view, uint32_t> ids_;
};

} // namespace watergen

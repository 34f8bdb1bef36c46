#include "watergen/pipeline/output/path_parts.h"

#include <algorithm>

namespace watergen {

uint32_t PathParts::part(std::string_view text) {
    if (const auto it = ids_.find(text); it != ids_.end()) return it->second;
    parts_.emplace_back(text);
    const auto id = static_cast<uint32_t>(parts_.size() - 1);
    ids_.emplace(parts_.back(), id);
    return id;
}

PathParts::Path PathParts::intern(std::string_view relative) {
    const size_t first = relative.find('/');
    const size_t second = first == std::string_view::npos ? first : relative.find('/', first + 1);
    const size_t split = second == std::string_view::npos ? 0 : second + 1;
    const uint32_t directory = part(relative.substr(0, split));
    return {directory, part(relative.substr(split))};
}

std::string PathParts::text(Path p) const {
    return parts_[p.directory] + parts_[p.rest];
}

bool PathParts::less(Path a, Path b) const {
    const std::string &ad = parts_[a.directory], &bd = parts_[b.directory];
    if (a.directory == b.directory) return parts_[a.rest] < parts_[b.rest];
    // Two job directories (each <scene>/<job>/) are never one the other's prefix: their order
    // is their paths'. A top-level file ("" directory) is compared whole.
    if (!ad.empty() && !bd.empty()) return ad < bd;
    return ad + parts_[a.rest] < bd + parts_[b.rest];
}

int PathParts::compare(Path p, std::string_view relative) const {
    const std::string_view directory = parts_[p.directory];
    const size_t head = std::min(directory.size(), relative.size());
    if (const int c = directory.compare(0, head, relative.substr(0, head)); c != 0) return c;
    if (directory.size() > relative.size()) return 1; // `relative` is a prefix of the directory
    return std::string_view(parts_[p.rest]).compare(relative.substr(directory.size()));
}

} // namespace watergen

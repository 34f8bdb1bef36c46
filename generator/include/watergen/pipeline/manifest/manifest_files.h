// The files a build's manifest.json names: each variant's "files" lists and its passes'. A
// merge checks them against the files a shard holds, and the no-op check against the files the
// build record verifies, so that neither can report an output whole that lacks one.
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace watergen {

// Every file path the manifest entry `entry` names (its "files" lists, its passes' "files"
// lists, a frozen variant's modules), each checked to be plain and inside the "directory" (or
// "shader") beside it; "" or why not.
std::string named_files(const nlohmann::ordered_json& entry, std::vector<std::string>& paths);

// named_files of every variant (and a modes build's every shader) of the manifest `bytes`; ""
// or why not (not a manifest).
std::string manifest_named_files(const std::string& bytes, std::vector<std::string>& paths);
// The same, read from `in` one variant at a time, each path handed to `each` (a manifest of
// many variants is larger than the memory its document would take).
std::string manifest_named_files(std::FILE* in, const std::function<void(std::string&&)>& each);

} // namespace watergen

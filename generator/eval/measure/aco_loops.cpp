#include "watergen/eval/measure/aco_loops.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <sstream>

namespace watergen {

namespace {

std::string trim(const std::string& s) {
    size_t b = 0, e = s.size();
    while (b < e && std::isspace(static_cast<unsigned char>(s[b])))
        ++b;
    while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1])))
        --e;
    return s.substr(b, e - b);
}

// "BB12:" -> 12; -1 for any other line.
long label_of(const std::string& line) {
    if (line.size() < 4 || line.compare(0, 2, "BB") != 0 || line.back() != ':') return -1;
    const std::string digits = line.substr(2, line.size() - 3);
    if (digits.empty() || !std::all_of(digits.begin(), digits.end(), ::isdigit)) return -1;
    return std::stol(digits);
}

// The label a branch names ("s_cbranch_vccz BB7" -> 7), -1 for another instruction.
long branch_target(const std::string& mnemonic, const std::string& rest) {
    if (mnemonic != "s_branch" && mnemonic.compare(0, 10, "s_cbranch_") != 0) return -1;
    const size_t at = rest.find("BB");
    if (at == std::string::npos) return -1;
    size_t end = at + 2;
    while (end < rest.size() && std::isdigit(static_cast<unsigned char>(rest[end])))
        ++end;
    return end == at + 2 ? -1 : std::stol(rest.substr(at + 2, end - at - 2));
}

} // namespace

std::optional<AsmListing> read_aco_listing(const std::string& disassembly, std::string* error) {
    std::map<long, uint32_t> label_at;               // label -> index of the instruction after it
    std::vector<std::pair<uint32_t, long>> branches; // (instruction index, target label)
    uint32_t count = 0;
    std::istringstream in(disassembly);
    std::string raw;
    while (std::getline(in, raw)) {
        const std::string line = trim(raw.substr(0, raw.find(';'))); // encodings follow ';'
        if (line.empty() || line[0] == '/' || line[0] == '(') continue;
        if (const long l = label_of(line); l >= 0) {
            label_at[l] = count;
            continue;
        }
        const size_t space = line.find_first_of(" \t");
        const std::string mnemonic = line.substr(0, space);
        if (!std::all_of(mnemonic.begin(), mnemonic.end(),
                         [](char c) { return std::islower(c) || std::isdigit(c) || c == '_'; }))
            continue;                           // not an instruction (a constant-data line)
        if (mnemonic == "s_code_end") continue; // padding after the program
        const long target =
            branch_target(mnemonic, space == std::string::npos ? "" : line.substr(space));
        if (target >= 0) branches.emplace_back(count, target);
        ++count;
    }
    AsmListing out;
    out.instructions = count;
    std::map<uint32_t, uint32_t> back_edges; // header index -> last back branch
    for (const auto& [at, target] : branches) {
        const auto it = label_at.find(target);
        if (it == label_at.end()) {
            *error = "a branch to BB" + std::to_string(target) + ", a label the listing lacks";
            return std::nullopt;
        }
        if (it->second <= at) back_edges[it->second] = std::max(back_edges[it->second], at);
    }
    std::vector<AsmLoop> open; // the loops around the current header
    for (const auto& [first, last] : back_edges) {
        while (!open.empty() && open.back().last < first)
            open.pop_back();
        if (!open.empty() && last > open.back().last) {
            *error = "loops that overlap without nesting";
            return std::nullopt;
        }
        AsmLoop loop{first, last, last - first + 1, static_cast<uint32_t>(open.size())};
        out.loops.push_back(loop);
        open.push_back(loop);
    }
    return out;
}

std::optional<double> weighted_instructions(const AsmListing& listing,
                                            const std::vector<double>& trip_counts) {
    if (trip_counts.size() != listing.loops.size()) return std::nullopt;
    // Every instruction counts once, and each loop adds its body (trip - 1) more times per run
    // of what encloses it: so weights multiply down the nest.
    std::vector<double> weight(listing.instructions, 1.0);
    for (size_t k = 0; k < listing.loops.size(); ++k)
        for (uint32_t i = listing.loops[k].first; i <= listing.loops[k].last; ++i)
            weight[i] *= trip_counts[k];
    double total = 0;
    for (double w : weight)
        total += w;
    return total;
}

} // namespace watergen

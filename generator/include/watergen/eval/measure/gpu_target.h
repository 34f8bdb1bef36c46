// The targets a cost is measured for: lavapipe (the instructions valgrind counts in its CPU
// code, and timed draws) and AMD GPU families, each compiled by ACO on RADV's null device
// (aco_device.h). A family is named by its architecture; the Steam Deck's APU (Van Gogh) runs
// RDNA2's instruction set, so `steamdeck` is rdna2 under another name.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace watergen {

struct GpuTarget {
    std::string name;     // "lavapipe", "gcn1", ..., "rdna3"
    std::string family;   // RADV_FORCE_FAMILY: "navi21"; "" for lavapipe
    std::string isa;      // what the name stands for: "RDNA2 (gfx10.3)"
    std::string alias_of; // "rdna2" for steamdeck: the same compiler output; "" otherwise
    // Mesa disassembles gfx6 through CLRX, which Debian does not package: no listing, so no
    // per-pixel estimate of loops (the static count stands in).
    bool disassembly = true;
    bool is_lavapipe() const { return family.empty(); }
};

// Every target: lavapipe, then the families oldest first, then the aliases.
const std::vector<GpuTarget>& gpu_targets();
const GpuTarget* find_gpu_target(const std::string& name);
// "lavapipe, gcn1, ..., steamdeck": for help texts and errors.
std::string gpu_target_names();
// "gcn1, ..., steamdeck": the AMD families alone (what a driver check compiles on).
std::string amd_target_names();

// The targets `words` name (each a name or a comma-separated list, as --target repeated or
// --target a,b), in the order given, each once; an alias stays itself (its costs are its
// ISA's). nullopt and *error (naming `flag`) for an unknown word or an empty name ("", "a,,b"):
// a list that names nothing is refused, never read as the default.
std::optional<std::vector<GpuTarget>> parse_gpu_targets(const std::vector<std::string>& words,
                                                        std::string* error,
                                                        const std::string& flag = "--target");

// The AMD families among `targets` (lavapipe left out), and whether lavapipe is among them.
std::vector<GpuTarget> amd_targets(const std::vector<GpuTarget>& targets);
bool has_lavapipe(const std::vector<GpuTarget>& targets);

} // namespace watergen

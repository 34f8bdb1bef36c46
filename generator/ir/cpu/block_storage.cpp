#include "block_storage.h"

#include <algorithm>
#include <map>

namespace watergen {

uint32_t StorageTimeline::add(uint32_t size, bool permanent) {
    slots_.push_back({(size + 15) / 16 * 16, permanent}); // 64-byte rows of floats
    return static_cast<uint32_t>(slots_.size() - 1);
}

void StorageTimeline::write(uint32_t slot, size_t at) {
    slots_[slot].written = at;
    slots_[slot].last_read = std::max(slots_[slot].last_read, at);
}

void StorageTimeline::read(const Operand& o, size_t at) {
    if (o.slot == UINT32_MAX || slots_[o.slot].permanent) return;
    slots_[o.slot].last_read = std::max(slots_[o.slot].last_read, at);
    if (!loops_.empty()) loops_.back().push_back(o.slot);
}

void StorageTimeline::close_loop(size_t start, size_t end) {
    const std::vector<uint32_t> reads = std::move(loops_.back());
    loops_.pop_back();
    for (uint32_t s : reads)
        if (slots_[s].written < start) read(Operand{0, 0, 0, s}, end);
}

// Prologue values first, each for good; then the others in order of the timeline, each taking
// the place of a value of its size read for the last time before it is written.
std::vector<uint32_t> StorageTimeline::offsets() const {
    std::vector<uint32_t> offset(slots_.size(), 0);
    uint32_t top = 0;
    // One position more than used: the program may be placed while it is being compiled, with
    // slots defined but not yet written (block_program.cpp runs the prologue so far).
    std::vector<std::vector<uint32_t>> writes(next_ + 1), frees(next_ + 1);
    for (uint32_t s = 0; s < slots_.size(); ++s) {
        if (slots_[s].permanent) {
            offset[s] = top;
            top += slots_[s].size;
            continue;
        }
        writes[slots_[s].written].push_back(s);
        frees[std::max(slots_[s].last_read, slots_[s].written)].push_back(s);
    }
    std::map<uint32_t, std::vector<uint32_t>> free_places; // by size
    for (size_t at = 0; at <= next_; ++at) {
        for (uint32_t s : writes[at]) {
            auto& places = free_places[slots_[s].size];
            if (places.empty()) {
                offset[s] = top;
                top += slots_[s].size;
            } else {
                offset[s] = places.back();
                places.pop_back();
            }
        }
        for (uint32_t s : frees[at])
            free_places[slots_[s].size].push_back(offset[s]);
    }
    offset.push_back(top); // the arena's size
    return offset;
}

void StorageTimeline::place(Program& program) const {
    const std::vector<uint32_t> offset = offsets();
    program.arena = offset.back();
    auto place = [&](Operand& o) {
        if (o.slot != UINT32_MAX) o.offset += offset[o.slot];
    };
    auto place_list = [&](std::vector<Instr>& list) {
        for (Instr& ins : list) {
            place(ins.out);
            for (Operand& a : ins.args)
                place(a);
        }
    };
    place_list(program.prologue);
    place_list(program.main);
    for (LoopPlan& loop : program.loops) {
        place_list(loop.body);
        for (auto& c : loop.carried) {
            place(c.storage);
            place(c.initial);
            place(c.next);
        }
        place(loop.keep_going);
        place(loop.count);
    }
    for (Operand& o : program.gathers)
        place(o);
    place(program.root);
}

} // namespace watergen

// Where a compiled program's values lie in the arena (block_program.h): every value gets a
// slot while the program is compiled; when it is done, slots are placed so that a value's place
// is reused once it has been read for the last time. Private to ir/.
#pragma once

#include <cstdint>
#include <vector>

#include "block_program.h"

namespace watergen {

// The storage timeline: instructions in the order they run get consecutive positions; a slot
// is written at one position and read at others. A loop body's instructions run again and
// again between the loop's start and end, so a value of the enclosing code read inside the
// body is alive until the loop ends.
class StorageTimeline {
  public:
    // A slot of `size` values; a permanent one (the prologue's) is never reused.
    uint32_t add(uint32_t size, bool permanent);
    // The next position.
    size_t step() { return next_++; }
    void write(uint32_t slot, size_t at);
    void read(const Operand& o, size_t at);

    // Reads between open_loop() and close_loop() are inside a loop body that runs from
    // position `start` to `end`.
    void open_loop() { loops_.emplace_back(); }
    void close_loop(size_t start, size_t end);

    // Places every slot and resolves every operand of the program to its offset; sets
    // Program::arena. Permanent slots are placed first, in the order they were added, so their
    // places are final even when a program is placed before it is compiled to the end.
    void place(Program& program) const;

  private:
    struct Slot {
        uint32_t size = 0;
        bool permanent = false;
        size_t written = 0, last_read = 0;
    };
    std::vector<uint32_t> offsets() const;

    std::vector<Slot> slots_;
    size_t next_ = 0;
    std::vector<std::vector<uint32_t>> loops_; // per open loop, the slots read inside
};

} // namespace watergen

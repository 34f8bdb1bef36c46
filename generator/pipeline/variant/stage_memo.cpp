#include "watergen/pipeline/variant/stage_memo.h"

#include <algorithm>
#include <memory>

#include <fmt/format.h>
#include <xxhash.h>

#include "watergen/ir/emit/emitter.h"

namespace watergen {

namespace {

size_t bytes_of(const ToolchainOutputs& t) {
    size_t n = (t.spirv.size() + t.spirv_optimized.size()) * sizeof(uint32_t) + t.glsl330.size() +
               t.essl300.size() + t.msl.size();
    for (const Diagnostic& d : t.diagnostics)
        n += d.message.size() + d.file.size();
    return n + 4096; // the reflection, roughly
}

// The key of `request` compiled from `blank_source` (its source with the stamp blank).
StageKey key_of(const CompileRequest& request, const std::string& blank_source,
                CrossCompile cross) {
    std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state(XXH3_createState(),
                                                                          XXH3_freeState);
    XXH3_128bits_reset(state.get());
    auto feed = [&](const std::string& part) { // length first: no two splits hash alike
        const uint64_t n = part.size();
        XXH3_128bits_update(state.get(), &n, sizeof n);
        XXH3_128bits_update(state.get(), part.data(), part.size());
    };
    feed(fmt::format("{}|{}|{}|{}|{}", static_cast<int>(request.language),
                     static_cast<int>(request.stage), request.hlsl_16bit_types,
                     cross == CrossCompile::Yes, request.entry_point));
    feed(request.file_name);
    std::string msl;
    for (const MslSlot& m : request.msl_bindings)
        msl += fmt::format("{},{},{};", m.set, m.binding, m.index);
    feed(msl);
    feed(blank_source);
    const XXH128_hash_t h = XXH3_128bits_digest(state.get());
    return {h.high64, h.low64};
}

} // namespace

std::string blank_stamp(const std::string& source, const std::string& variant_key) {
    if (variant_key.empty()) return source;
    const std::string stamp = stamp_text(variant_key);
    const size_t at = source.find(stamp);
    if (at == std::string::npos) return source;
    std::string blank = source;
    blank.replace(at, stamp.size(), stamp_text(""));
    return blank;
}

StageKey stage_key(const CompileRequest& request, CrossCompile cross,
                   const std::string& variant_key) {
    return key_of(request, blank_stamp(request.source, variant_key), cross);
}

void StageMemo::expect(std::vector<StageKey> keys) {
    std::sort(keys.begin(), keys.end());
    std::lock_guard<std::mutex> hold(lock_);
    for (size_t i = 0, j = 0; i < keys.size(); i = j) {
        while (j < keys.size() && keys[j] == keys[i])
            ++j;
        if (j - i > 1) entries_[keys[i]].expected += j - i;
    }
}

ToolchainOutputs StageMemo::take(std::map<StageKey, Entry>::iterator it) {
    ++counts_.reused;
    if (--it->second.expected > 0) return it->second.outputs;
    ToolchainOutputs last = std::move(it->second.outputs);
    held_bytes_ -= it->second.bytes;
    entries_.erase(it);
    return last;
}

ToolchainOutputs StageMemo::run(const CompileRequest& request, CrossCompile cross,
                                const std::string& variant_key) {
    CompileRequest blank = request;
    blank.source = blank_stamp(request.source, variant_key);
    const StageKey key = key_of(request, blank.source, cross);
    std::unique_lock<std::mutex> hold(lock_);
    for (;;) {
        auto it = entries_.find(key);
        if (it == entries_.end()) break;
        Entry& e = it->second;
        if (e.state == Entry::State::Done) return take(it);
        if (e.state == Entry::State::Waiting && e.expected < 2) { // nobody else will ask
            entries_.erase(it);
            break;
        }
        if (e.state == Entry::State::Waiting) {
            e.state = Entry::State::Compiling;
            hold.unlock();
            ToolchainOutputs outputs = run_toolchain(blank, cross);
            hold.lock();
            ++counts_.compiled;
            it = entries_.find(key); // still there: only its compiler or its last use erases it
            const size_t bytes = bytes_of(outputs);
            if (held_bytes_ + bytes > max_bytes_) {
                // Not kept: the variants still to come compile it themselves.
                entries_.erase(it);
                done_.notify_all();
                return outputs;
            }
            held_bytes_ += bytes;
            it->second.bytes = bytes;
            it->second.outputs = outputs;
            it->second.state = Entry::State::Done;
            --it->second.expected;
            done_.notify_all();
            return outputs;
        }
        done_.wait(hold); // another thread compiles it: look again when it is done
    }
    hold.unlock();
    ToolchainOutputs outputs = run_toolchain(blank, cross);
    hold.lock();
    ++counts_.compiled;
    return outputs;
}

size_t StageMemo::entries() const {
    std::lock_guard<std::mutex> hold(lock_);
    return entries_.size();
}

StageCounts StageMemo::counts() const {
    std::lock_guard<std::mutex> hold(lock_);
    return counts_;
}

} // namespace watergen

// Lane-invariant carried values (block_invariance.h).
#include "block_invariance.h"

#include <unordered_map>

namespace watergen {

namespace {

// Per node of a loop body `g`: whether it is lane-invariant, given its captured and carried
// values'. Derivatives and varyings vary; loops nested in the body follow their own carried
// values.
std::vector<char> invariant_nodes(const Graph& g, const std::vector<char>& captured,
                                  const std::vector<char>& carried) {
    std::vector<char> invariant(g.size(), 0);
    std::unordered_map<uint32_t, std::vector<char>> loops; // carried values, by Loop node
    for (uint32_t id : g.live_nodes()) {
        const Node& n = g.node(id);
        bool same = true;
        for (uint32_t a : n.args)
            same = same && invariant[a];
        switch (n.op) {
        case Op::Varying:
        case Op::Ddx:
        case Op::Ddy:
        case Op::Switch:
        case Op::SwitchResult:
            same = false;
            break;
        case Op::Captured:
            same = captured[static_cast<size_t>(n.values[0])];
            break;
        case Op::Carried:
            same = carried[static_cast<size_t>(n.values[0])];
            break;
        case Op::Loop: {
            std::vector<char> args;
            for (uint32_t a : n.args)
                args.push_back(invariant[a]);
            loops[id] = invariant_carried(n, args);
            break;
        }
        case Op::LoopResult:
            same = loops.at(n.args[0])[static_cast<size_t>(n.values[0])];
            break;
        default:
            break;
        }
        invariant[id] = same;
    }
    return invariant;
}

} // namespace

std::vector<char> invariant_carried(const Node& loop, const std::vector<char>& args) {
    const LoopBody& body = *loop.loop;
    std::vector<char> carried(args.begin(), args.begin() + static_cast<long>(body.carried()));
    if (body.has_exit) return std::vector<char>(body.carried(), 0);
    const std::vector<char> captured(args.begin() + static_cast<long>(body.first_capture()),
                                     args.end());
    for (bool dropped = true; dropped;) {
        dropped = false;
        const std::vector<char> invariant = invariant_nodes(*body.body, captured, carried);
        size_t k = 0;
        for (const auto& o : body.body->outputs()) {
            if (o.name == "continue") continue;
            if (carried[k] && !invariant[o.node]) {
                carried[k] = 0;
                dropped = true;
            }
            ++k;
        }
    }
    return carried;
}

} // namespace watergen

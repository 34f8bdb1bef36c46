// BlockEvaluator's driver: node order, lane-invariant nodes, storage reuse, and loops (the
// operations themselves are in block_evaluator_ops.cpp).
#include "block_evaluator.h"

#include <algorithm>

namespace watergen {

// A Loop node's body: its live nodes, the frame its leaves read and the evaluator that runs it
// (kept across blocks, so its lane-invariant nodes are computed once).
struct BlockEvaluator::LoopState {
    std::vector<uint32_t> live;
    LoopFrame frame;
    std::unique_ptr<BlockEvaluator> body;
    std::vector<uint32_t> next; // body node of each carried value's next value
    uint32_t keep_going = UINT32_MAX;
};

namespace {

// Leaves whose values change from block to block, or from iteration to iteration of a loop.
bool varies(Op op) {
    return op == Op::Varying || op == Op::Ddx || op == Op::Ddy || op == Op::Loop ||
           op == Op::LoopIndex || op == Op::Carried || op == Op::Captured || op == Op::Switch;
}

} // namespace

BlockEvaluator::BlockEvaluator(const Graph& g, const Graph& params,
                               const std::vector<uint32_t>& live, const EvalInputs& in,
                               EvalPrecision p, const std::vector<uint32_t>& keep,
                               const LoopFrame* frame)
    : g_(g), params_(params), live_(live), in_(in), p_(p), frame_(frame), values_(g.size()),
      invariant_(g.size(), 0), done_(g.size(), 0), comps_(g.size(), 1) {
    // A per-lane value's storage goes back to the pool after its last user: the working set is
    // the values alive at once, not the whole graph (2304 nodes for Gerstner).
    last_use_.assign(g.size(), 0);
    for (size_t k = 0; k < live_.size(); ++k)
        for (uint32_t a : g_.node(live_[k]).args)
            last_use_[a] = k;
    for (uint32_t id : keep)
        last_use_[id] = SIZE_MAX;
    for (uint32_t id : live_) {
        const Node& n = g_.node(id);
        comps_[id] = component_count(n.type);
        if (n.op == Op::Loop) {
            comps_[id] = 0; // the carried values side by side
            for (Type t : n.loop->carried_types)
                comps_[id] += component_count(t);
        }
        if (n.op == Op::Switch) {
            comps_[id] = 0; // the results side by side
            for (Type t : n.cases->result_types)
                comps_[id] += component_count(t);
        }
        // Derivatives stay per lane: a quad's difference of the same value is 0, or NaN for an
        // infinite one, and 0 past the end of a block.
        bool invariant = !varies(n.op);
        for (uint32_t a : n.args)
            invariant = invariant && invariant_[a];
        invariant_[id] = invariant;
    }
}

BlockEvaluator::~BlockEvaluator() = default;

bool BlockEvaluator::run(size_t begin, size_t count, std::string& error) {
    for (size_t k = 0; k < live_.size(); ++k) {
        const uint32_t id = live_[k];
        if (invariant_[id] && done_[id]) continue; // the same for every block
        const Node& node = g_.node(id);
        n_ = invariant_[id] ? 1 : count;
        const int comps = comps_[id];
        auto& out = values_[id];
        if (out.capacity() == 0 && !pool_.empty()) {
            out.swap(pool_.back());
            pool_.pop_back();
        }
        out.resize(n_ * static_cast<size_t>(std::max(comps, 1)));
        if (!compute(id, node, comps, begin, out, error)) return false;
        done_[id] = 1;
        for (uint32_t a : node.args)
            if (last_use_[a] == k && !invariant_[a]) {
                pool_.emplace_back();
                pool_.back().swap(values_[a]);
            }
        // Half mode: relaxed nodes are binary16, the rest binary32, as a GPU that honours
        // mediump at 16 bits would compute them.
        const EvalPrecision p =
            (p_ == EvalPrecision::Half && !node.relaxed) ? EvalPrecision::Float : p_;
        if (p == EvalPrecision::Half && texture_result(id)) {
            for (double& v : out)
                v = round_to_half_toward_zero(static_cast<float>(v));
        } else if (p == EvalPrecision::Float) {
            for (double& v : out)
                v = static_cast<double>(static_cast<float>(v));
        } else if (p == EvalPrecision::Half) {
            for (double& v : out)
                v = round_to(v, p);
        }
    }
    return true;
}

void BlockEvaluator::bind_arguments(const Node& n) {
    const size_t count = n.args.size();
    sources_.resize(count);
    lane_stride_.resize(count);
    component_stride_.resize(count);
    narrowed_.resize(count);
    const bool narrow =
        p_ == EvalPrecision::Half && n.relaxed && n.op != Op::Sample && n.op != Op::SampleLevel;
    for (size_t i = 0; i < count; ++i) {
        const uint32_t id = n.args[i];
        const Node& a = g_.node(id);
        const size_t comps = static_cast<size_t>(std::max(comps_[id], 1));
        sources_[i] = values_[id].data();
        lane_stride_[i] = invariant_[id] ? 0 : comps;
        component_stride_[i] = comps == 1 ? 0 : 1;
        if (!narrow || a.relaxed || !(is_float_numeric(a.type) || a.type == Type::Mat3)) continue;
        narrowed_[i] = values_[id];
        const bool toward_zero = texture_result(id);
        for (double& v : narrowed_[i])
            v = toward_zero ? round_to_half_toward_zero(v) : round_to_half(v);
        sources_[i] = narrowed_[i].data();
    }
}

// A texture sample, or components of one. lavapipe converts these to binary16 rounding
// toward zero (NIR folds the conversion into the sampler), other values to nearest.
bool BlockEvaluator::texture_result(uint32_t id) const {
    const Node& n = g_.node(id);
    if (n.op == Op::Swizzle) return texture_result(n.args[0]);
    return n.op == Op::Sample || n.op == Op::SampleLevel;
}

// Runs the loop over the block: every lane iterates until the trip count or until its exit
// condition is false; the body is evaluated for all lanes, and a lane that has left keeps its
// carried values (the GPU's per-pixel break).
bool BlockEvaluator::run_loop(uint32_t id, const Node& n, size_t begin, std::vector<double>& out,
                              std::string& error) {
    const LoopBody& body = *n.loop;
    auto& state = loops_[id];
    if (!state) {
        state = std::make_unique<LoopState>();
        const Graph& bg = *body.body;
        state->live = bg.live_nodes();
        std::vector<uint32_t> keep;
        for (const auto& o : bg.outputs()) {
            keep.push_back(o.node);
            if (o.name == "continue")
                state->keep_going = o.node;
            else
                state->next.push_back(o.node);
        }
        size_t offset = 0;
        for (Type t : body.carried_types) {
            state->frame.carried_offset.push_back(offset);
            offset += static_cast<size_t>(component_count(t));
        }
        state->body = std::make_unique<BlockEvaluator>(bg, params_, state->live, in_, p_, keep,
                                                       &state->frame);
    }
    const size_t total = static_cast<size_t>(comps_[id]), carried = body.carried();
    // The initial values.
    for (size_t l = 0; l < n_; ++l)
        for (size_t k = 0, c0 = 0; k < carried; ++k) {
            const int ck = component_count(body.carried_types[k]);
            for (int c = 0; c < ck; ++c)
                out[l * total + c0 + static_cast<size_t>(c)] = arg(n, k, l, c);
            c0 += static_cast<size_t>(ck);
        }
    LoopFrame& frame = state->frame;
    frame.carried = out.data();
    frame.carried_lane_stride = total;
    frame.captured.clear();
    for (size_t m = body.first_capture(); m < n.args.size(); ++m)
        frame.captured.push_back({sources_[m], lane_stride_[m], component_stride_[m]});
    // A trip count from data is the same on every lane (dsl.h checks it), and floored; a NaN
    // fails the comparison as it fails the GPU's.
    int trips = body.trip_count;
    if (body.counted) {
        const double count = arg(n, carried, 0, 0);
        trips = count >= 1.0 ? static_cast<int>(std::min(count, double(trips))) : 0;
    }
    std::vector<char> active(n_, 1);
    size_t remaining = n_;
    for (int i = 0; i < trips && remaining > 0; ++i) {
        frame.index = i;
        if (!state->body->run(begin, n_, error)) return false;
        for (size_t k = 0; k < carried; ++k) {
            const uint32_t next = state->next[k];
            const double* v = state->body->values(next);
            const size_t ck = static_cast<size_t>(component_count(body.carried_types[k]));
            const size_t stride = state->body->invariant(next) ? 0 : ck;
            for (size_t l = 0; l < n_; ++l)
                if (active[l])
                    std::copy_n(v + l * stride, ck,
                                out.data() + l * total + frame.carried_offset[k]);
        }
        if (state->keep_going == UINT32_MAX) continue;
        const double* go = state->body->values(state->keep_going);
        const size_t stride = state->body->invariant(state->keep_going) ? 0 : 1;
        for (size_t l = 0; l < n_; ++l)
            if (active[l] && go[l * stride] == 0) {
                active[l] = 0;
                --remaining;
            }
    }
    return true;
}

} // namespace watergen

namespace watergen {

// Runs the case the selector picks (the same on every lane: its first lane's value decides) over
// the block, and copies its results side by side into the Switch node's storage.
bool BlockEvaluator::run_switch(uint32_t id, const Node& n, size_t begin, std::vector<double>& out,
                                std::string& error) {
    const SwitchCases& cases = *n.cases;
    const size_t c = cases.case_for(sources_[0][0]);
    auto& state = cases_[{id, c}];
    const Graph& body = *cases.cases[c];
    if (!state) {
        state = std::make_unique<LoopState>();
        state->live = body.live_nodes();
        for (const auto& o : body.outputs())
            state->next.push_back(o.node);
        state->body = std::make_unique<BlockEvaluator>(body, params_, state->live, in_, p_,
                                                       state->next, &state->frame);
    }
    LoopFrame& frame = state->frame;
    frame.captured.clear();
    const size_t end = c + 1 < cases.cases.size() ? cases.case_args[c + 1] : n.args.size();
    for (size_t m = cases.case_args[c]; m < end; ++m)
        frame.captured.push_back({sources_[m], lane_stride_[m], component_stride_[m]});
    if (!state->body->run(begin, n_, error)) return false;
    const size_t total = static_cast<size_t>(comps_[id]);
    for (size_t k = 0, offset = 0; k < cases.results(); ++k) {
        const uint32_t result = state->next[k];
        const double* v = state->body->values(result);
        const size_t ck = static_cast<size_t>(component_count(cases.result_types[k]));
        const size_t stride = state->body->invariant(result) ? 0 : ck;
        for (size_t l = 0; l < n_; ++l)
            std::copy_n(v + l * stride, ck, out.data() + l * total + offset);
        offset += ck;
    }
    return true;
}

} // namespace watergen

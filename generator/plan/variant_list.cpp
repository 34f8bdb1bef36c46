#include "watergen/plan/variant_list.h"
#include "watergen/water/axis_registry.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace watergen {

VariantList::VariantList(std::vector<std::vector<std::string>> choices)
    : choices_(std::move(choices)) {
    for (const auto& list : choices_)
        if (list.size() > 256)
            throw std::invalid_argument("VariantList: an axis offers more than 256 choices");
}

void VariantList::add(const std::vector<size_t>& index) {
    for (size_t a = 0; a < choices_.size(); ++a)
        indices_.push_back(static_cast<uint8_t>(index[a]));
    ++count_;
}

void VariantList::add_from(const VariantList& other, size_t i) {
    const size_t axes = choices_.size();
    indices_.insert(indices_.end(), other.indices_.begin() + i * axes,
                    other.indices_.begin() + (i + 1) * axes);
    ++count_;
}

void VariantList::sort_by_key() {
    // A key is the concatenation of one piece per axis: "axis=choice", after a comma on every
    // axis but the first, or nothing for a choice left out at its default (spelled_in_key).
    // Two variants compare as their pieces' characters from the first axis where they differ.
    const size_t axes_count = choices_.size();
    std::vector<std::vector<std::string>> piece(axes_count);
    for (size_t a = 0; a < axes_count; ++a)
        for (const std::string& c : choices_[a])
            piece[a].push_back(!spelled_in_key(axes()[a], c) ? ""
                               : a == 0                      ? axes()[a].name + "=" + c
                                                             : "," + axes()[a].name + "=" + c);
    struct Cursor {
        const std::vector<std::vector<std::string>>* piece;
        const uint8_t* index;
        size_t axis, at;
        size_t axes;
        // The next character, or -1 at the key's end.
        int next() {
            while (axis < axes) {
                const std::string& p = (*piece)[axis][index[axis]];
                if (at < p.size()) return static_cast<unsigned char>(p[at++]);
                ++axis;
                at = 0;
            }
            return -1;
        }
    };
    auto less = [&](const uint8_t* x, const uint8_t* y) {
        size_t a = 0;
        while (a < axes_count && x[a] == y[a])
            ++a;
        if (a == axes_count) return false;
        Cursor cx{&piece, x, a, 0, axes_count}, cy{&piece, y, a, 0, axes_count};
        for (;;) {
            const int p = cx.next(), q = cy.next();
            if (p != q || p < 0) return p < q;
        }
    };
    std::vector<uint32_t> order(count_);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) {
        return less(&indices_[x * axes_count], &indices_[y * axes_count]);
    });
    std::vector<uint8_t> sorted(indices_.size());
    for (size_t k = 0; k < order.size(); ++k)
        std::copy_n(&indices_[order[k] * axes_count], axes_count, &sorted[k * axes_count]);
    indices_ = std::move(sorted);
}

Variant VariantList::at(size_t i) const {
    Variant v = default_variant();
    fill(i, v);
    return v;
}

void VariantList::fill(size_t i, Variant& into) const {
    const size_t axes = choices_.size();
    for (size_t a = 0; a < axes && a < into.choices.size(); ++a)
        into.choices[a] = choices_[a][indices_[i * axes + a]];
}

} // namespace watergen

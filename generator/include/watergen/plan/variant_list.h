// A list of variants kept as one byte an axis (the position of its choice among the list's
// choices on that axis): about 15 bytes a variant where a Variant's strings take about 550, so
// that a list of the whole space (3.5 million variants) stays small. Sorting it by key makes no
// key: two variants compare as their keys' characters from the first axis where they differ.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <vector>

#include "watergen/water/variant.h"

namespace watergen {

class VariantList {
  public:
    // A list whose variants choose among `choices` (per axis, axes() order; < 256 an axis).
    explicit VariantList(std::vector<std::vector<std::string>> choices = {});

    // The variant of choice `index[a]` of this list's choices on each axis a.
    void add(const std::vector<size_t>& index);
    // Variant `i` of `other`, whose choices must be this list's.
    void add_from(const VariantList& other, size_t i);
    void sort_by_key();

    size_t size() const { return count_; }
    bool empty() const { return count_ == 0; }
    Variant at(size_t i) const;
    Variant operator[](size_t i) const { return at(i); }
    Variant front() const { return at(0); }
    Variant back() const { return at(count_ - 1); }
    // Sets `into` (a variant of axes().size() choices) to variant `i`, reusing its strings.
    void fill(size_t i, Variant& into) const;
    const std::vector<std::vector<std::string>>& choices() const { return choices_; }

    // Visits the variants in order, each made as it is reached (by value).
    class Iterator {
      public:
        using iterator_category = std::input_iterator_tag;
        using value_type = Variant;
        using difference_type = std::ptrdiff_t;
        using pointer = const Variant*;
        using reference = Variant;
        Iterator(const VariantList* list, size_t i) : list_(list), i_(i) {}
        Variant operator*() const { return list_->at(i_); }
        Iterator& operator++() {
            ++i_;
            return *this;
        }
        Iterator operator++(int) {
            Iterator was = *this;
            ++i_;
            return was;
        }
        bool operator==(const Iterator& o) const { return i_ == o.i_; }

      private:
        const VariantList* list_;
        size_t i_;
    };
    Iterator begin() const { return {this, 0}; }
    Iterator end() const { return {this, count_}; }

  private:
    std::vector<std::vector<std::string>> choices_;
    std::vector<uint8_t> indices_; // count_ x choices_.size()
    size_t count_ = 0;
};

} // namespace watergen

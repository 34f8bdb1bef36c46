// Small text helpers shared by every message that lists names or prints a number.
#pragma once

#include <concepts>
#include <string>
#include <vector>

namespace watergen {

// "a, b, c" (or with another separator).
std::string join(const std::vector<std::string>& names, const std::string& separator = ", ");

// The same for the names `name(item)` of `items`.
template <class Items, std::invocable<const typename Items::value_type&> Name>
std::string join(const Items& items, Name name, const std::string& separator = ", ") {
    std::vector<std::string> names;
    for (const auto& item : items)
        names.push_back(name(item));
    return join(names, separator);
}

// The items of "a,b,c" between separators, as std::getline reads them: "" gives none, "a,"
// gives "a", "a,,b" an empty item between.
std::vector<std::string> split(const std::string& text, char separator);

// The shortest text that reads back as the same double ("4.0000001", "1000", "1e+20"):
// messages such as "min 4.0000001 is above max 4" never round two different numbers alike.
std::string spell_number(double value);

// "1.5" or "(0, 8, -30)" with 6 significant digits ({:g}): values as fact texts and fold
// reports print them (the manifest holds these texts, so their form is stable).
std::string spell_values(const std::vector<double>& values);

} // namespace watergen

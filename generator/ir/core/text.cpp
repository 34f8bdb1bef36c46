#include "watergen/ir/core/text.h"

#include <sstream>

#include <fmt/format.h>

namespace watergen {

std::string join(const std::vector<std::string>& names, const std::string& separator) {
    std::string s;
    for (size_t i = 0; i < names.size(); ++i)
        s += (i == 0 ? "" : separator) + names[i];
    return s;
}

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, separator);)
        out.push_back(item);
    return out;
}

std::string spell_number(double value) {
    return fmt::format("{}", value);
}

std::string spell_values(const std::vector<double>& values) {
    if (values.size() == 1) return fmt::format("{:g}", values[0]);
    std::string s = "(";
    for (size_t i = 0; i < values.size(); ++i)
        s += (i ? ", " : "") + fmt::format("{:g}", values[i]);
    return s + ")";
}

} // namespace watergen

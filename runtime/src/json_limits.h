// A pass over a JSON text with nlohmann's SAX parser, before any DOM is built from it: counts
// its values, its nesting depth and its longest string, and stops at the first limit passed.
// What a build's file can hold is bounded (each reader states its limits and why), and a DOM is
// ~10 to ~25 times the bytes of a text of small values; this keeps the DOM a reader builds
// within what a real file of that kind needs. Private to watergen_reflection and
// watergen_runtime; not installed.
#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace watergen::json_limits {

struct Limits {
    size_t values;       // every value: objects, arrays, strings, numbers, literals
    size_t depth = 16;   // nested objects and arrays
    size_t string_bytes; // the longest string or key
};

// "" when `text` is JSON within `limits`; else the first limit passed ("more than 4194304 JSON
// values; expected at most ..."), or "" with `syntax_error` set when the text is not JSON (the
// DOM parser then reports where).
inline std::string check(const std::string& text, const Limits& limits, bool* syntax_error) {
    struct Counter : nlohmann::json_sax<nlohmann::json> {
        explicit Counter(const Limits& l) : limits(l) {}
        const Limits& limits;
        size_t values = 0, depth = 0;
        std::string problem;
        bool syntax = false;
        bool value() {
            if (++values <= limits.values) return true;
            problem = "more than " + std::to_string(limits.values) + " JSON values";
            return false;
        }
        bool text(const std::string& s) {
            if (s.size() <= limits.string_bytes) return value();
            problem = "a string of " + std::to_string(s.size()) + " bytes; at most " +
                      std::to_string(limits.string_bytes);
            return false;
        }
        bool open() {
            if (++depth <= limits.depth) return value();
            problem = "JSON nested more than " + std::to_string(limits.depth) + " levels deep";
            return false;
        }
        bool null() override { return value(); }
        bool boolean(bool) override { return value(); }
        bool number_integer(number_integer_t) override { return value(); }
        bool number_unsigned(number_unsigned_t) override { return value(); }
        bool number_float(number_float_t, const string_t&) override { return value(); }
        bool string(string_t& s) override { return text(s); }
        bool binary(binary_t&) override { return value(); }
        bool start_object(std::size_t) override { return open(); }
        bool key(string_t& k) override { return text(k); }
        bool end_object() override { return --depth, true; }
        bool start_array(std::size_t) override { return open(); }
        bool end_array() override { return --depth, true; }
        bool parse_error(std::size_t, const std::string&,
                         const nlohmann::detail::exception&) override {
            syntax = true;
            return false;
        }
    } counter(limits);
    nlohmann::json::sax_parse(text, &counter);
    *syntax_error = counter.syntax && counter.problem.empty();
    return counter.problem;
}

} // namespace watergen::json_limits

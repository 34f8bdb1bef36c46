// Typed reading of a parsed description file (material, scene): every getter checks the JSON
// type, and on a mismatch records one error "file:line:column: error: /pointer: expected X,
// got Y" and returns false, so a reader is a chain of `if (!r.number(...)) return`.
//
//   JsonReader r(source, diagnostics);
//   if (!r.keys("", {"name", "depth"}, {"name"})) return std::nullopt;
//   double lo = 0, hi = 0;
//   if (r.has("/depth") && !r.range("/depth", lo, hi)) return std::nullopt;
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "watergen/ir/core/diagnostic.h"
#include "watergen/plan/json_source.h"

namespace watergen {

// The interval a number must lie in, with its unit for the message ("m", "degrees").
struct NumberBounds {
    double min = 0.0, max = 0.0;
    std::string unit;
};

class JsonReader {
  public:
    JsonReader(const JsonSource& source, Diagnostics& diagnostics)
        : source_(source), diagnostics_(diagnostics) {}

    // Called with the pointer of every value a getter read successfully (a scene records
    // where each fact stands, for explain).
    void on_read(std::function<void(const std::string& pointer)> observer) {
        observer_ = std::move(observer);
    }

    const JsonSource& source() const { return source_; }
    // Records "<pointer>: <what>" at the value; returns false.
    bool fail(const std::string& pointer, const std::string& what);
    bool has(const std::string& pointer) const;
    const Json& at(const std::string& pointer) const; // the value must exist
    // Names of an object's members, in file order.
    std::vector<std::string> members(const std::string& pointer) const;

    // An object whose keys are among `allowed` and include every `required` one; a missing
    // key reads "missing key 'k'" followed by `missing_note` when one is given.
    bool keys(const std::string& pointer, const std::vector<std::string>& allowed,
              const std::vector<std::string>& required, const std::string& missing_note = "");
    // An object (an array), else "expected <expected>, got ..."; `expected` says what it maps.
    bool object(const std::string& pointer, const std::string& expected);
    bool array(const std::string& pointer, const std::string& expected);

    bool string(const std::string& pointer, std::string& out);
    bool boolean(const std::string& pointer, bool& out);
    bool number(const std::string& pointer, double& out);
    // A string from `allowed`.
    bool string_in(const std::string& pointer, const std::vector<std::string>& allowed,
                   std::string& out);
    // An array of strings (duplicates allowed; the caller knows what they mean).
    bool strings(const std::string& pointer, std::vector<std::string>& out);
    // An array of distinct strings from `allowed`.
    bool strings_in(const std::string& pointer, const std::vector<std::string>& allowed,
                    std::vector<std::string>& out);
    // A number, or an array of at least `min_count` numbers.
    bool numbers(const std::string& pointer, std::vector<double>& out, size_t min_count = 0);
    // {"min": a, "max": b} with a <= b, both within `bounds` when given.
    bool range(const std::string& pointer, double& min, double& max,
               const NumberBounds* bounds = nullptr);

  private:
    bool read(const std::string& pointer) {
        if (observer_) observer_(pointer);
        return true;
    }

    const JsonSource& source_;
    Diagnostics& diagnostics_;
    std::function<void(const std::string&)> observer_;
};

// JsonSource::load with its error appended to `diagnostics`.
std::optional<JsonSource> load_json(const std::filesystem::path& path, Diagnostics& diagnostics);

} // namespace watergen

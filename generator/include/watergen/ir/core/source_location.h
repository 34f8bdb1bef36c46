// Where a call was written, for what a project registers (axis_registry.h): its diagnostics and
// name clashes carry the registering file and line. std::source_location is not usable with
// every compiler the project builds with (clang 14 with libstdc++ 12, the fuzz build), so this
// takes the same two builtins GCC and clang both give a default argument at its call site.
#pragma once

namespace watergen {

struct SourceLocation {
    const char* file = "";
    int line = 0;

    static constexpr SourceLocation current(const char* file = __builtin_FILE(),
                                            int line = __builtin_LINE()) {
        return {file, line};
    }
};

} // namespace watergen

// Report figures kept on disk until the report is written: an unnamed temporary file (gone
// with the process however it ends) that texts are appended to and read back from, so that a
// report of many variants and views holds one figure in memory at a time, not all of them.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>

namespace watergen {

struct SpooledText {
    uint64_t offset = 0, size = 0;
};

class FigureSpool {
  public:
    FigureSpool();
    ~FigureSpool();
    FigureSpool(const FigureSpool&) = delete;
    FigureSpool& operator=(const FigureSpool&) = delete;

    bool ok() const { return file_ != nullptr && error_.empty(); }
    const std::string& error() const { return error_; } // the first failure
    SpooledText append(const std::string& text);
    std::string read(SpooledText span);
    // Copies `span` to `out` in pieces; false (error() says why) on a failed read.
    bool copy(SpooledText span, std::ostream& out);

  private:
    std::FILE* file_ = nullptr;
    uint64_t size_ = 0;
    std::string error_;
};

} // namespace watergen

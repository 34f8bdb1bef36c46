#include "watergen/eval/report/figure_spool.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

namespace watergen {

FigureSpool::FigureSpool() : file_(std::tmpfile()) {
    if (!file_) error_ = std::string("cannot create a temporary file: ") + std::strerror(errno);
}

FigureSpool::~FigureSpool() {
    if (file_) std::fclose(file_);
}

SpooledText FigureSpool::append(const std::string& text) {
    SpooledText span{size_, text.size()};
    if (!ok()) return span;
    if (std::fseek(file_, static_cast<long>(size_), SEEK_SET) != 0 ||
        std::fwrite(text.data(), 1, text.size(), file_) != text.size())
        error_ = std::string("cannot write the report's figures to a temporary file: ") +
                 std::strerror(errno);
    size_ += text.size();
    return span;
}

std::string FigureSpool::read(SpooledText span) {
    std::string text(span.size, '\0');
    if (!ok() || span.size == 0) return ok() ? text : std::string();
    if (std::fseek(file_, static_cast<long>(span.offset), SEEK_SET) != 0 ||
        std::fread(text.data(), 1, span.size, file_) != span.size) {
        error_ = std::string("cannot read the report's figures back: ") + std::strerror(errno);
        return {};
    }
    return text;
}

bool FigureSpool::copy(SpooledText span, std::ostream& out) {
    constexpr uint64_t kPiece = 1 << 20;
    for (uint64_t done = 0; done < span.size && ok();) {
        const uint64_t n = std::min(kPiece, span.size - done);
        out << read({span.offset + done, n});
        done += n;
    }
    return ok();
}

} // namespace watergen

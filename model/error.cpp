#include "model/error.hpp"

#include <fmt/format.h>

namespace smql {

std::string_view toString(ErrorKind kind) {
    switch (kind) {
        case ErrorKind::Syntax:
            return "syntax error";
        case ErrorKind::Binding:
            return "error";
        case ErrorKind::Input:
            return "input error";
        case ErrorKind::Storage:
            return "storage error";
        case ErrorKind::Usage:
            return "usage error";
        case ErrorKind::Limit:
            return "limit exceeded";
        case ErrorKind::Interrupted:
            return "interrupted";
    }
    return "error";
}

Error::Error(ErrorKind kind, std::string message, std::optional<SourceLocation> where, std::string hint)
    : std::runtime_error(message), kind_(kind), message_(std::move(message)), where_(where), hint_(std::move(hint)) {}

std::string Error::render(std::string_view source) const {
    std::string out;
    if (where_ && where_->line > 0 && where_->column > 0)
        out = fmt::format("{} at line {}, column {}: {}", toString(kind_), where_->line, where_->column, message_);
    else
        out = fmt::format("{}: {}", toString(kind_), message_);

    if (where_ && where_->line > 0 && where_->column > 0 && !source.empty()) {
        // Find the offending line of the source and underline the spot.
        std::size_t start = 0;
        for (int line = 1; line < where_->line && start != std::string_view::npos; ++line) {
            start = source.find('\n', start);
            if (start != std::string_view::npos) ++start;
        }
        if (start != std::string_view::npos && start <= source.size()) {
            std::size_t end = source.find('\n', start);
            std::string_view text = source.substr(start, end == std::string_view::npos ? source.npos : end - start);
            int width = std::max(1, where_->length);
            out += fmt::format("\n  {}\n  {}{}", text, std::string(where_->column - 1, ' '), std::string(width, '^'));
        }
    }
    if (!hint_.empty()) out += fmt::format("\n  hint: {}", hint_);
    return out;
}

}  // namespace smql

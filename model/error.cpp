#include "model/error.hpp"

#include <algorithm>

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

namespace {

// Messages name what the user wrote, which may be anything: a NUL or an escape sequence is shown as
// \xNN, never sent raw to a terminal; and a name of megabytes is cut, so an error costs what its
// sentence costs. Cuts fall between UTF-8 characters.
constexpr std::size_t kMaxMessageBytes = 1000;
constexpr std::size_t kMaxSourceLineBytes = 200;

std::size_t utf8Boundary(std::string_view text, std::size_t at) {
    while (at > 0 && at < text.size() && (static_cast<unsigned char>(text[at]) & 0xC0) == 0x80) --at;
    return at;
}

std::string bounded(std::string_view text) {
    std::string out;
    for (char c : text.substr(0, kMaxMessageBytes)) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 && c != '\n' && c != '\t')
            out += fmt::format("\\x{:02X}", byte);
        else
            out += c;
    }
    if (text.size() <= kMaxMessageBytes && out.size() <= kMaxMessageBytes) return out;
    // Cut with room for the note, so that a message bounded once is not cut again.
    out.resize(utf8Boundary(out, kMaxMessageBytes - 40));
    return out + fmt::format("... ({} bytes in all)", text.size());
}

}  // namespace

Error::Error(ErrorKind kind, std::string message, std::optional<SourceLocation> where, std::string hint)
    : std::runtime_error(bounded(message)),
      kind_(kind),
      message_(bounded(message)),
      where_(where),
      hint_(bounded(hint)) {}

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
            // A long line is shown around the spot; control bytes as '?', so the caret stays under it.
            std::size_t column = static_cast<std::size_t>(where_->column - 1);
            std::size_t from =
                column > kMaxSourceLineBytes / 2 ? utf8Boundary(text, column - kMaxSourceLineBytes / 2) : 0;
            from = std::min(from, text.size());
            std::string shown(
                text.substr(from, utf8Boundary(text, std::min(text.size(), from + kMaxSourceLineBytes)) - from));
            for (char& c : shown)
                if (static_cast<unsigned char>(c) < 0x20 && c != '\t') c = '?';
            const std::size_t caret = column >= from ? column - from : 0;
            const int width = std::clamp(where_->length, 1,
                                         static_cast<int>(std::max<std::size_t>(
                                             1, kMaxSourceLineBytes - std::min(caret, kMaxSourceLineBytes - 1))));
            out += fmt::format("\n  {}{}\n  {}{}", from > 0 ? "..." : "", shown,
                               std::string(caret + (from > 0 ? 3 : 0), ' '),
                               std::string(static_cast<std::size_t>(width), '^'));
        }
    }
    if (!hint_.empty()) out += fmt::format("\n  hint: {}", hint_);
    return out;
}

}  // namespace smql

#include "engine/parser/source.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "model/utf8.hpp"

namespace smql::parser {

using grammar::SmqlLexer;

namespace {

// The grammar ends with a catch-all token, so the lexer has no error of its
// own to report; this listener replaces ANTLR's console listener so that, if
// that ever changes, the error surfaces as an smql::Error instead of text on
// stderr.
class LexerErrors : public antlr4::BaseErrorListener {
public:
    void syntaxError(antlr4::Recognizer*, antlr4::Token*, std::size_t line, std::size_t column, const std::string&,
                     std::exception_ptr) override {
        throw Error(ErrorKind::Syntax, "unreadable character",
                    SourceLocation{static_cast<int>(line), static_cast<int>(column) + 1, 1});
    }
};

}  // namespace

Source::Source(std::string_view text) {
    // Checked here rather than left to the runtime, whose decoder swallows
    // the bytes after a bad one (a quote among them reads as an unterminated
    // string) instead of saying where the text stops being UTF-8.
    if (std::optional<std::size_t> bad = model::invalidUtf8At(text)) {
        std::string_view before = text.substr(0, *bad);
        std::size_t lineStart = before.rfind('\n');
        lineStart = lineStart == std::string_view::npos ? 0 : lineStart + 1;
        int line = 1 + static_cast<int>(std::count(before.begin(), before.end(), '\n'));
        // Columns count characters: skip UTF-8 continuation bytes.
        int column =
            1 + static_cast<int>(std::count_if(before.begin() + static_cast<std::ptrdiff_t>(lineStart), before.end(),
                                               [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
        throw Error(ErrorKind::Syntax,
                    fmt::format("the text is not valid UTF-8: byte {} (0x{:02X}) does not start or continue a "
                                "UTF-8 character",
                                *bad + 1, static_cast<unsigned char>(text[*bad])),
                    SourceLocation{line, column, 1},
                    "save the query as UTF-8 text (a Latin-1 or Windows-1252 file must be converted, e.g. with iconv)");
    }
    input_ = std::make_unique<antlr4::ANTLRInputStream>(std::string(text));
    static LexerErrors lexerErrors;
    lexer_ = std::make_unique<SmqlLexer>(input_.get());
    lexer_->removeErrorListeners();
    lexer_->addErrorListener(&lexerErrors);
    tokens_ = lexer_->getAllTokens();
}

std::vector<StatementSlice> Source::statements() const {
    std::vector<StatementSlice> slices;
    std::size_t begin = 0;
    for (std::size_t i = 0; i <= tokens_.size(); ++i) {
        if (i < tokens_.size() && tokens_[i]->getType() != SmqlLexer::SEMI) continue;
        if (i > begin) slices.push_back({begin, i});
        begin = i + 1;
    }
    return slices;
}

std::string Source::textBetween(const antlr4::Token& first, const antlr4::Token& last) const {
    return input_->getText(antlr4::misc::Interval(first.getStartIndex(), last.getStopIndex()));
}

SourceLocation Source::endOf(const StatementSlice& slice) const {
    if (hasTerminator(slice)) return locationOf(*tokens_[slice.end]);
    const antlr4::Token& last = *tokens_[slice.end - 1];
    // Just past the last token; a multi-line token (a string) ends on a later line.
    std::string text = last.getText();
    std::size_t newline = text.rfind('\n');
    if (newline == std::string::npos) {
        SourceLocation where = locationOf(last);
        where.column += static_cast<int>(last.getStopIndex() - last.getStartIndex() + 1);
        where.length = 1;
        return where;
    }
    int line = static_cast<int>(last.getLine() + std::count(text.begin(), text.end(), '\n'));
    // Columns count characters, not bytes: skip UTF-8 continuation bytes.
    int column =
        1 + static_cast<int>(std::count_if(text.begin() + static_cast<std::ptrdiff_t>(newline) + 1, text.end(),
                                           [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
    return SourceLocation{line, column, 1};
}

SourceLocation locationOf(const antlr4::Token& token) { return span(token, token); }

SourceLocation span(const antlr4::Token& first, const antlr4::Token& last) {
    SourceLocation where{static_cast<int>(first.getLine()), static_cast<int>(first.getCharPositionInLine()) + 1, 1};
    std::size_t stop = last.getLine() == first.getLine() ? last.getStopIndex() : first.getStopIndex();
    std::string firstText = first.getText();
    if (stop == first.getStopIndex() && firstText.find('\n') != std::string::npos) {
        // A string running over several lines: underline its first line only.
        std::string_view firstLine = std::string_view(firstText).substr(0, firstText.find('\n'));
        where.length = static_cast<int>(std::count_if(
            firstLine.begin(), firstLine.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
    } else {
        where.length = static_cast<int>(stop - first.getStartIndex() + 1);
    }
    where.length = std::max(1, where.length);
    return where;
}

SourceLocation span(antlr4::ParserRuleContext& context) { return span(*context.getStart(), *context.getStop()); }

std::string lowerCase(std::string_view text) {
    std::string lower(text);
    // ASCII only and locale-independent: keywords and units are ASCII, and a
    // quoted name in another script keeps its letters as written.
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; });
    return lower;
}

}  // namespace smql::parser

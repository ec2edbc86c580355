#include "engine/parser/statement_parser.hpp"

#include <optional>
#include <set>

#include "engine/parser/syntax_errors.hpp"

namespace smql::parser {

using grammar::SmqlLexer;
using grammar::SmqlParser;

namespace {

// Thrown by the listener at the first report; the statement-local index of
// the token that did not fit. Not an ANTLR exception, so the generated rules
// do not catch it and no recovery is attempted.
struct FirstError {
    std::size_t tokenIndex;
};

class StopAtFirstError : public antlr4::BaseErrorListener {
public:
    void syntaxError(antlr4::Recognizer*, antlr4::Token* offending, std::size_t, std::size_t, const std::string&,
                     std::exception_ptr) override {
        throw FirstError{offending ? offending->getTokenIndex() : 0};
    }
};

StopAtFirstError stopAtFirstError;  // stateless, shared by every parse

// Copies of the statement's tokens, closed by an EOF where its `;` was: the
// grammar parses one statement and never sees separators.
std::vector<std::unique_ptr<antlr4::Token>> copyTokens(const Source& source, const StatementSlice& slice) {
    std::vector<std::unique_ptr<antlr4::Token>> tokens;
    tokens.reserve(slice.end - slice.begin + 1);
    for (std::size_t i = slice.begin; i < slice.end; ++i)
        tokens.push_back(std::make_unique<antlr4::CommonToken>(source.tokens()[i].get()));
    tokens.push_back(std::make_unique<antlr4::CommonToken>(antlr4::Token::EOF, "<EOF>"));
    return tokens;
}

std::unique_ptr<SmqlParser> makeParser(antlr4::TokenStream& stream) {
    auto parser = std::make_unique<SmqlParser>(&stream);
    parser->removeErrorListeners();  // the console listener prints to stderr
    parser->addErrorListener(&stopAtFirstError);
    return parser;
}

// Where a parse of `tokens` first fails, if it does.
std::optional<std::size_t> firstErrorIn(std::vector<std::unique_ptr<antlr4::Token>> tokens) {
    antlr4::ListTokenSource source(std::move(tokens));
    antlr4::CommonTokenStream stream(&source);
    std::unique_ptr<SmqlParser> parser = makeParser(stream);
    try {
        parser->statement();
        return std::nullopt;
    } catch (const FirstError& error) {
        return error.tokenIndex;
    }
}

// The token types that would have fitted at `failedAt`: put each candidate
// there in turn and keep those with which the parse gets further. ANTLR's
// own expected-token sets stop at rule boundaries (after `FIND cushion` they
// hold only the end of the statement, not WHERE or LIMIT); trying is exact,
// and a statement is short enough for a few dozen re-parses to cost nothing.
std::set<std::size_t> expectedAt(const Source& source, const StatementSlice& slice, std::size_t failedAt) {
    std::vector<std::size_t> candidates;
    for (std::size_t type = SmqlLexer::FIND; type < SmqlLexer::UNTERMINATED_STRING; ++type) candidates.push_back(type);
    for (std::size_t type = SmqlLexer::EQ; type <= SmqlLexer::STAR; ++type) candidates.push_back(type);
    candidates.push_back(antlr4::Token::EOF);

    const std::size_t length = slice.end - slice.begin;
    std::set<std::size_t> expected;
    for (std::size_t type : candidates) {
        std::vector<std::unique_ptr<antlr4::Token>> tokens = copyTokens(source, slice);
        auto candidate = std::make_unique<antlr4::CommonToken>(type, "");
        if (failedAt < length) {
            tokens[failedAt] = std::move(candidate);
            if (type == antlr4::Token::EOF) tokens.resize(failedAt + 1);
        } else if (type != antlr4::Token::EOF) {
            tokens.insert(tokens.begin() + static_cast<std::ptrdiff_t>(failedAt), std::move(candidate));
        } else {
            continue;  // the statement already ends here: that is the error
        }
        std::optional<std::size_t> next = firstErrorIn(std::move(tokens));
        if (!next || *next > failedAt) expected.insert(type);
    }
    return expected;
}

}  // namespace

StatementParser::StatementParser(const Source& source, StatementSlice slice)
    : source_(source),
      slice_(slice),
      tokens_(std::make_unique<antlr4::ListTokenSource>(copyTokens(source, slice))),
      stream_(std::make_unique<antlr4::CommonTokenStream>(tokens_.get())),
      parser_(makeParser(*stream_)) {}

StatementParser::~StatementParser() = default;

// Two stages, as ANTLR's documentation advises: SLL prediction, cheaper, with an error strategy
// that gives up at once, which reads every statement that is valid SMQL; only when it gives up,
// the full LL prediction with the listener that locates the first error. A statement SLL reads
// gets the tree LL would give it (the grammar has no ambiguity that needs the full context).
SmqlParser::StatementContext& StatementParser::parse() {
    auto* prediction = parser_->getInterpreter<antlr4::atn::ParserATNSimulator>();
    prediction->setPredictionMode(antlr4::atn::PredictionMode::SLL);
    parser_->setErrorHandler(std::make_shared<antlr4::BailErrorStrategy>());
    parser_->removeErrorListeners();
    try {
        return *parser_->statement();
    } catch (const antlr4::ParseCancellationException&) {
        // Not SLL, or not SMQL: the second stage says which.
    }
    stream_->seek(0);
    parser_->reset();
    prediction->setPredictionMode(antlr4::atn::PredictionMode::LL);
    parser_->setErrorHandler(std::make_shared<antlr4::DefaultErrorStrategy>());
    parser_->addErrorListener(&stopAtFirstError);
    try {
        return *parser_->statement();
    } catch (const FirstError& error) {
        throw syntaxError(source_, slice_, error.tokenIndex, expectedAt(source_, slice_, error.tokenIndex));
    }
}

}  // namespace smql::parser

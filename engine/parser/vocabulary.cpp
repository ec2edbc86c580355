#include "engine/parser/vocabulary.hpp"

#include <vector>

namespace smql::parser {

const std::string& tokenName(std::size_t type) {
    // The vocabulary hangs off a lexer instance; read it once from a lexer
    // over empty input.
    static const std::vector<std::string> names = [] {
        antlr4::ANTLRInputStream empty;
        SmqlLexer lexer(&empty);
        const antlr4::dfa::Vocabulary& vocabulary = lexer.getVocabulary();
        std::vector<std::string> all(vocabulary.getMaxTokenType() + 1);
        for (std::size_t t = 0; t < all.size(); ++t) {
            all[t] = vocabulary.getSymbolicName(t);
            // A keyword C++ cannot name a token after (NULL, a macro) is declared with a '_' after it.
            if (all[t].ends_with('_')) all[t].pop_back();
        }
        return all;
    }();
    static const std::string endOfInput = "EOF";
    return type < names.size() ? names[type] : endOfInput;
}

}  // namespace smql::parser

// Errors name what the user wrote, which may be anything: control bytes are shown escaped, and a
// huge name is cut, between UTF-8 characters, so an error costs what its sentence costs.
#include <catch2/catch.hpp>

#include <string>

#include "model/error.hpp"

using smql::Error;
using smql::ErrorKind;

TEST_CASE("error messages escape control bytes and stay short", "[model][error]") {
    Error nul(ErrorKind::Binding, std::string("unknown category 'a\0b'", 22), std::nullopt, std::string("hint\x1b[2J"));
    CHECK(nul.message() == "unknown category 'a\\x00b'");
    CHECK(nul.hint() == "hint\\x1B[2J");
    CHECK(std::string(nul.what()) == nul.message());

    const std::string huge = "unknown category '" + std::string(4 << 20, 'x') + "'";
    Error cut(ErrorKind::Binding, huge);
    CHECK(cut.message().size() < 1000);
    CHECK_THAT(cut.message(), Catch::EndsWith("... (4194323 bytes in all)"));
    // Bounded once, the message is not cut again when an error is made from it.
    CHECK(Error(ErrorKind::Binding, cut.message()).message() == cut.message());

    // A cut never splits a character: 'é' is two bytes.
    std::string accents;
    for (int i = 0; i < 600; ++i) accents += "\xC3\xA9";
    std::string kept = Error(ErrorKind::Binding, accents).message();
    kept = kept.substr(0, kept.find("..."));
    CHECK(kept.size() % 2 == 0);

    // The source line under the message is shown around the spot, the caret under it.
    const std::string line = std::string(5000, 'a') + " WHERE";
    std::string shown = Error(ErrorKind::Syntax, "here", smql::SourceLocation{1, 5002, 5}).render(line);
    CHECK(shown.size() < 600);
    CHECK_THAT(shown, Catch::Contains("...") && Catch::Contains("WHERE"));
    const auto text = shown.find("\n  ") + 3, caret = shown.find('^');
    CHECK(shown.substr(shown.find('\n', text) + 3 + (caret - shown.find('\n', text) - 3), 5) == "^^^^^");
    CHECK(shown.substr(text + (caret - shown.find('\n', text) - 3), 5) == "WHERE");
}

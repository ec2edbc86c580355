// The answer to a question in words, from its translation and the rows its SMQL returned:
// "2 cushions are on the sofa: cushion#12, cushion#14", "No, there is no piano", "3".
#pragma once

#include <optional>
#include <string>

#include "engine/ask/translator.hpp"
#include "model/error.hpp"
#include "model/result.hpp"

namespace smql::ask {

// `rows` is the result of running translation.smql (empty when it did not run).
std::string answer(const Translation& translation, const ResultSet& rows, const std::string& scene);

// The rows the answer speaks of: for "what is the picture on?", which runs RELATE against every
// thing, only the relations it names (the picture attached to wall#19), not every relation of the
// picture; the rows of every other kind of question as they are.
ResultSet answeredRows(const Translation& translation, ResultSet rows);

// The whole message ASK shows: the SMQL, the words it mapped, then the answer.
std::string message(const Translation& translation, const std::string& answerText);

// The answer when the translated statement failed as it ran and the question names a thing the scene holds none
// of ("how do I get to the table?" in a bathroom without one): that is the reason a person is told, as other
// questions about it are answered ("There is no table here."); nullopt when every word names something here.
std::optional<std::string> absentAnswer(const Translation& translation);

// An error of the translated statement (when it was bound or when it ran), said of the question:
// its location is in the SMQL, which the message quotes, not in the text the user typed.
Error failedTranslation(const Error& error, const std::string& smql, std::optional<SourceLocation> question);

}  // namespace smql::ask

// The built-in reader's kinds of question, one file each (as the binder has a file per statement):
// VSI-Bench's route plans (read_route.cpp) and appearance order (read_appearance.cpp), read from the
// whole text; how a thing is placed (read_placement.cpp) and what it looks like (read_description.cpp),
// read with the phrase grammar from the question's words. Situated questions are situation.hpp's; the
// other kinds are still rule_translator.cpp's.
#pragma once

#include <optional>

#include "engine/ask/lexicon.hpp"
#include "engine/ask/phrase.hpp"
#include "engine/ask/translator.hpp"

namespace smql::ask {

// VSI-Bench's route plan ("You are a robot beginning at the bed facing the tv. ... [please fill
// in] ..."): the things it names, with the steps to fill in; nothing when the text is not one.
std::optional<Translation> routePlan(const Question& question, const Lexicon& lexicon);

// VSI-Bench's appearance order ("What will be the first-time appearance order of the following
// categories in the video: chair, sofa, tv?"): the things by the frame that first saw each; nothing
// when the text is not one; an error for a scene that keeps no such frames.
std::optional<Translation> appearanceOrder(const Question& question, const Lexicon& lexicon);

// "How is the sink located?", "how is the towel placed on the wall?", "how is the guitar case
// positioned behind the other one?": from w[i] (past "how is"), where the thing is (FIND ... PATH), or
// how it stands to the thing named (RELATE). False when the words are not such a question.
bool readPlacement(const Words& w, std::size_t& i, PhraseParser& parser, Translation& out);

// "What does the urinal look like?", "what does the cabinet near the copier say?", "what does the
// sink appear to be?": what the memory holds of the thing (DESCRIBE), from w[0]; "describe the room", "what is
// the room like?": the scene summed up (DESCRIBE of `sceneRoot`, its node). False when the words are not such a
// question.
bool readDescription(const Words& w, std::size_t& i, PhraseParser& parser, model::NodeId sceneRoot, Translation& out);

}  // namespace smql::ask

// The built-in reader's kinds of question that are read from the whole text rather than by the
// phrase grammar of rule_translator.cpp, one file each (as the binder has a file per statement):
// VSI-Bench's route plans (read_route.cpp) and appearance order (read_appearance.cpp); situated
// questions are situation.hpp's.
#pragma once

#include <optional>

#include "engine/ask/lexicon.hpp"
#include "engine/ask/translator.hpp"

namespace smql::ask {

// VSI-Bench's route plan ("You are a robot beginning at the bed facing the tv. ... [please fill
// in] ..."): the things it names, with the steps to fill in; nothing when the text is not one.
std::optional<Translation> routePlan(const Question& question, const Lexicon& lexicon);

// VSI-Bench's appearance order ("What will be the first-time appearance order of the following
// categories in the video: chair, sofa, tv?"): the things by the frame that first saw each; nothing
// when the text is not one; an error for a scene that keeps no such frames.
std::optional<Translation> appearanceOrder(const Question& question, const Lexicon& lexicon);

}  // namespace smql::ask

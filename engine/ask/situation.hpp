// Situated questions: a person's place and heading said in words before the question, as SQA3D
// gives them ("I am sitting on the bed facing the window. What is to my left?"). The situation
// becomes a pose: the thing the person is at and the thing the view faces (SMQL's `VIEW FROM a
// FACING b`), and how far the person's heading is turned from the view's, so that "my left",
// "behind me" and "which way should I turn to reach the door?" are read against it (docs/ask.md,
// "Situated questions").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/ask/lexicon.hpp"
#include "engine/ask/phrase.hpp"
#include "engine/ask/translator.hpp"

namespace smql::ask {

// Quarter turns clockwise, seen from above: 0 ahead, 1 right, 2 behind, 3 left.
enum Side : int { Ahead = 0, Right = 1, Behind = 2, Left = 3 };

struct Pose {
    Phrase at;                     // where the view stands: VIEW FROM at
    std::optional<Phrase> facing;  // what the view faces; none: the middle of the scene
    int turn = 0;                  // quarter turns clockwise from the person's heading to the view's
    std::string words;             // how the answer says the pose: "at the bed, facing the window"
};

// The situation and the question of a text whose last sentence is a question and whose earlier
// ones place the person who asks ("I am ...", "Sitting on ...", "There is a chair on my left.").
struct Situated {
    std::string situation;
    std::string question;
};
std::optional<Situated> splitSituation(const std::string& text);

// The pose a situation says, from the things of the scene it names: the thing the person is on,
// at or by; the thing faced; things on a side ("with the door on my right"). Nothing when it
// names none of the scene's things.
std::optional<Pose> readPose(const std::string& situation, const Lexicon& lexicon, PhraseParser& parser);

// "my 2 o'clock", "my six o'clock direction" from w[i] ("my"): the side (the nearest quarter) and
// the words taken.
std::optional<std::pair<int, std::size_t>> clockAt(const Words& w, std::size_t i);

// "VIEW FROM bed FACING window" (or "VIEW FROM bed" facing the middle of the scene).
std::string viewClause(const Pose& pose);

// `smql` with `view` after each FIND's and COUNT's target and at the end of a RELATE.
std::string withView(const std::string& smql, const std::string& view);

// "if I turn around, ...", "... if I turn left?": the question without the turn, and the pose
// turned (the person's heading turns; the view stays).
std::string takeTurn(const std::string& question, Pose& pose);

// Which way is a thing from where the person is: "which direction should I go to exit the room?",
// "is the door on my left or right?", "where should I turn to get to the sink?". A Direction
// translation whose roles are the pose's things and the thing asked about (answer.cpp turns the
// answer by the pose's turn).
std::optional<Translation> situatedDirection(const std::string& question, const Pose& pose, const Lexicon& lexicon,
                                             PhraseParser& parser, Translation& out);

}  // namespace smql::ask

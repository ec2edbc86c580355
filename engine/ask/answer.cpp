#include "engine/ask/answer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "engine/ask/lexicon.hpp"
#include "engine/ask/phrase.hpp"
#include "engine/ask/units.hpp"
#include "model/category.hpp"
#include "model/geometry.hpp"
#include "model/seating.hpp"
#include "relations/predicates.hpp"

namespace smql::ask {

namespace {

constexpr std::size_t kNamedInAnswer = 12;  // more rows than this are counted, not named

// The words with their first letter a capital, as a sentence begins.
std::string capitalised(std::string words) {
    if (!words.empty()) words.front() = static_cast<char>(std::toupper(static_cast<unsigned char>(words.front())));
    return words;
}

// A tally, the most counted first (ties in the tally's order).
std::vector<std::pair<std::string, std::size_t>> mostFirst(const std::map<std::string, std::size_t>& tally) {
    std::vector<std::pair<std::string, std::size_t>> order(tally.begin(), tally.end());
    std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    return order;
}

std::string text(const Value& v) {
    if (const auto* s = std::get_if<std::string>(&v)) return *s;
    if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
    return {};
}

// "cushion#12", as paths and RELATE name nodes.
std::vector<std::string> labels(const ResultSet& rs) {
    std::vector<std::string> out;
    int id = rs.columnIndex("id"), category = rs.columnIndex("category");
    if (id < 0 || category < 0) return out;
    for (const auto& row : rs.rows) out.push_back(text(row[category]) + "#" + text(row[id]));
    return out;
}

std::string listed(const std::vector<std::string>& items, std::string_view separator = ", ",
                   std::size_t named = kNamedInAnswer) {
    std::string out;
    for (std::size_t i = 0; i < items.size() && i < named; ++i) out += (i ? std::string(separator) : "") + items[i];
    // "a, b and 3 more".
    if (items.size() > named) out += fmt::format("{}and {} more", separator, items.size() - named);
    return out;
}

// Every item, the last after "and": "5 chairs, 3 tables and a bed".
std::string listedWithAnd(const std::vector<std::string>& items) {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i)
        out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
    return out;
}

// The things a subject stands so to, as a sentence lists them: "bed#8, desk#12 and table#13", or the first
// kNamedInAnswer and how many more.
std::string listedThings(const std::vector<std::string>& items) {
    return items.size() <= kNamedInAnswer ? listedWithAnd(items) : listed(items);
}

// When every row has one category, the answer names it ("2 cushions"), else "things".
std::optional<std::string> sharedCategory(const ResultSet& rs) {
    int category = rs.columnIndex("category");
    if (category < 0 || rs.rows.empty()) return std::nullopt;
    std::string first = text(rs.rows.front()[category]);
    for (const auto& row : rs.rows)
        if (text(row[category]) != first) return std::nullopt;
    // In words, as the subject is said: "1 trash bin is between ...".
    return model::categoryWords(first);
}

std::string withCondition(const Translation& t) { return t.condition.empty() ? "" : " " + t.condition; }

// The question's words the scene has none of ("piano"), for answers that found nothing to compare.
std::string absentWords(const Translation& t) {
    std::vector<std::string> words;
    for (const auto& m : t.mappings)
        if (m.categories.empty()) {
            // One of it: "there is no lamp here", asked of "lamps".
            const std::size_t last = m.word.rfind(' ') + 1;  // 0 for one word
            words.push_back(m.word.substr(0, last) + model::singularWord(m.word.substr(last)));
        }
    std::string out;
    for (std::size_t i = 0; i < words.size(); ++i) out += (i ? " or " : "") + words[i];
    return out;
}

// "a bed", "an oven".
std::string withArticle(const std::string& noun) {
    return (std::string_view("aeiou").find(noun.front()) == std::string_view::npos ? "a " : "an ") + noun;
}

// Whether `m` is the word the subject names: "mug" of "red mug", "mugs" of "red mugs".
bool namesSubject(const Translation& t, const WordMapping& m) {
    return t.subject == m.word || t.subject.ends_with(" " + m.word) || t.subjectPlural == m.word ||
           t.subjectPlural.ends_with(" " + m.word);
}

// Where the scene holds things the ingest could not name, a kind it has none of may be one of them (ScanNet's
// bathroom stores its tub as object#9): said after an answer that finds none of `what`. Empty otherwise.
std::string mayBeUnnamed(const Translation& t, const std::string& what) {
    if (!t.unnamedThings || what.empty() || what == "thing") return "";
    return fmt::format(" The memory holds things it could not name ({}): one of them may be {}.",
                       pluralOf(std::string(model::kUnnamedCategory)), withArticle(what));
}

// The subject is of a kind the scene has none of ("is there a bathtub?"): mayBeUnnamed of it, else empty.
std::string subjectMayBeUnnamed(const Translation& t) {
    for (const auto& m : t.mappings)
        if (m.categories.empty() && namesSubject(t, m)) return mayBeUnnamed(t, t.subject);
    return "";
}

// "There is no piano here.", words the scene has none of; and that one of the things it could not name may be one.
std::string noneHere(const Translation& t, const std::string& absent) {
    return fmt::format("There is no {} here.{}", absent, mayBeUnnamed(t, absent));
}

// Nothing answers: a word that names nothing in the scene is why ("which is closer to the door" where there is no
// door), else nothing meets the condition.
std::string noneFound(const Translation& t) {
    if (std::string absent = absentWords(t); !absent.empty()) return noneHere(t, absent);
    return fmt::format("There is no {}{}.", t.subject, withCondition(t));
}

// m above the floor (height 0, or the floor's top): a thing whose bottom is this low stands on it.
constexpr double kOnFloor = 0.15;

// How a node stands to its parent in the tree, in words: a thing is on the surface it rests on ("mug#27 is on
// desk#23"), in the holder it rests in ("apple#5 is in bowl#4"), and at the enclosure it rests on or in ("vase#3 is
// at cabinet#2"); a wall, a door or a window is the parent of what stands on the floor nearest it, which stands by it
// ("sofa#50 stands by wall#19"), and of what is raised off the floor there. On a wall, a slab standing upright
// hangs on it ("picture#80 is on wall#19"); anything else rests on something the memory does not hold (a mug on an
// unseen shelf), so it is by the wall, at its height ("mug#11 is by wall#3, 1.28 m above the floor"). By a door or
// a window it may hang on the wall beside, so it is at it. Below a floor (a scene without walls), a thing on it is on
// it, and one off it is that high above it (TUM's office photos: a bottle on a shelf the memory does not hold was
// "at floor#2").
std::string placeWords(const Translation& t, const ResultSet& rs, std::size_t row, const std::string& parent) {
    const std::string kind = parent.substr(0, parent.find('#'));
    const bool floor = kind == "floor";
    if (!floor && !isOneOf(kind, {"wall", "door", "window"})) {
        const relations::Affordance carrier = relations::affordanceOf(kind);
        return (carrier == relations::Affordance::Surface  ? "is on "
                : carrier == relations::Affordance::Holder ? "is in "
                                                           : "is at ") +
               parent;
    }
    const int box = rs.columnIndex("box");
    const auto* b = box >= 0 ? std::get_if<model::Box>(&rs.rows[row][box]) : nullptr;
    if (!b) return "is at " + parent;
    if (floor)
        return model::bottom(*b) <= kOnFloor
                   ? "is on " + parent
                   : fmt::format("is {} above {}", formatLength(model::bottom(*b), t.unit), parent);
    if (model::bottom(*b) <= kOnFloor) return "stands by " + parent;
    if (kind != "wall") return "is at " + parent;
    if (relations::hungShape(*b)) return "is on " + parent;
    return fmt::format("is by {}, {} above the floor", parent, formatLength(model::bottom(*b), t.unit));
}

std::string locate(const Translation& t, const ResultSet& rs, const std::string& scene) {
    if (rs.rows.empty()) {
        if (const std::string may = subjectMayBeUnnamed(t); !may.empty())
            return fmt::format("No {}{} is stored in scene '{}'.{}", t.subject, withCondition(t), scene, may);
        return fmt::format("There is no {}{} in scene '{}'.", t.subject, withCondition(t), scene);
    }
    int path = rs.columnIndex("path");
    auto names = labels(rs);
    std::vector<std::string> places;
    for (std::size_t r = 0; r < rs.rows.size(); ++r) {
        std::string p = path >= 0 ? text(rs.rows[r][path]) : "";
        // The node's parent in the tree: what it rests on, or the anchor it is nearest.
        std::size_t last = p.rfind(" / ");
        std::size_t before = last == std::string::npos ? std::string::npos : p.rfind(" / ", last - 1);
        std::string parent = before == std::string::npos ? "" : p.substr(before + 3, last - before - 3);
        if (last != std::string::npos && before == std::string::npos) {
            // Right below the scene's root: an anchor (a wall, a door) or a free-standing node.
            places.push_back(fmt::format("{} is in {} ({})", names[r], p.substr(0, last), p));
            continue;
        }
        places.push_back(parent.empty() ? names[r]
                                        : fmt::format("{} {} ({})", names[r], placeWords(t, rs, r, parent), p));
    }
    std::string head = rs.rows.size() == 1 ? "" : fmt::format("{} {}: ", rs.rows.size(), t.subjectPlural);
    return head + listed(places, "; ");
}

std::string relational(const Translation& t, const ResultSet& rs) {
    auto shared = sharedCategory(rs);
    std::size_t n = rs.rows.size();
    // "what is in the room?": the whole scene, no condition to say.
    if (t.condition.empty()) {
        if (n == 0)
            return t.subject == "thing" ? "There is nothing here."
                                        : fmt::format("There is no {} here.{}", t.subject, subjectMayBeUnnamed(t));
        std::string nouns = t.subject == "thing" && shared ? pluralOf(*shared) : t.subjectPlural;
        std::string noun = t.subject == "thing" && shared ? *shared : t.subject;
        return n == 1 ? fmt::format("There is 1 {}: {}", noun, listed(labels(rs)))
                      : fmt::format("There are {} {}: {}", n, nouns, listed(labels(rs)));
    }
    if (n == 0) {
        // "what is on the bed?" where the scene holds no bed: say so, not that nothing is on it.
        if (std::string absent = absentWords(t); !absent.empty()) return noneHere(t, absent);
        if (t.subject == "thing") return fmt::format("Nothing is {}.", t.condition);
        return fmt::format("No {} is {}.", t.subject, t.condition);
    }
    std::string noun = t.subject == "thing" && shared ? *shared : t.subject;
    // "what is there besides the cushions?": no verb before the exclusion.
    if (t.condition.starts_with("besides ")) {
        std::string nouns = t.subject == "thing" && shared ? pluralOf(*shared) : t.subjectPlural;
        return fmt::format("{} {} {}: {}", n, n == 1 ? noun : nouns, t.condition, listed(labels(rs)));
    }
    if (n == 1) return fmt::format("1 {} is {}: {}", noun, t.condition, listed(labels(rs)));
    std::string nouns = t.subject == "thing" && shared ? pluralOf(*shared) : t.subjectPlural;
    // Things on one side of a reference come nearest it first (the translator orders them: FIND then returns
    // each row's distance).
    const std::string order = rs.columnIndex("distance") >= 0 ? ", nearest first" : "";
    return fmt::format("{} {} are {}{}: {}", n, nouns, t.condition, order, listed(labels(rs)));
}

// The word asked for when the scene holds none of it but holds the kind it is ("desk" -> table, WordNet's hypernym):
// the rows are of that kind, and a count or an existence question is of the word asked, so the answer says that none
// is stored and names what is. Null when the subject was not widened so.
const WordMapping* widenedSubject(const Translation& t) {
    for (const auto& m : t.mappings)
        if (m.how == describe(WordMatch::How::Broader) && !m.categories.empty() && namesSubject(t, m)) return &m;
    return nullptr;
}

// "there are 3 tables, the kind a desk is, which may be desks"
std::string broaderKind(const Translation& t, const WordMapping& widened, std::size_t n) {
    const std::string& kind = widened.categories.front();
    return fmt::format("there {} {} {}, the kind a {} is, which may be {}", n == 1 ? "is" : "are", n,
                       n == 1 ? kind : pluralOf(kind), t.subject, n == 1 ? "one" : t.subjectPlural);
}

// Things counted by the holder they are on or in (Translation::measure "each", "most", "fewest"; the rows the things
// and every holder, roles the kinds of each): each thing goes to the holder its box lies nearest (on a bed's pillows,
// the bed under them), and each holder says how many it holds, most first, or the one that holds the most or fewest.
std::string countByHolder(const Translation& t, const ResultSet& rs) {
    const int category = rs.columnIndex("category"), box = rs.columnIndex("box");
    if (category < 0 || box < 0 || t.roles.size() != 2 || t.choices.size() != 2) return noneFound(t);
    const auto names = labels(rs);
    auto isOf = [&](std::size_t r, std::size_t role) {
        const std::string c = text(rs.rows[r][static_cast<std::size_t>(category)]);
        return std::find(t.roles[role].begin(), t.roles[role].end(), c) != t.roles[role].end();
    };
    auto boxOf = [&](std::size_t r) -> const model::Box* {
        return std::get_if<model::Box>(&rs.rows[r][static_cast<std::size_t>(box)]);
    };
    std::vector<std::size_t> holders;
    std::vector<std::size_t> things;
    for (std::size_t r = 0; r < rs.rows.size(); ++r) {
        if (!boxOf(r)) continue;
        if (isOf(r, 1))
            holders.push_back(r);
        else if (t.roles[0].empty() || isOf(r, 0))  // no kinds: things of any kind ("how many things ...")
            things.push_back(r);
    }
    const std::string holderWord = t.choices[1], thingWord = t.choices[0];
    if (holders.empty()) return fmt::format("There is no {} here.", holderWord);
    std::vector<std::size_t> held(holders.size(), 0);
    for (const std::size_t r : things) {
        std::size_t best = 0;
        double nearest = std::numeric_limits<double>::infinity();
        for (std::size_t h = 0; h < holders.size(); ++h) {
            const model::Box &a = *boxOf(r), &b = *boxOf(holders[h]);
            const double gap = model::distance(a, b) + 1e-3 * model::centerDistance(a, b);
            if (gap < nearest) nearest = gap, best = h;
        }
        ++held[best];
    }
    std::vector<std::size_t> order(holders.size());
    for (std::size_t h = 0; h < order.size(); ++h) order[h] = h;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return held[a] > held[b]; });
    const std::string preposition = t.predicate == "in" || t.predicate == "near" ? t.predicate : "on";
    std::vector<std::string> each;  // "5 on bed#2"
    for (const std::size_t h : order) each.push_back(fmt::format("{} {} {}", held[h], preposition, names[holders[h]]));
    const std::string plural = capitalised(pluralOf(thingWord));
    if (t.measure == "each")
        return fmt::format("{} {} each {}: {} ({} in all).", plural, preposition, holderWord, listed(each),
                           things.size());
    const bool most = t.measure == "most";
    const std::size_t pick = most ? order.front() : order.back();
    if (holders.size() == 1) return fmt::format("There is one {}: {}.", holderWord, each.front());
    if (std::count(held.begin(), held.end(), held[pick]) > 1)
        return fmt::format("No {} has {} {} than the others: {}.", holderWord, most ? "more" : "fewer",
                           pluralOf(thingWord), listed(each));
    return fmt::format("{} has the {} {}: {}.", names[holders[pick]], most ? "most" : "fewest", pluralOf(thingWord),
                       listed(each));
}

std::string count(const Translation& t, const ResultSet& rs) {
    if (t.measure == "each" || t.measure == "most" || t.measure == "fewest") return countByHolder(t, rs);
    // Several kinds asked at once: the rows found, tallied by the kinds in the order asked.
    if (const int category = rs.columnIndex("category"); category >= 0 && !t.roles.empty()) {
        std::vector<std::string> counts;
        std::vector<std::ptrdiff_t> tallies;
        for (std::size_t k = 0; k < t.roles.size() && k < t.choices.size(); ++k) {
            const auto n = std::count_if(rs.rows.begin(), rs.rows.end(), [&](const auto& row) {
                const std::string c = text(row[static_cast<std::size_t>(category)]);
                return std::find(t.roles[k].begin(), t.roles[k].end(), c) != t.roles[k].end();
            });
            counts.push_back(fmt::format("{} {}", n, n == 1 ? t.choices[k] : pluralOf(t.choices[k])));
            tallies.push_back(n);
        }
        // "how many more cushions than tables are there?": by how many.
        if (t.measure.starts_with("how many") && tallies.size() == 2) {
            const bool more = t.measure == "how many more";
            const std::ptrdiff_t by = more ? tallies[0] - tallies[1] : tallies[1] - tallies[0];
            if (by == 0)
                return fmt::format("None: there are as many {} as {}: {}.", pluralOf(t.choices[0]),
                                   pluralOf(t.choices[1]), listedWithAnd(counts));
            if (by < 0)
                return fmt::format("None: there are {} {} than {}: {}.", more ? "fewer" : "more",
                                   pluralOf(t.choices[0]), pluralOf(t.choices[1]), listedWithAnd(counts));
            return fmt::format("{} {} {} than {}: {}.", by, more ? "more" : "fewer",
                               by == 1 ? t.choices[0] : pluralOf(t.choices[0]), pluralOf(t.choices[1]),
                               listedWithAnd(counts));
        }
        // "are there more chairs than tables?"; "are there more books or cushions?" (Translation::predicate "or"):
        // which of the two.
        if (!t.measure.empty() && tallies.size() == 2) {
            const bool holds = t.measure == "more" ? tallies[0] > tallies[1] : tallies[0] < tallies[1];
            if (t.predicate == "or" && tallies[0] == tallies[1])
                return fmt::format("There are as many {} as {}: {}.", pluralOf(t.choices[0]), pluralOf(t.choices[1]),
                                   listedWithAnd(counts));
            if (t.predicate == "or")
                return fmt::format("There are {} {} than {}: {}.", t.measure, pluralOf(t.choices[holds ? 0 : 1]),
                                   pluralOf(t.choices[holds ? 1 : 0]), listedWithAnd(counts));
            return fmt::format("{}, there are {}{} {} than {}: {}.", holds ? "Yes" : "No", holds ? "" : "not ",
                               t.measure, pluralOf(t.choices[0]), pluralOf(t.choices[1]), listedWithAnd(counts));
        }
        return fmt::format("{} ({} in all).", listedWithAnd(counts), rs.rows.size());
    }
    std::int64_t n = 0;
    if (!rs.rows.empty() && !rs.rows.front().empty())
        if (const auto* v = std::get_if<std::int64_t>(&rs.rows.front().front())) n = *v;
    if (const WordMapping* widened = widenedSubject(t); widened && n > 0)
        return fmt::format("0 stored as {}{}; {}.", t.subjectPlural, withCondition(t),
                           broaderKind(t, *widened, static_cast<std::size_t>(n)));
    // "how many books are on the piano?" where there is no piano: that is why, as existence says it.
    if (const std::string absent = absentWords(t);
        n == 0 && !t.condition.empty() && !absent.empty() && absent != t.subject)
        return fmt::format("0 {}: there is no {} here.", t.subjectPlural, absent);
    if (t.condition.empty() || t.condition.starts_with("besides "))
        return fmt::format("{} {}{}.{}", n, n == 1 ? t.subject : t.subjectPlural, withCondition(t),
                           n == 0 ? subjectMayBeUnnamed(t) : "");
    return fmt::format("{} {} {} {}.", n, n == 1 ? t.subject : t.subjectPlural, n == 1 ? "is" : "are", t.condition);
}

std::string existence(const Translation& t, const ResultSet& rs) {
    std::size_t n = rs.rows.size();
    // "is there a sink between the toilet and the table?" where there is no table: that is why.
    if (const std::string absent = absentWords(t);
        n == 0 && !t.condition.empty() && !absent.empty() && absent != t.subject)
        return fmt::format("No: there is no {} here.", absent);
    if (n == 0 && t.subject == "thing" && !t.condition.empty()) return fmt::format("No, nothing is {}.", t.condition);
    if (const std::string may = subjectMayBeUnnamed(t); n == 0 && !may.empty())
        return fmt::format("No {}{} is stored.{}", t.subject, withCondition(t), may);
    if (n == 0) return fmt::format("No, there is no {}{}.", t.subject, withCondition(t));
    if (const WordMapping* widened = widenedSubject(t))
        return fmt::format("None is stored as a {}{}; {}: {}", t.subject, withCondition(t), broaderKind(t, *widened, n),
                           listed(labels(rs)));
    if (n == 1) return fmt::format("Yes, there is 1 {}{}: {}", t.subject, withCondition(t), listed(labels(rs)));
    return fmt::format("Yes, there are {} {}{}: {}", n, t.subjectPlural, withCondition(t), listed(labels(rs)));
}

std::string yesNo(const Translation& t, const ResultSet& rs) {
    // Of every one of them (Translation::measure "every"): the rows are those it does not hold of.
    if (t.measure == "every") {
        if (std::string absent = absentWords(t); !absent.empty())
            return fmt::format("No: there is no {} here.", absent);
        if (rs.rows.empty()) return fmt::format("Yes: every {} is {}.", t.subject, t.condition);
        return fmt::format("No: {} {} not {}.", listedWithAnd(labels(rs)), rs.rows.size() == 1 ? "is" : "are",
                           t.condition);
    }
    int relation = rs.columnIndex("relation"), subject = rs.columnIndex("subject"), object = rs.columnIndex("object");
    std::string words = t.predicate;
    std::replace(words.begin(), words.end(), '_', ' ');  // "left of", as RELATE says it
    if (words == "attached") words += " to";
    std::vector<std::string> holding;
    for (const auto& row : rs.rows)
        if (text(row[relation]) == t.predicate)
            holding.push_back(fmt::format("{} is {} {}", text(row[subject]), words, text(row[object])));
    // A yes needs one pair to show it; the rows hold every pair.
    if (!holding.empty()) return "Yes: " + listed(holding, "; ", 3);
    if (rs.message.empty()) {
        std::string absent = absentWords(t);
        return absent.empty() ? fmt::format("No: there is no {} or no {} to compare.", t.subject, t.object)
                              : fmt::format("No: there is no {} here.", absent);
    }
    std::string first = rs.message.substr(0, rs.message.find('\n'));
    return fmt::format("No, the {} is not {} ({}).", t.subject, t.condition, first);
}

// "Is the sink to the left or right of the toilet?": which of the two sides (Translation::choices, predicates) holds
// between the things asked of, by RELATE's rows, with what RELATE found of them.
std::string eitherSide(const Translation& t, const ResultSet& rs) {
    const int relation = rs.columnIndex("relation");
    auto words = [](std::string predicate) {
        if (predicate == "left_of" || predicate == "right_of")
            return "to the " + predicate.substr(0, predicate.find('_')) + " of";
        std::replace(predicate.begin(), predicate.end(), '_', ' ');
        return predicate;
    };
    std::vector<std::string> holding;
    for (const auto& choice : t.choices)
        if (std::any_of(rs.rows.begin(), rs.rows.end(),
                        [&](const Row& row) { return relation >= 0 && text(row[relation]) == choice; }))
            holding.push_back(words(choice));
    const std::string found = rs.message.substr(0, rs.message.find('\n'));
    if (holding.empty())
        return fmt::format("Neither: the {} is not {} the {} or {} it ({}).", t.subject, words(t.choices[0]), t.object,
                           words(t.choices[1]), found);
    return fmt::format("The {} is {} the {} ({}).", t.subject, listedWithAnd(holding), t.object, found);
}

std::optional<double> number(const Value& v) {
    if (const auto* d = std::get_if<double>(&v)) return *d;
    if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
    return std::nullopt;
}

// A length in the question's unit: "1.23 m", "123 cm".
std::string length(double metres, const std::string& unit) { return formatLength(metres, unit); }

std::string distance(const Translation& t, const ResultSet& rs) {
    int d = rs.columnIndex("distance");
    auto names = labels(rs);
    // Measured from where the person stands (distance(HERE): the statement's viewpoint), or from a thing.
    // Outside a sub-query: "(FIND table ORDER BY distance(HERE) LIMIT 1)" is a thing measured from.
    const std::size_t here = t.smql.find("distance(HERE)");
    const bool fromYou = here != std::string::npos &&
                         std::count(t.smql.begin(), t.smql.begin() + static_cast<std::ptrdiff_t>(here), '(') ==
                             std::count(t.smql.begin(), t.smql.begin() + static_cast<std::ptrdiff_t>(here), ')');
    std::string from = fromYou ? "you" : "the " + t.object;
    // "how far apart are the chairs?": each from the nearest other of its kind ("the objects": of any).
    const bool anyThing = t.subject == "thing" && isOneOf(t.object, {"objects", "things", "items"});
    if (!fromYou && (t.object == t.subject || t.object == t.subjectPlural || anyThing))
        from = (rs.rows.size() == 2 ? "the other " : "the nearest other ") + t.subject;
    std::vector<std::string> parts;
    std::vector<double> each;
    for (std::size_t r = 0; r < rs.rows.size() && d >= 0; ++r)
        if (auto metres = number(rs.rows[r][d]); metres && std::isfinite(*metres)) {
            parts.push_back(fmt::format("{} is {} from {}", names[r], length(*metres, t.unit), from));
            each.push_back(*metres);
        }
    if (parts.empty()) {
        std::string absent = absentWords(t);
        return absent.empty() ? fmt::format("There is no {} or no {} to measure between.", t.subject, t.object)
                              : noneHere(t, absent);
    }
    std::string how = fromYou ? " (along the floor, from where you stand: the scene's viewpoint)"
                              : " (measured between the closest points of their boxes)";
    // "is there room to walk between the bed and the wall?": the narrowest gap (the rows come nearest first) against
    // the width a person needs.
    if (t.predicate == "walk") {
        const double needed = 2 * model::kBodyRadius;
        // Two of one kind ("between the two sofas") are one pair, said once.
        const bool onePair = (t.object == t.subject || t.object == t.subjectPlural) && parts.size() == 2;
        const std::string others = parts.size() > 1 && !onePair
                                       ? fmt::format(" Farther: {}.", listed({parts.begin() + 1, parts.end()}, "; "))
                                       : "";
        return fmt::format("{}: {}, where a person needs about {} to walk between them{}.{}",
                           each.front() >= needed ? "Yes" : "No", parts.front(), length(needed, t.unit), how, others);
    }
    // "the average distance between the chairs": the mean over the things of each one's distance, with its range.
    if (t.average && each.size() > 1) {
        const auto [low, high] = std::minmax_element(each.begin(), each.end());
        const double mean = std::accumulate(each.begin(), each.end(), 0.0) / static_cast<double>(each.size());
        const std::string range = length(*low, t.unit) == length(*high, t.unit)
                                      ? ""
                                      : fmt::format(", {} to {}", length(*low, t.unit), length(*high, t.unit));
        return fmt::format("The {} {} are {} from {} on average{}{}: {}.", each.size(), t.subjectPlural,
                           length(mean, t.unit), from, range, how, listed(parts, "; "));
    }
    if (parts.size() == 1)
        return fmt::format("The {} is {} from {}{}: {}.", t.subject, length(*number(rs.rows.front()[d]), t.unit), from,
                           how, parts.front());
    return fmt::format("{} {}, nearest first{}: {}.", parts.size(), t.subjectPlural, how, listed(parts, "; "));
}

// Things a person lies in or on, whose width is across their length (a bed 2 m long is 1.6 m wide), where the
// memory's width is a box's larger horizontal side (a sofa's width is its length).
bool widthAcrossLength(const std::string& category) {
    return isOneOf(category, {"bed", "bunk-bed", "crib", "mattress", "bathtub"});
}

// One row's box as a question of size reads it.
struct RowSize {
    double width = 0, depth = 0, height = 0;
    std::optional<double> volume, centre;  // centre: z, where the translator asked for it (a height over the floor)
    bool across = false;                   // its kind's width is across its length (widthAcrossLength)
    // The one number a measure asks: a height over the floor where z was asked, unless "how high" asks of the thing
    // itself (`high`); none for "size" (three numbers), or a volume the row lacks.
    std::optional<double> asked(const std::string& m, bool high) const {
        if (m == "height") return centre && !high ? *centre - height / 2 : height;
        if (m == "width") return across ? depth : width;
        if (m == "depth") return depth;
        if (m == "longest") return std::max({width, depth, height});
        if (m == "volume") return volume;
        return std::nullopt;
    }
};

// The size of row `r` of a size question's rows (id, category, width, depth, height, volume[, z]); none without a box.
std::optional<RowSize> rowSize(const ResultSet& rs, std::size_t r) {
    const auto& row = rs.rows[r];
    auto at = [&](const char* column) -> std::optional<double> {
        const int c = rs.columnIndex(column);
        return c >= 0 ? number(row[static_cast<std::size_t>(c)]) : std::nullopt;
    };
    const auto width = at("width"), depth = at("depth"), height = at("height");
    if (!width || !depth || !height) return std::nullopt;
    const int category = rs.columnIndex("category");
    return RowSize{*width,  *depth,
                   *height, at("volume"),
                   at("z"), category >= 0 && widthAcrossLength(text(row[static_cast<std::size_t>(category)]))};
}

// "The average height of the tables": the mean of the measure over the rows with a box, with its range.
std::string averageSize(const Translation& t, const ResultSet& rs) {
    const std::string& m = t.measure;
    const bool high = t.predicate == "high";
    // The sides each row is measured by: one for a measure, the three for "size".
    std::vector<std::vector<double>> sides(m == "size" ? 3 : 1);
    bool above = false;  // a height over the floor
    for (std::size_t r = 0; r < rs.rows.size(); ++r) {
        const auto box = rowSize(rs, r);
        if (!box) continue;
        above = above || (m == "height" && box->centre && !high);
        if (m == "size")
            sides[0].push_back(box->width), sides[1].push_back(box->depth), sides[2].push_back(box->height);
        else if (auto value = box->asked(m, high))
            sides[0].push_back(*value);
    }
    const std::size_t n = sides[0].size();
    if (n == 0) return noneFound(t);
    auto mean = [n](const std::vector<double>& values) {
        return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(n);
    };
    auto said = [&](double value) { return m == "volume" ? fmt::format("{:.3f} m³", value) : length(value, t.unit); };
    const auto [low, highest] = std::minmax_element(sides[0].begin(), sides[0].end());
    const std::string range = n > 1 && m != "size" ? fmt::format(" ({} to {})", said(*low), said(*highest)) : "";
    const std::string things = n == 1 ? "The one " + t.subject : fmt::format("The {} {}", n, t.subjectPlural);
    const std::string onAverage = n > 1 ? " on average" : "";
    if (m == "size")
        return fmt::format("{} {} {} wide, {} deep and {} tall{}.", things, n == 1 ? "is" : "are", said(mean(sides[0])),
                           said(mean(sides[1])), said(mean(sides[2])), onAverage);
    static const std::map<std::string, std::string, std::less<>> kSaid{
        {"height", "tall"}, {"width", "wide"}, {"depth", "deep"}, {"longest", "long"}, {"volume", "in volume"}};
    return fmt::format("{} {} {} {}{}{}.", things, n == 1 ? "is" : "are", said(mean(sides[0])),
                       above ? "above the floor" : kSaid.at(m), onAverage, range);
}

std::string size(const Translation& t, const ResultSet& rs) {
    if (t.average) return averageSize(t, rs);
    const std::string& m = t.measure;
    const bool high = t.predicate == "high";
    auto names = labels(rs);
    std::vector<std::string> parts;
    for (std::size_t r = 0; r < rs.rows.size(); ++r) {
        const auto box = rowSize(rs, r);
        if (!box) {
            parts.push_back(names[r] + " has no box");
            continue;
        }
        const std::optional<double> value = box->asked(m, high);
        // "how high is the sink?": how tall, and its top above the floor where it stands above the floor (a basin, a
        // shelf), as a person means a sink's or a counter's height.
        if (m == "height" && high && box->centre && *box->centre - box->height / 2 > kOnFloor)
            parts.push_back(fmt::format("{} is {} tall, its top {} above the floor", names[r],
                                        length(box->height, t.unit), length(*box->centre + box->height / 2, t.unit)));
        // A ceiling's height is how far above the floor it is (its box's bottom; the translator asks for z).
        else if (m == "height")
            parts.push_back(fmt::format("{} is {} {}", names[r], length(*value, t.unit),
                                        box->centre && !high ? "above the floor" : "tall"));
        else if (m == "width" || m == "depth")
            parts.push_back(
                fmt::format("{} is {} {}", names[r], length(*value, t.unit), m == "width" ? "wide" : "deep"));
        else if (m == "longest")
            parts.push_back(fmt::format("the longest side of {} is {}", names[r], length(*value, t.unit)));
        else if (m == "volume" && value)
            parts.push_back(fmt::format("{} takes {:.3f} m³", names[r], *value));
        else
            parts.push_back(fmt::format("{} is {} wide, {} deep and {} tall", names[r], length(box->width, t.unit),
                                        length(box->depth, t.unit), length(box->height, t.unit)));
    }
    if (parts.empty()) return noneFound(t);
    std::string out = listed(parts, "; ");
    // A sentence opens with a capital, unless it opens with a node's label, which is written as FIND takes it
    // ("tv#27 is 0.52 m tall", not "Tv#27").
    if (out.substr(0, out.find(' ')).find('#') == std::string::npos) out = capitalised(std::move(out));
    return out + ".";
}

// The area of the convex hull of points in the floor plane (Andrew's monotone chain).
double hullArea(std::vector<model::Vec2> p) {
    if (p.size() < 3) return 0;
    std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    auto cross = [](const model::Vec2& o, const model::Vec2& a, const model::Vec2& b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<model::Vec2> hull(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
        hull[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, lower = k + 1; i > 0; --i) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0) --k;
        hull[k++] = p[i - 1];
    }
    hull.resize(k > 0 ? k - 1 : 0);
    double area = 0;
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const auto& a = hull[i];
        const auto& b = hull[(i + 1) % hull.size()];
        area += a.x * b.y - b.x * a.y;
    }
    return std::abs(area) / 2;
}

std::string boxSize(const model::Box& b) {
    return fmt::format("{:.2f} x {:.2f} x {:.2f} m", b.size.x, b.size.y, b.size.z);
}

std::string superlative(const Translation& t, const ResultSet& rs) {
    if (rs.rows.size() < t.pick) {
        if (rs.rows.empty()) return noneFound(t);
        return fmt::format("There are only {} {}{}.", rs.rows.size(), rs.rows.size() == 1 ? t.subject : t.subjectPlural,
                           withCondition(t));
    }
    // "list the tables from largest to smallest": all of them, in order.
    if (t.top == std::numeric_limits<std::size_t>::max())
        return fmt::format("The {} {}, {}: {}.", rs.rows.size(), rs.rows.size() == 1 ? t.subject : t.subjectPlural,
                           t.measure, listed(labels(rs), ", ", rs.rows.size()));
    if (t.top > 1) {
        // "the two largest objects": each, in order.
        auto names = labels(rs);
        names.resize(std::min(names.size(), t.top));
        return fmt::format("The {} {}: {}.", t.measure, t.subjectPlural, listed(names));
    }
    const auto& row = rs.rows[t.pick - 1];
    std::string name = labels(rs)[t.pick - 1];
    static const std::array<std::string_view, 10> ordinals{"",      "second",  "third",  "fourth", "fifth",
                                                           "sixth", "seventh", "eighth", "ninth",  "tenth"};
    std::string ordinal = t.pick > 1 && t.pick <= ordinals.size() ? std::string(ordinals[t.pick - 1]) + " " : "";
    std::string detail;
    if (int d = rs.columnIndex("distance"); d >= 0) {
        if (auto metres = number(row[d]); metres && std::isfinite(*metres))
            detail = fmt::format(", {} away", length(*metres, t.unit));
    } else if (int b = rs.columnIndex("box"); b >= 0) {
        if (const auto* box = std::get_if<model::Box>(&row[b])) detail = fmt::format(", {}", boxSize(*box));
    }
    bool byDistance = t.measure.starts_with("closest") || t.measure.starts_with("nearest") ||
                      t.measure.starts_with("farthest") || t.measure.starts_with("furthest");
    std::string path;
    if (int p = rs.columnIndex("path"); p >= 0) path = fmt::format(" ({})", text(row[p]));
    // "which is closer to the toilet, the table or the sink?" where there is no table: the answer is among what is
    // here, and says what is not.
    const std::string absent = absentWords(t);
    const std::string missing = absent.empty() ? "" : " " + noneHere(t, absent);
    if (byDistance)
        return fmt::format("{} is the {}{} {}{}{}.{}", name, ordinal, t.subject, t.measure, detail, path, missing);
    return fmt::format("{} is the {}{} {}{}{}.{}", name, ordinal, t.measure, t.subject, detail, path, missing);
}

std::string direction(const Translation& t, const ResultSet& rs) {
    int id = rs.columnIndex("id"), category = rs.columnIndex("category"), box = rs.columnIndex("box");
    const std::array<std::string_view, 3> roleNames{" to stand by", " to face", ""};
    if (t.roles.size() < 3) return "There is nothing to place.";
    std::array<const Row*, 3> pickedRows{};
    std::array<std::vector<const Row*>, 3> found;
    std::vector<const Row*> asked;  // the things asked about, the one answered for first
    auto boxOf = [&](const Row* row) { return std::get<model::Box>((*row)[box]); };
    for (std::size_t role = 0; role < 3; ++role) {
        if (role == 1 && t.roles[1].empty()) continue;  // facing the middle of the scene
        // Only things with a box have a place to stand by or face.
        for (const auto& row : rs.rows)
            if (std::holds_alternative<model::Box>(row[box]) &&
                std::find(t.roles[role].begin(), t.roles[role].end(), text(row[category])) != t.roles[role].end())
                found[role].push_back(&row);
        if (const std::string kinds = listed(t.roles[role], " or "); found[role].empty())
            return fmt::format("There is no {} here{}.{}", kinds, roleNames[role], mayBeUnnamed(t, kinds));
    }
    // Of several things to stand by or to face, the two nearest each other: standing by a chair facing the desk is
    // standing by the desk's chair, not one across the room (the first of the rows where one of them is alone).
    pickedRows[0] = found[0].front();
    if (!found[1].empty()) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const Row* at : found[0])
            for (const Row* faced : found[1])
                if (at != faced)
                    if (const double gap = model::distance(boxOf(at), boxOf(faced)); gap < nearest) {
                        nearest = gap;
                        pickedRows[0] = at, pickedRows[1] = faced;
                    }
        if (!pickedRows[1]) return fmt::format("There is no other {} here to face.", listed(t.roles[1], " or "));
    }
    // The thing asked about is another than the one stood by or faced ("the other chair"); every one asked about
    // leaves those out. Of several, the nearest to where the person stands is the one meant, and answered first.
    auto other = [&](const Row* row) { return row != pickedRows[0] && row != pickedRows[1]; };
    const auto others = std::stable_partition(found[2].begin(), found[2].end(), other);
    asked.assign(found[2].begin(), others == found[2].begin() ? found[2].end() : others);
    auto gapTo = [&](const Row* row) { return model::distance(boxOf(row), boxOf(pickedRows[0])); };
    std::stable_sort(asked.begin(), asked.end(), [&](const Row* a, const Row* b) { return gapTo(a) < gapTo(b); });
    pickedRows[2] = asked.front();
    std::string notes;
    for (std::size_t role = 0; role < 3; ++role) {
        if (found[role].size() < 2 || (role == 2 && t.everyAsked)) continue;
        const Row* picked = pickedRows[role];
        const Row* by = role == 0 ? pickedRows[1] : pickedRows[0];
        notes += fmt::format(" There are {} {}{}; this takes {}#{}{}.", found[role].size(),
                             pluralOf(text((*picked)[category])), roleNames[role], text((*picked)[category]),
                             text((*picked)[id]),
                             by ? fmt::format(", the nearest to {}#{}", text((*by)[category]), text((*by)[id])) : "");
    }
    const model::Vec3 at = boxOf(pickedRows[0]).center;
    model::Vec3 facing{};
    if (pickedRows[1]) {
        facing = boxOf(pickedRows[1]).center;
    } else {
        // The middle of the scene: the mean centre of the things.
        double n = 0;
        for (const auto& row : rs.rows)
            if (std::holds_alternative<model::Box>(row[box])) {
                const auto c = std::get<model::Box>(row[box]).center;
                facing.x += c.x, facing.y += c.y, n += 1;
            }
        facing.x /= n, facing.y /= n;
    }
    bool quadrants = std::find(t.choices.begin(), t.choices.end(), "front-left") != t.choices.end();
    bool back = std::find(t.choices.begin(), t.choices.end(), "back") != t.choices.end();
    bool front = std::find(t.choices.begin(), t.choices.end(), "front") != t.choices.end();
    auto label = [&](const Row* row) { return text((*row)[category]) + "#" + text((*row)[id]); };
    // Which way a thing is: its angle from the person's heading (left positive), the side and the answer's word.
    struct Way {
        double angle;
        std::string side, word;
    };
    auto wayTo = [&](const Row* row) {
        const model::Vec3 to = boxOf(row).center;
        double fx = facing.x - at.x, fy = facing.y - at.y, vx = to.x - at.x, vy = to.y - at.y;
        // Counter-clockwise from the facing direction is to the left (z up); a situation's person faces
        // `turn` quarter turns counter-clockwise of that.
        double angle = std::atan2(fx * vy - fy * vx, fx * vx + fy * vy) / model::kDegree - 90.0 * t.turn;
        angle = std::remainder(angle, 360.0);
        std::string side = angle > 0 ? "left" : "right";
        std::string word;
        if (quadrants)
            word = std::string(std::abs(angle) <= 90 ? "front-" : "back-") + side;
        else if (back && std::abs(angle) >= 135)
            word = "back";
        else if (front && std::abs(angle) <= 45)
            word = "front";
        else
            word = side;
        return Way{angle, side, word};
    };
    // How far: between the closest points of the boxes of the thing stood by and the thing asked about (gapTo).
    auto away = [&](const Row* row) {
        const double gap = gapTo(row);
        return gap < 0.05 ? fmt::format("beside {}", label(pickedRows[0]))
                          : fmt::format("{:.1f} m from {}", gap, label(pickedRows[0]));
    };
    if (t.everyAsked && asked.size() > 1) {
        // "where is the lamp?" where there are several: each, nearest first.
        std::vector<std::string> each;
        for (const Row* row : asked)
            each.push_back(fmt::format("{} to your {}, {}", label(row), wayTo(row).word, away(row)));
        return fmt::format("{} {}, nearest first, {}: {}.{}", asked.size(), t.subjectPlural, t.object,
                           listed(each, "; "), notes);
    }
    const Way way = wayTo(pickedRows[2]);
    if (t.turn != 0 || !pickedRows[1])
        return fmt::format("The {} is to your {} ({}, {}, is {:.0f} degrees to the {} of your heading, {}).{}",
                           t.subject, way.word, label(pickedRows[2]), away(pickedRows[2]), std::abs(way.angle),
                           way.side, t.object, notes);
    return fmt::format("The {} is to your {} ({}, {}, is {:.0f} degrees to the {} of the way from {} to {}).{}",
                       t.subject, way.word, label(pickedRows[2]), away(pickedRows[2]), std::abs(way.angle), way.side,
                       label(pickedRows[0]), label(pickedRows[1]), notes);
}

std::string affordance(const Translation& t, const ResultSet& rs) {
    if (rs.rows.empty())
        return t.condition.empty() ? fmt::format("Nothing here to {}.", t.predicate)
                                   : fmt::format("Nothing to {} {}.", t.predicate, t.condition);
    return fmt::format("You can {} {}{}: {}", t.predicate,
                       rs.rows.size() == 1 ? "1 thing" : fmt::format("{} things", rs.rows.size()), withCondition(t),
                       listed(labels(rs)));
}

// How many people the seats found take: each one place for every kSeatPlaceWidth of its longest side.
std::string seating(const Translation& t, const ResultSet& rs) {
    const int width = rs.columnIndex("width");
    const auto names = labels(rs);
    std::size_t total = 0;
    std::vector<std::string> ones, several;
    for (std::size_t r = 0; r < rs.rows.size(); ++r) {
        const std::optional<double> longest = width >= 0 ? number(rs.rows[r][width]) : std::nullopt;
        if (!longest) continue;  // no box: no place to sit
        const std::size_t places = model::seatPlaces(*longest);
        total += places;
        if (places == 1)
            ones.push_back(names[r]);
        else
            several.push_back(fmt::format("{} on {}, {} long", places, names[r], length(*longest, t.unit)));
    }
    if (total == 0) {
        if (const std::string absent = absentWords(t); !absent.empty()) return noneHere(t, absent);
        return t.object.empty() || t.condition == "on"
                   ? "There is nothing to sit on here."
                   : fmt::format("There is nothing to sit on {} the {}.", t.condition, t.object);
    }
    if (!ones.empty()) several.push_back(ones.size() == 1 ? "1 on " + ones.front() : "1 on each of " + listed(ones));
    const std::string how =
        fmt::format("one place for every {} of a seat's length", length(model::kSeatPlaceWidth, t.unit));
    const std::string where = t.object.empty() ? "" : fmt::format(" {} the {}", t.condition, t.object);
    return fmt::format("About {} {} can sit{}: {} ({}).", total, total == 1 ? "person" : "people", where,
                       listed(several, "; "), how);
}

// "a bed", "an oven", "2 microwaves".
std::string counted(const std::string& category, std::size_t n) {
    return n == 1 ? withArticle(category) : fmt::format("{} {}", n, pluralOf(category));
}

// A tally of kinds in words, in its order ("5 chairs", "a bed"), and the things no model named last ("6 other
// things"): how DESCRIBE's room and "what kinds of things are there?" say what a place holds.
std::vector<std::string> tallied(const std::vector<std::pair<std::string, std::size_t>>& kinds, std::size_t unnamed) {
    std::vector<std::string> out;
    for (const auto& [category, n] : kinds) out.push_back(counted(model::categoryWords(category), n));
    if (unnamed) out.push_back(unnamed == 1 ? "1 other thing" : fmt::format("{} other things", unnamed));
    return out;
}

std::string roomKind(const Translation& t, const ResultSet& rs);

// A thing that marks a kind of room (a bed: the bedroom), by its row.
struct RoomMark {
    std::size_t row;
    std::string room;
};
// A kind of room by its mark nearest a box.
struct RoomNear {
    std::string room;
    std::size_t row;
    double metres;
};

// Each kind of room once, by its mark nearest `own`, nearest first.
std::vector<RoomNear> roomsNear(const model::Box& own, const std::vector<RoomMark>& marks, const ResultSet& rs,
                                int box) {
    std::vector<RoomNear> near;
    for (const auto& m : marks) {
        const double metres = model::distance(own, std::get<model::Box>(rs.rows[m.row][box]));
        auto same = std::find_if(near.begin(), near.end(), [&](const RoomNear& n) { return n.room == m.room; });
        if (same == near.end())
            near.push_back({m.room, m.row, metres});
        else if (metres < same->metres)
            *same = {m.room, m.row, metres};
    }
    std::sort(near.begin(), near.end(), [](const RoomNear& a, const RoomNear& b) { return a.metres < b.metres; });
    return near;
}

// "which room has the most chairs?", "how many chairs are in each room?": each thing in the kind of room whose mark
// stands nearest it within a room's area (or that it marks), the rooms by how many they hold.
std::string roomWithMost(const Translation& t, const ResultSet& rs, const std::vector<std::size_t>& things,
                         const std::vector<RoomMark>& marks) {
    const int box = rs.columnIndex("box");
    std::map<std::string, std::size_t> held;
    for (const auto& m : marks) held.try_emplace(m.room, 0);  // a room that holds none of them counts 0
    for (const std::size_t r : things) {
        const auto own = std::find_if(marks.begin(), marks.end(), [&](const RoomMark& m) { return m.row == r; });
        if (own != marks.end()) {
            ++held[own->room];
            continue;
        }
        const auto near = roomsNear(std::get<model::Box>(rs.rows[r][box]), marks, rs, box);
        if (near.front().metres <= kRoomAreaReach) ++held[near.front().room];
    }
    const auto order = mostFirst(held);
    std::vector<std::string> each;
    for (const auto& [room, n] : order) each.push_back(fmt::format("the {} {}", room, n));
    const std::size_t outside =
        things.size() - std::accumulate(order.begin(), order.end(), std::size_t{0},
                                        [](std::size_t sum, const auto& o) { return sum + o.second; });
    if (outside) each.push_back(fmt::format("{} in no room's area", outside));
    if (t.measure == "each")
        return fmt::format("{} {} by room: {}.", things.size(), things.size() == 1 ? t.subject : t.subjectPlural,
                           listed(each, ", ", each.size()));
    const bool most = t.measure == "most";
    const auto& picked = most ? order.front() : order.back();
    if (std::count_if(order.begin(), order.end(), [&](const auto& o) { return o.second == picked.second; }) > 1)
        return fmt::format("No room has {} {} than the others: {}.", most ? "more" : "fewer", t.subjectPlural,
                           listed(each, ", ", each.size()));
    return fmt::format("The {} has the {} {}: {}.", picked.first, t.measure, t.subjectPlural,
                       listed(each, ", ", each.size()));
}

// Which room a thing is in (QuestionKind::RoomOf): for each thing asked about (the last of Translation::roles; empty:
// every thing), the kinds of room (choices, marked by the other roles) whose marks stand within a room's area of it
// (kRoomAreaReach), the nearest first; a thing that marks a room is in that room.
std::string roomOf(const Translation& t, const ResultSet& rs) {
    const int category = rs.columnIndex("category"), box = rs.columnIndex("box");
    if (category < 0 || box < 0 || t.roles.empty()) return noneFound(t);
    const auto names = labels(rs);
    const std::vector<std::string>& asked = t.roles.back();
    auto roomMarkedBy = [&](const std::string& c) -> std::optional<std::string> {
        for (std::size_t k = 0; k + 1 < t.roles.size() && k < t.choices.size(); ++k)
            if (std::find(t.roles[k].begin(), t.roles[k].end(), c) != t.roles[k].end()) return t.choices[k];
        return std::nullopt;
    };
    std::vector<std::size_t> things;
    std::vector<RoomMark> marks;
    for (std::size_t r = 0; r < rs.rows.size(); ++r) {
        if (!std::holds_alternative<model::Box>(rs.rows[r][box])) continue;
        const std::string c = text(rs.rows[r][category]);
        if (asked.empty() || std::find(asked.begin(), asked.end(), c) != asked.end()) things.push_back(r);
        if (auto room = roomMarkedBy(c)) marks.push_back({r, *room});
    }
    if (things.empty()) return noneFound(t);
    if (marks.empty())
        return fmt::format(
            "Nothing here marks a kind of room (a bed, a sofa, a fridge, a toilet or a desk): the {} "
            "{} in no room a thing names.",
            things.size() == 1 ? t.subject : t.subjectPlural, things.size() == 1 ? "is" : "are");
    // A scene whose things mark fewer kinds of room than a home's several is one room (an office with a sofa is an
    // office): everything in it is in it, and the room is what roomKind says of it.
    std::set<std::string> rooms;
    for (const auto& m : marks) rooms.insert(m.room);
    if (rooms.size() < kSeveralRooms) {
        std::string looks = roomKind(t, rs);  // "It looks like a living room (2 sofas)."
        looks.front() = static_cast<char>(std::tolower(static_cast<unsigned char>(looks.front())));
        return things.size() == 1
                   ? fmt::format("{} is in this room: {}", names[things.front()], looks)
                   : fmt::format("The {} {} are in this room: {}", things.size(), t.subjectPlural, looks);
    }
    // Where one thing is: "in the living room (sofa#7, 0.06 m); by the bedroom (bed#8, 0.27 m) too".
    auto placeOf = [&](std::size_t thing, bool one) {
        const auto& own = std::get<model::Box>(rs.rows[thing][box]);
        if (auto room = roomMarkedBy(text(rs.rows[thing][category])))
            return fmt::format("in the {}{}", *room,
                               one ? fmt::format(": {} marks it", names[thing]) : ", which it marks");
        const std::vector<RoomNear> near = roomsNear(own, marks, rs, box);
        const RoomNear& first = near.front();
        if (first.metres > kRoomAreaReach)
            return fmt::format("in no room's area ({}, {} the nearest mark of one, is {} away)", names[first.row],
                               withArticle(first.room), length(first.metres, t.unit));
        std::string out =
            one ? fmt::format("in the {}: {} is {} from it", first.room, names[first.row], length(first.metres, t.unit))
                : fmt::format("in the {} ({}, {})", first.room, names[first.row], length(first.metres, t.unit));
        std::vector<std::string> also;
        for (std::size_t k = 1; k < near.size() && near[k].metres <= kRoomAreaReach; ++k)
            also.push_back(
                fmt::format("the {} ({}, {})", near[k].room, names[near[k].row], length(near[k].metres, t.unit)));
        if (!also.empty()) out += fmt::format("{} by {} too", one ? ";" : ",", listedWithAnd(also));
        return out;
    };
    if (t.measure == "most" || t.measure == "fewest" || t.measure == "each") return roomWithMost(t, rs, things, marks);
    if (things.size() == 1) return fmt::format("The {} is {}.", t.subject, placeOf(things.front(), true));
    std::vector<std::string> each;
    for (std::size_t thing : things) each.push_back(fmt::format("{} is {}", names[thing], placeOf(thing, false)));
    return fmt::format("{} {}: {}.", things.size(), t.subjectPlural, listed(each, "; "));
}

// The kinds of room the things mark (Translation::choices, each marked by the categories in the same place of roles),
// most marked first; "is this a kitchen?" (Translation::predicate) answered yes or no.
std::string roomKind(const Translation& t, const ResultSet& rs) {
    const int category = rs.columnIndex("category");
    std::map<std::string, std::size_t> held;
    for (const auto& row : rs.rows) ++held[text(row[category])];
    struct Marked {
        std::string room;
        std::vector<std::string> things;  // "a bed", "2 nightstands"
        std::size_t count = 0;
    };
    std::vector<Marked> marked;
    for (std::size_t k = 0; k < t.choices.size(); ++k) {
        Marked m{t.choices[k], {}, 0};
        for (const auto& c : t.roles[k])
            if (auto it = held.find(c); it != held.end()) {
                m.things.push_back(counted(c, it->second));
                m.count += it->second;
            }
        if (m.count > 0) marked.push_back(std::move(m));
    }
    std::stable_sort(marked.begin(), marked.end(), [](const Marked& a, const Marked& b) {
        return a.things.size() != b.things.size() ? a.things.size() > b.things.size() : a.count > b.count;
    });
    // "a kitchen's (a fridge and an oven), a bedroom's (a bed)"
    auto eachRoom = [&] {
        std::vector<std::string> each;
        for (const auto& m : marked)
            each.push_back(fmt::format("{}'s ({})", withArticle(m.room), listedWithAnd(m.things)));
        return listedWithAnd(each);
    };
    auto looks = [&]() -> std::string {
        if (marked.empty())
            return fmt::format(
                "nothing among its {} {} marks a kind of room (a bed, a sofa, a fridge, a toilet or a desk)",
                rs.rows.size(), rs.rows.size() == 1 ? "thing" : "things");
        // Three kinds or more: one space of several rooms (a studio apartment).
        if (marked.size() >= kSeveralRooms)
            return "it holds the things of several rooms, as a home or a studio does: " + eachRoom();
        std::string out = fmt::format("it looks like {} ({})", withArticle(marked.front().room),
                                      listedWithAnd(marked.front().things));
        if (marked.size() == 1) return out;
        return fmt::format("{}, with {}'s things ({})", out, withArticle(marked[1].room),
                           listedWithAnd(marked[1].things));
    };
    // The kind of room asked about ("is this a kitchen?", "how many bedrooms are there?"), among those marked.
    const auto it = std::find_if(marked.begin(), marked.end(), [&](const Marked& m) { return m.room == t.predicate; });
    // "how many bedrooms are there?": things mark a kind of room, not how many rooms of it there are.
    if (t.measure == "count" && !t.predicate.empty()) {
        if (it != marked.end())
            return fmt::format("At least one {}: it holds {} (the memory does not tell rooms of one kind apart).",
                               t.predicate, listedWithAnd(it->things));
        return fmt::format("None: nothing here marks {}; {}.", withArticle(t.predicate), looks());
    }
    // "how many rooms are there?": the kinds of room the things mark, as many rooms as a person would count by
    // them; one space that marks fewer kinds than a home's several is one room.
    if (t.measure == "count")
        return marked.size() < kSeveralRooms ? fmt::format("One room: {}.", looks())
                                             : fmt::format("{} rooms, by their things: {}.", marked.size(), eachRoom());
    if (!t.predicate.empty()) {
        if (it != marked.end()) return fmt::format("Yes: it holds {}.", listedWithAnd(it->things));
        return fmt::format("No: nothing here marks {}; {}.", withArticle(t.predicate), looks());
    }
    return capitalised(looks()) + ".";
}

std::string attribute(const Translation& t, const ResultSet& rs) {
    int column = rs.columnIndex(t.measure);
    auto names = labels(rs);
    std::vector<std::string> parts;
    for (std::size_t r = 0; r < rs.rows.size(); ++r) {
        std::string value = column >= 0 ? text(rs.rows[r][column]) : "";
        parts.push_back(value.empty() ? fmt::format("{} has no {} recorded", names[r], t.measure)
                                      : fmt::format("{} is {}", names[r], value));
    }
    if (parts.empty()) return noneFound(t);
    return listed(parts, "; ") + ".";
}

// "How many colours are there?": the attribute's values over the things, the most common first, and how many things
// have none recorded; "what is the most common colour?" (predicate "most") leads with it.
std::string attributeTally(const Translation& t, const ResultSet& rs) {
    const int column = rs.columnIndex(t.measure);
    std::map<std::string, std::size_t> tally;
    std::size_t none = 0;
    for (const auto& row : rs.rows) {
        const std::string value = column >= 0 ? text(row[static_cast<std::size_t>(column)]) : "";
        if (value.empty())
            ++none;
        else
            ++tally[value];
    }
    if (tally.empty())
        return fmt::format("No {} is recorded for the {} things here (their capture gave none).", t.measure,
                           rs.rows.size());
    const auto byCount = mostFirst(tally);
    std::vector<std::string> each;
    for (const auto& [value, n] : byCount) each.push_back(fmt::format("{} ({})", value, n));
    const std::string all = fmt::format(
        "{} {} among {} things: {}{}.", byCount.size(), byCount.size() == 1 ? t.measure : pluralOf(t.measure),
        rs.rows.size(), listedWithAnd(each), none ? fmt::format("; {} with none recorded", none) : std::string());
    if (t.predicate != "most") return all;
    return fmt::format("{} is the most common {} ({} things): {}", capitalised(byCount.front().first), t.measure,
                       byCount.front().second, all);
}

// "what is the lamp on?": the things the subject stands in that relation to.
// The rows of RELATE subject TO thing that answer "what is the subject on?": those of the
// question's relation, and "attached" for "on" where the subject rests on nothing.
std::vector<std::size_t> reverseRows(const Translation& t, const ResultSet& rs) {
    int relation = rs.columnIndex("relation"), subject = rs.columnIndex("subject"), object = rs.columnIndex("object");
    std::vector<std::size_t> out;
    if (relation < 0 || subject < 0 || object < 0) return out;
    // Resting on a thing or hanging on it are both "on" in English; a subject that rests on
    // something is said to be on that, not on the wall it touches.
    auto categoryOf = [](const std::string& label) { return label.substr(0, label.find('#')); };
    auto isBackground = [&](const std::string& label) {
        return std::find(t.background.begin(), t.background.end(), categoryOf(label)) != t.background.end();
    };
    std::set<std::string> resting, onThings;  // subjects resting on something; on a thing, not an anchor
    std::set<std::string> onWall;             // subjects attached to a wall
    // What each subject rests on or in: "what is the mug next to?" asks what stands beside it, not the table it is on.
    std::set<std::pair<std::string, std::string>> carriers;
    for (const auto& row : rs.rows) {
        if (isOneOf(text(row[relation]), {"on", "in"})) carriers.emplace(text(row[subject]), text(row[object]));
        if (text(row[relation]) == t.predicate) {
            resting.insert(text(row[subject]));
            if (!isBackground(text(row[object]))) onThings.insert(text(row[subject]));
        }
        if (text(row[relation]) == "attached" && categoryOf(text(row[object])) == "wall")
            onWall.insert(text(row[subject]));
    }
    for (std::size_t i = 0; i < rs.rows.size(); ++i) {
        const auto& row = rs.rows[i];
        std::string r = text(row[relation]), s = text(row[subject]);
        const bool toWall = categoryOf(text(row[object])) == "wall";
        // A door, a window or a picture is in a wall as much as on it: "which wall is the door in?".
        const bool inWall = t.predicate == "in" && (r == "on" || r == "attached") && toWall;
        // A thing on nothing that a wall holds hangs on the wall, not on the window beside it or the floor
        // its lower edge meets ("what is the door on?").
        const bool hangs = t.predicate == "on" && r == "attached" && !resting.count(s) && (!onWall.count(s) || toWall);
        // Beside it, not under it: "what is the lamp above?" may well be the table it stands on.
        const bool carrier = isOneOf(t.predicate, {"near", "left_of", "right_of", "in_front_of", "behind"}) &&
                             carriers.count({s, text(row[object])});
        bool match = (r == t.predicate && !carrier) || hangs || inWall;
        // On the rug, not on the floor and the rug.
        if (match && !(onThings.count(s) && isBackground(text(row[object])))) out.push_back(i);
    }
    return out;
}

std::string reverse(const Translation& t, const ResultSet& rs) {
    const int subject = rs.columnIndex("subject"), object = rs.columnIndex("object");
    std::map<std::string, std::vector<std::string>> held;  // subject -> objects
    std::vector<std::string> order;
    for (std::size_t i : reverseRows(t, rs)) {
        std::string s = text(rs.rows[i][subject]);
        if (!held.count(s)) order.push_back(s);
        held[s].push_back(text(rs.rows[i][object]));
    }
    if (order.empty()) {
        if (rs.rows.empty()) return fmt::format("There is no {} here.{}", t.subject, subjectMayBeUnnamed(t));
        // Off the floor, a thing rests on something, which the capture may not have shown (a mug on a shelf).
        if (t.predicate == "on")
            return fmt::format("Nothing stored: the {} is on nothing the memory holds.", t.subject);
        return fmt::format("Nothing: the {} is not {} anything here.", t.subject, t.condition);
    }
    std::vector<std::string> parts;
    for (const auto& s : order) parts.push_back(fmt::format("{} is {} {}", s, t.condition, listedThings(held[s])));
    return listed(parts, "; ") + ".";
}

// "Is the sofa longer than the bed?": every node of one side against every node of the other, by
// the measure the comparative names; yes when every pair holds, no when none does.
std::string comparison(const Translation& t, const ResultSet& rs) {
    const int id = rs.columnIndex("id"), category = rs.columnIndex("category"), value = rs.columnIndex(t.measure);
    if (t.roles.size() != 2 || id < 0 || category < 0 || value < 0) return "There is nothing to compare.";
    struct Side {
        std::vector<std::pair<std::string, double>> nodes;  // label, value
    };
    std::array<Side, 2> sides;
    for (const auto& row : rs.rows) {
        auto v = number(row[value]);
        if (!v || !std::isfinite(*v)) continue;
        const std::string cat = text(row[category]), node = "#" + text(row[id]);
        for (std::size_t s = 0; s < 2; ++s) {
            const auto& role = t.roles[s];
            if (std::find(role.begin(), role.end(), cat) != role.end() ||
                std::find(role.begin(), role.end(), node) != role.end())
                sides[s].nodes.emplace_back(cat + node, *v);
        }
    }
    if (sides[0].nodes.empty())
        return fmt::format("There is no {} here to compare.{}", t.subject, mayBeUnnamed(t, t.subject));
    if (sides[1].nodes.empty())
        return fmt::format("There is no {} here to compare.{}", t.object, mayBeUnnamed(t, t.object));
    std::size_t holds = 0, pairs = 0;
    for (const auto& [a, va] : sides[0].nodes)
        for (const auto& [b, vb] : sides[1].nodes) {
            if (a == b) continue;
            ++pairs;
            holds += t.greater ? va > vb : va < vb;
        }
    auto said = [&](double v) {
        if (t.measure == "volume") return fmt::format("{:.3f} m³ in volume", v);
        if (t.measure == "z") return fmt::format("{} high (its centre)", formatLength(v, t.unit));
        return fmt::format("{} {}", formatLength(v, t.unit), t.condition);
    };
    std::vector<std::string> values;
    for (const auto& side : sides)
        for (const auto& [label, v] : side.nodes) values.push_back(fmt::format("{} is {}", label, said(v)));
    const std::string than = fmt::format("{} than the {}", t.predicate, t.object);
    // By how much: the first of each side in the rows' order (the tallest of each, for "taller").
    if (t.byHowMuch) {
        const auto& [a, va] = sides[0].nodes.front();
        // Two of one kind ("are the two beds the same size?"): the first and the next.
        const bool oneKind = sides[1].nodes.front().first == a;
        if (oneKind && sides[1].nodes.size() < 2) return fmt::format("There is only one {} here.", t.subject);
        const auto& [b, vb] = sides[1].nodes[oneKind ? 1 : 0];
        const double by = t.greater ? va - vb : vb - va;
        const std::string amount =
            t.measure == "volume" ? fmt::format("{:.3f} m³", std::abs(by)) : formatLength(std::abs(by), t.unit);
        std::vector<std::string> picked;  // "chair#20 of 4 chairs"
        const std::array<std::string, 2> plurals{t.subjectPlural, pluralOf(t.object)};
        for (std::size_t side = 0; side < (oneKind ? 0 : 2); ++side)
            if (sides[side].nodes.size() > 1)
                picked.push_back(fmt::format("{} of {} {}", sides[side].nodes.front().first, sides[side].nodes.size(),
                                             plurals[side]));
        const std::string several =
            picked.empty() ? "" : fmt::format(" ({}, the first by {})", listedWithAnd(picked), t.measure);
        if (t.eitherWay && t.predicate == "the same") {
            // Alike within what a person would not tell apart by eye: 5 cm or 5 % of a length, 10 % of a volume.
            const double larger = std::max(std::abs(va), std::abs(vb));
            const bool alike = t.measure == "volume" ? std::abs(va - vb) <= 0.1 * larger
                                                     : std::abs(va - vb) <= std::max(0.05, 0.05 * larger);
            return fmt::format("{}: {} is {}; {} is {} ({} apart){}.", alike ? "Yes, about the same" : "No", a,
                               said(va), b, said(vb), amount, several);
        }
        if (t.eitherWay) {
            if (by == 0) return fmt::format("{} and {} are alike: each is {}{}.", a, b, said(va), several);
            return fmt::format("{} is {}: {} {} than {}, {}{}.", a, said(va), amount, (va > vb) ? "more" : "less", b,
                               said(vb), several);
        }
        if (by <= 0) return fmt::format("It is not: {} is {}; {} is {}{}.", a, said(va), b, said(vb), several);
        return fmt::format("{} is {} {} ({}): {} against {}{}.", a, amount, than, b, said(va), said(vb), several);
    }
    std::string verdict;
    if (pairs == 0)
        verdict = fmt::format("There is nothing but the {} itself to compare", t.subject);
    else if (holds == pairs)
        verdict = fmt::format("Yes, the {} is {}", t.subject, than);
    else if (holds == 0)
        verdict = fmt::format("No, the {} is not {}", t.subject, than);
    else
        verdict = fmt::format("Partly: {} of {} pairs of {} and {} hold", holds, pairs, t.subject, t.object);
    return fmt::format("{}: {}.", verdict, listed(values, "; ", 6));
}

// The room's floor area: inside its walls (the convex hull of their footprints), else its floor's
// footprint, else the area the layout came with (a room node's `area`, else its box).
std::string roomSize(const Translation& t, const ResultSet& rs) {
    const int category = rs.columnIndex("category"), kind = rs.columnIndex("kind"), box = rs.columnIndex("box"),
              area = rs.columnIndex("area");
    std::vector<model::Vec2> wallCorners;
    std::size_t walls = 0;
    double floor = 0, room = 0;
    for (const auto& row : rs.rows) {
        const auto* b = box >= 0 ? std::get_if<model::Box>(&row[box]) : nullptr;
        const std::string cat = category >= 0 ? text(row[category]) : "", k = kind >= 0 ? text(row[kind]) : "";
        if (k == "room") {
            if (auto a = area >= 0 ? number(row[area]) : std::nullopt)
                room += *a;
            else if (const auto* s = area >= 0 ? std::get_if<std::string>(&row[area]) : nullptr; s && !s->empty())
                room += std::strtod(s->c_str(), nullptr);
            else if (b)
                room += model::footprintArea(*b);
        } else if (cat == "wall" && b) {
            ++walls;
            for (const auto& c : model::footprint(*b)) wallCorners.push_back(c);
        } else if (cat == "floor" && b) {
            floor += model::footprintArea(*b);
        }
    }
    double metres2 = 0;
    std::string how;
    if (walls >= 3) {
        metres2 = hullArea(wallCorners);
        how = fmt::format("inside its {} walls", walls);
    }
    if (metres2 <= 0 && floor > 0) metres2 = floor, how = "its floor's extent";
    if (metres2 <= 0 && room > 0) metres2 = room, how = "the figure its layout came with";
    if (metres2 <= 0) return "The memory holds no walls, floor or room figure to measure the room by.";
    (void)t;
    return fmt::format("The room is about {:.1f} m² ({}).", metres2, how);
}

// The room's outline seen from above, a rectangle: its floor's footprint where the memory holds a floor, else the
// rectangle that holds every thing's footprint, turned as the things stand: furniture, doors and windows stand square
// to the walls, so of the turns of the things' boxes (a quarter of a circle apart are one) the one most of them
// share within 5 degrees, each counted by its longer side.
struct RoomOutline {
    model::Vec2 centre;
    double yaw = 0;
    double halfX = 0, halfY = 0;  // along the turned axes
    std::string how;
    double floor = 0;  // the floor's top, where the memory holds a floor
};

std::optional<RoomOutline> roomOutline(const ResultSet& rs) {
    const int category = rs.columnIndex("category"), box = rs.columnIndex("box");
    if (box < 0) return std::nullopt;
    std::vector<model::Vec2> corners;
    std::vector<std::pair<double, double>> turns;  // a box's turn in [0, 90) degrees, and its longer side
    for (const auto& row : rs.rows) {
        const auto* b = std::get_if<model::Box>(&row[box]);
        if (!b) continue;
        if (category >= 0 && text(row[category]) == "floor")
            return RoomOutline{
                {b->center.x, b->center.y}, b->yaw, b->size.x / 2, b->size.y / 2, "its floor", model::top(*b)};
        if (category >= 0 && text(row[category]) == "ceiling") continue;
        for (const auto& c : model::footprint(*b)) corners.push_back(c);
        turns.emplace_back(std::fmod(std::fmod(b->yaw, M_PI / 2) + M_PI / 2, M_PI / 2), std::max(b->size.x, b->size.y));
    }
    if (corners.empty()) return std::nullopt;
    constexpr double kShared = 5 * M_PI / 180;
    double yaw = 0, most = -1;
    for (const auto& [turn, side] : turns) {
        double shared = 0;
        for (const auto& [other, length] : turns) {
            const double apart = std::abs(turn - other);
            if (std::min(apart, M_PI / 2 - apart) <= kShared) shared += length;
        }
        if (shared > most) yaw = turn, most = shared;
    }
    const double c = std::cos(yaw), s = std::sin(yaw);
    double x0 = 1e18, x1 = -1e18, y0 = 1e18, y1 = -1e18;
    for (const auto& p : corners) {
        const double u = c * p.x + s * p.y, v = -s * p.x + c * p.y;
        x0 = std::min(x0, u), x1 = std::max(x1, u), y0 = std::min(y0, v), y1 = std::max(y1, v);
    }
    const double u = (x0 + x1) / 2, v = (y0 + y1) / 2;
    return RoomOutline{{c * u - s * v, s * u + c * v}, yaw, (x1 - x0) / 2, (y1 - y0) / 2, "its things"};
}

// m from a corner of the room's outline within which a thing stands in that corner.
constexpr double kCornerReach = 1.0;
// m above the floor: a thing whose bottom is this high hangs overhead (a ceiling light).
constexpr double kOverhead = 1.8;

// What is in the middle of the room, or in its corners (QuestionKind::RoomPlace, `measure` "middle" or "corner").
// The middle: the things whose footprints come within an eighth of the outline's shorter side of its centre (0.3 m
// at least), nearest first, said as a person sees them: what stands on the floor there, what rests on those, what
// hangs overhead. A corner: the things standing on the floor within kCornerReach of it, each in its nearest corner.
std::string roomPlace(const Translation& t, const ResultSet& rs) {
    const int id = rs.columnIndex("id"), category = rs.columnIndex("category"), kind = rs.columnIndex("kind"),
              box = rs.columnIndex("box");
    const auto outline = roomOutline(rs);
    if (!outline || id < 0 || category < 0 || kind < 0)
        return "The memory holds no floor or things to find the room's outline by.";
    const double floor = outline->floor;
    struct Thing {
        std::string label;
        model::Box box;
    };
    std::vector<Thing> things;
    for (const auto& row : rs.rows)
        if (const auto* b = std::get_if<model::Box>(&row[box]); b && text(row[kind]) == "object")
            things.push_back({text(row[category]) + "#" + text(row[id]), *b});
    auto standing = [&](const Thing& thing) { return model::bottom(thing.box) - floor <= kOnFloor; };
    const std::string room =
        fmt::format("{:.1f} x {:.1f} m by {}", 2 * outline->halfX, 2 * outline->halfY, outline->how);
    const double reach = std::max(0.3, std::min(outline->halfX, outline->halfY) / 4);
    auto gap = [&](const Thing& thing) { return model::footprintGap(thing.box, outline->centre); };
    // The corners, counter-clockwise from the outline's own first.
    const double c = std::cos(outline->yaw), s = std::sin(outline->yaw);
    std::array<model::Vec2, 4> corners;
    const std::array<std::pair<double, double>, 4> signs{{{1, 1}, {-1, 1}, {-1, -1}, {1, -1}}};
    for (std::size_t k = 0; k < 4; ++k) {
        const double u = signs[k].first * outline->halfX, v = signs[k].second * outline->halfY;
        corners[k] = {outline->centre.x + c * u - s * v, outline->centre.y + s * u + c * v};
    }
    auto cornerGap = [&](const Thing& thing) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const auto& corner : corners) nearest = std::min(nearest, model::footprintGap(thing.box, corner));
        return nearest;
    };
    if (!t.roles.empty()) {
        // "Is the table in the middle of the room?": each thing of the kind asked about, in it or not, as the
        // listing below measures it (a corner holds what stands on the floor within kCornerReach of it).
        std::vector<std::string> in, out;
        for (const auto& row : rs.rows) {
            const auto* b = std::get_if<model::Box>(&row[box]);
            if (!b || std::find(t.roles[0].begin(), t.roles[0].end(), text(row[category])) == t.roles[0].end())
                continue;
            const Thing thing{text(row[category]) + "#" + text(row[id]), *b};
            const bool middle = t.measure == "middle";
            const double metres = middle ? gap(thing) : cornerGap(thing);
            const bool holds = middle ? metres <= reach : metres <= kCornerReach && standing(thing);
            const std::string where = middle ? "its centre" : "the nearest corner";
            (holds ? in : out)
                .push_back(metres < 0.05 ? fmt::format("{} (over {})", thing.label, where)
                                         : fmt::format("{} ({:.1f} m from {})", thing.label, metres, where));
        }
        const std::string place = t.measure == "middle" ? "in the middle of the room" : "in a corner";
        const std::string measure =
            t.measure == "middle"
                ? fmt::format("{}; the middle within {:.1f} m of its centre", room, reach)
                : fmt::format("{}; a corner holds what stands on the floor within {:.1f} m of it", room, kCornerReach);
        if (in.empty() && out.empty()) return noneHere(t, listed(t.roles[0], " or "));
        if (out.empty())
            return fmt::format("Yes: {} {} {} ({}).", listedWithAnd(in), in.size() == 1 ? "is" : "are", place, measure);
        if (in.empty())
            return fmt::format("No: {} {} not {} ({}).", listedWithAnd(out), out.size() == 1 ? "is" : "are", place,
                               measure);
        return fmt::format("{} of the {} {}: {}; not {} ({}).", in.size(), in.size() + out.size(), t.subjectPlural,
                           in.size() == 1 ? "is " + place : "are " + place, listedWithAnd(in), listedWithAnd(out),
                           measure);
    }
    if (t.measure == "middle") {
        std::stable_sort(things.begin(), things.end(), [&](const Thing& a, const Thing& b) { return gap(a) < gap(b); });
        std::vector<std::string> onFloor, onThose, overhead;
        for (const auto& thing : things) {
            if (gap(thing) > reach) continue;
            const double bottom = model::bottom(thing.box) - floor;
            (bottom <= kOnFloor ? onFloor : bottom >= kOverhead ? overhead : onThose).push_back(thing.label);
        }
        std::vector<std::string> parts;
        if (!onFloor.empty()) parts.push_back("on the floor " + listedWithAnd(onFloor));
        if (!onThose.empty()) parts.push_back((onFloor.empty() ? "raised " : "on those ") + listedWithAnd(onThose));
        if (!overhead.empty()) parts.push_back("overhead " + listedWithAnd(overhead));
        if (parts.empty()) {
            if (things.empty()) return fmt::format("Nothing stands in the middle of the room ({}).", room);
            return fmt::format(
                "Nothing stands in the middle of the room ({}): the thing nearest its centre is {}, {:.1f} m from it.",
                room, things.front().label, gap(things.front()));
        }
        return fmt::format("In the middle of the room ({}; within {:.1f} m of its centre, nearest first): {}.", room,
                           reach, listed(parts, "; "));
    }
    std::array<std::vector<std::string>, 4> held;
    for (const auto& thing : things) {
        if (!standing(thing)) continue;
        std::size_t nearest = 0;
        for (std::size_t k = 1; k < 4; ++k)
            if (model::footprintGap(thing.box, corners[k]) < model::footprintGap(thing.box, corners[nearest]))
                nearest = k;
        if (model::footprintGap(thing.box, corners[nearest]) <= kCornerReach) held[nearest].push_back(thing.label);
    }
    std::vector<std::string> each;
    static constexpr std::array<std::string_view, 4> which{"in one", "in another", "in a third", "in the fourth"};
    for (const auto& corner : held)
        if (!corner.empty()) each.push_back(fmt::format("{} {}", listedWithAnd(corner), which[each.size()]));
    if (each.empty())
        return fmt::format("Nothing stands on the floor in the room's corners ({}; within {:.1f} m of a corner).", room,
                           kCornerReach);
    return fmt::format(
        "{} of the room's 4 corners hold things standing on the floor ({}; within {:.1f} m of a "
        "corner): {}.",
        each.size(), room, kCornerReach, listed(each, "; "));
}

// VSI-Bench's route plan: from the start, facing the thing faced, each "go forward" walks to the
// nearest thing of the next kind named, and each turn to fill in is the one toward the thing walked
// to next: back from 135 degrees, else left or right, as the direction questions measure.
std::string route(const Translation& t, const ResultSet& rs) {
    const int id = rs.columnIndex("id"), category = rs.columnIndex("category"), box = rs.columnIndex("box");
    if (t.roles.size() < 3 || id < 0 || category < 0 || box < 0) return "There is no route to fill in.";
    struct Thing {
        std::string label;
        model::Vec3 at;
    };
    auto nearest = [&](const std::vector<std::string>& role, std::optional<model::Vec3> from) -> std::optional<Thing> {
        std::optional<Thing> best;
        double bestD = 0;
        for (const auto& row : rs.rows) {
            const auto* b = std::get_if<model::Box>(&row[box]);
            if (!b || std::find(role.begin(), role.end(), text(row[category])) == role.end()) continue;
            double d = from ? std::hypot(b->center.x - from->x, b->center.y - from->y) : 0;
            if (from && d < 1e-6) d = 1e9;  // the thing stood at is not the one walked to
            if (!best || d < bestD) best = Thing{text(row[category]) + "#" + text(row[id]), b->center}, bestD = d;
        }
        return best;
    };
    auto start = nearest(t.roles[0], std::nullopt);
    if (!start) return fmt::format("There is no {} to begin at.", t.roles[0].front());
    auto facing = nearest(t.roles[1], start->at);
    if (!facing) return fmt::format("There is no {} to face.", t.roles[1].front());
    model::Vec3 at = start->at;
    double hx = facing->at.x - at.x, hy = facing->at.y - at.y;
    std::size_t next = 2;
    std::vector<std::string> turns, why;
    std::string where = start->label;
    for (const auto& step : t.steps) {
        if (next >= t.roles.size()) break;
        auto target = nearest(t.roles[next], at);
        if (!target) return fmt::format("There is no {} on the way.", t.roles[next].front());
        double vx = target->at.x - at.x, vy = target->at.y - at.y;
        if (step == "turn") {
            double angle = std::atan2(hx * vy - hy * vx, hx * vx + hy * vy) / model::kDegree;
            std::string turn = std::abs(angle) >= 135 ? "Turn Back" : angle > 0 ? "Turn Left" : "Turn Right";
            turns.push_back(turn);
            why.push_back(fmt::format("at {}, {} is {:.0f} degrees to the {}", where, target->label, std::abs(angle),
                                      angle > 0 ? "left" : "right"));
            continue;
        }
        if (std::hypot(vx, vy) > 1e-6) hx = vx, hy = vy;
        at = target->at;
        where = target->label;
        ++next;
    }
    if (turns.empty()) return "The route has no turn to fill in.";
    return fmt::format("{} ({}).", listed(turns, ", ", turns.size()), listed(why, "; ", why.size()));
}

// DESCRIBE's summing up of a place (catalog::describePlace's fields): "scene0000_00: a floor of 7.35 x 7.28 m
// (53.5 m²), 4 walls, no door or window found; 29 things: 5 chairs, ..., a bed, a desk and 6 other things".
std::string place(const std::string& name, const std::map<std::string, std::string>& fields) {
    auto field = [&](const char* key) {
        auto it = fields.find(key);
        return it == fields.end() ? std::string() : it->second;
    };
    std::vector<std::string> parts;
    if (const std::string floor = field("floor"); !floor.empty()) {
        const auto comma = floor.find(", ");
        parts.push_back(comma == std::string::npos
                            ? "a floor of " + floor
                            : fmt::format("a floor of {} ({})", floor.substr(0, comma), floor.substr(comma + 2)));
    }
    // "2.69 m, floor to ceiling"
    if (const std::string height = field("height"); !height.empty())
        parts.push_back(height.substr(0, height.find(',')) + " high");
    const std::string walls = field("walls");
    if (!walls.empty()) parts.push_back(walls == "0" ? "no wall found" : walls == "1" ? "1 wall" : walls + " walls");
    const std::string doors = field("doors"), windows = field("windows");
    // "3 doors (door#12, door#13, door#14)"
    auto openings = [](const std::string& what, const std::string& labels) {
        if (labels == "none found") return fmt::format("no {} found", what);
        const auto n = 1 + std::count(labels.begin(), labels.end(), ',');
        return n == 1 ? fmt::format("a {} ({})", what, labels) : fmt::format("{} {}s ({})", n, what, labels);
    };
    if (doors == "none found" && windows == "none found")
        parts.push_back("no door or window found");
    else
        for (const auto& [what, labels] : {std::pair{"door", doors}, std::pair{"window", windows}})
            parts.push_back(openings(what, labels));
    std::string out = name + ": " + listed(parts, ", ", parts.size());
    // "29: chair 5, table 3, bed 1"; the things no model named ("object") come last, as other things.
    const std::string things = field("things");
    const auto colon = things.find(": ");
    if (colon == std::string::npos) return out + "; nothing in it";
    std::vector<std::pair<std::string, std::size_t>> kinds;
    std::size_t unnamed = 0;
    for (std::size_t at = colon + 2; at < things.size();) {
        const std::size_t end = std::min(things.find(", ", at), things.size());
        const std::string entry = things.substr(at, end - at);
        const std::size_t space = entry.rfind(' ');
        const std::string category = entry.substr(0, space);
        const std::size_t count = std::stoul(entry.substr(space + 1));
        if (category == model::kUnnamedCategory)
            unnamed = count;
        else
            kinds.emplace_back(category, count);
        at = end + 2;
    }
    const std::string total = things.substr(0, colon);
    return fmt::format("{}; {} {}: {}", out, total, total == "1" ? "thing" : "things",
                       listedWithAnd(tallied(kinds, unnamed)));
}

// A plugged-in translator's statement: its rows said as they are.
std::string statement(const Translation& t, const ResultSet& rs) {
    // DESCRIBE's rows (id, field, value): each node by what it looks like, its size and any text.
    if (const int id = rs.columnIndex("id"), field = rs.columnIndex("field"), value = rs.columnIndex("value");
        id >= 0 && field >= 0 && value >= 0 && rs.columns.size() == 3) {
        std::vector<std::string> nodes;
        std::string node, category, looks;
        std::map<std::string, std::string> placeFields;  // a scene's own node: what sums it up
        auto flush = [&] {
            if (!placeFields.empty())
                nodes.push_back(place(category, placeFields));
            else if (!node.empty())
                nodes.push_back(fmt::format("{}#{}{}", category, node, looks));
            looks.clear();
            placeFields.clear();
        };
        for (const auto& row : rs.rows) {
            if (text(row[id]) != node) {
                flush();
                node = text(row[id]);
            }
            const std::string f = text(row[field]);
            if (f == "category")
                category = text(row[value]);
            else if (f == "kind" && text(row[value]) == "scene")
                placeFields[f] = "scene";
            else if (!placeFields.empty() && isOneOf(f, {"floor", "height", "walls", "doors", "windows", "things"}))
                placeFields[f] = text(row[value]);
            else if (isOneOf(f, {"dimensions", "color", "material", "shape", "text", "label", "state"}))
                looks += fmt::format("{} {} {}", looks.empty() ? ":" : ",", f, text(row[value]));
        }
        flush();
        if (nodes.empty()) {
            const std::string absent = absentWords(t);
            return absent.empty() ? "Nothing of the kind is here." : noneHere(t, absent);
        }
        return listed(nodes, "; ") + ".";
    }
    if (rs.columnIndex("instruction") >= 0) {
        std::string out;
        for (const auto& row : rs.rows) out += (out.empty() ? "" : " ") + text(row[rs.columnIndex("instruction")]);
        return out.empty() ? rs.message : out;
    }
    if (rs.columns.size() == 1 && rs.columns.front().name == "count" && rs.rows.size() == 1)
        return fmt::format("{}.", text(rs.rows.front().front()));
    if (!rs.message.empty()) return rs.message;
    auto names = labels(rs);
    if (rs.rows.empty()) return "Nothing.";
    if (names.empty()) return fmt::format("{} row{}.", rs.rows.size(), rs.rows.size() == 1 ? "" : "s");
    return fmt::format("{} found: {}", rs.rows.size(), listed(names));
}

// VSI-Bench's appearance order: the categories asked, by the first frame that saw a thing of each.
// A frame number stored as an attribute (text) or a number; none where the node has none.
std::optional<double> frameOf(const Value& v) {
    if (std::optional<double> frame = number(v)) return frame;
    if (const auto* s = std::get_if<std::string>(&v); s && !s->empty()) return std::strtod(s->c_str(), nullptr);
    return std::nullopt;
}

// "what did I see first?": the things first seen in the frame of the first row (the rows in order of first sight, from
// the end for "last").
std::string firstThingSeen(const Translation& t, const ResultSet& rs) {
    const int seen = rs.columnIndex("first_seen");
    const auto names = labels(rs);
    std::vector<std::string> those;
    std::optional<double> frame;
    for (std::size_t r = 0; r < rs.rows.size() && seen >= 0; ++r) {
        const std::optional<double> f = frameOf(rs.rows[r][static_cast<std::size_t>(seen)]);
        if (!f || (frame && *f != *frame)) break;
        frame = f;
        those.push_back(names[r]);
    }
    if (those.empty()) return "Nothing here was dated by a frame.";
    const bool one = those.size() == 1;
    return fmt::format("{} {} the {} {} to come into view, first seen in frame {:.0f}.", listedThings(those),
                       one ? "was" : "were", t.measure, one ? "thing" : "things", *frame);
}

std::string appearance(const Translation& t, const ResultSet& rs) {
    if (t.roles.empty()) return firstThingSeen(t, rs);
    const int category = rs.columnIndex("category"), seen = rs.columnIndex("first_seen");
    // "when did I last see the mug?": the frame that last saw it.
    const int lastSeen = rs.columnIndex("last_seen");
    const bool last = t.measure == "last";
    std::vector<std::pair<double, std::size_t>> firsts;  // frame, choice
    std::vector<std::string> unseen;
    for (std::size_t k = 0; k < t.roles.size() && k < t.choices.size(); ++k) {
        std::optional<double> first;
        for (const auto& row : rs.rows) {
            if (category < 0 || seen < 0) break;
            if (std::find(t.roles[k].begin(), t.roles[k].end(), text(row[category])) == t.roles[k].end()) continue;
            std::optional<double> frame = frameOf(row[lastSeen >= 0 ? lastSeen : seen]);
            if (frame && (!first || (lastSeen >= 0 ? *frame > *first : *frame < *first))) first = frame;
        }
        if (first)
            firsts.emplace_back(*first, k);
        else
            unseen.push_back(t.choices[k]);
    }
    if (firsts.empty()) return "None of them was seen.";
    std::stable_sort(firsts.begin(), firsts.end());
    // "did I see the bed before the sofa?": whether the first asked was seen first.
    if (t.predicate == "before" && t.choices.size() == 2) {
        if (!unseen.empty()) return fmt::format("No: {} was never seen.", listed(unseen, ", ", unseen.size()));
        const auto [firstFrame, first] = firsts.front();
        const auto [secondFrame, second] = firsts.back();
        if (firstFrame == secondFrame)
            return fmt::format("Both at once: {} and {} were first seen in frame {:.0f}.", t.choices[0], t.choices[1],
                               firstFrame);
        return fmt::format("{}: {} was first seen in frame {:.0f}, {} in frame {:.0f}.", first == 0 ? "Yes" : "No",
                           t.choices[first], firstFrame, t.choices[second], secondFrame);
    }
    if (t.choices.size() == 1) {
        return capitalised(fmt::format("{} was {} seen in frame {:.0f}.", t.choices[0], last ? "last" : "first",
                                       firsts.front().first));
    }
    // "which did I see last, the bed or the sofa?": the one that came into view last.
    if (last) {
        std::vector<std::string> before;
        for (auto it = firsts.begin(); it + 1 < firsts.end(); ++it)
            before.push_back(fmt::format("{} in frame {:.0f}", t.choices[it->second], it->first));
        std::string out = fmt::format("{} came into view last, first seen in frame {:.0f}",
                                      t.choices[firsts.back().second], firsts.back().first);
        if (!before.empty()) out += fmt::format(" (before it: {})", listed(before, ", ", before.size()));
        out = capitalised(std::move(out));
        if (!unseen.empty()) out += fmt::format("; never seen: {}", listed(unseen, ", ", unseen.size()));
        return out + ".";
    }
    std::vector<std::string> order, frames;
    for (const auto& [frame, k] : firsts) {
        order.push_back(t.choices[k]);
        frames.push_back(fmt::format("{} in frame {:.0f}", t.choices[k], frame));
    }
    std::string out =
        fmt::format("{} (first seen: {})", listed(order, ", ", order.size()), listed(frames, ", ", frames.size()));
    if (!unseen.empty()) out += fmt::format("; never seen: {}", listed(unseen, ", ", unseen.size()));
    return out + ".";
}

// "what kinds of things are there?": the categories of the rows, most first, and the things the memory could not name
// last ("3 kinds of things: 4 tables, 2 chairs, a sofa and 2 other things").
std::string kinds(const Translation& t, const ResultSet& rs) {
    const auto category = static_cast<std::size_t>(rs.columnIndex("category"));
    std::map<std::string, std::size_t> tally;
    std::size_t unnamed = 0;
    for (const auto& row : rs.rows) {
        const std::string c = text(row[category]);
        if (c == model::kUnnamedCategory)
            ++unnamed;
        else
            ++tally[c];
    }
    const auto byCount = mostFirst(tally);
    // "kinds of furniture", not "of pieces of furniture" (a mass noun's plural).
    const std::string noun = t.subjectPlural.starts_with("pieces of ")
                                 ? t.subjectPlural.substr(std::string("pieces of ").size())
                                 : t.subjectPlural;
    const std::string all = fmt::format("{} {} of {}{}: {}.", byCount.size(), byCount.size() == 1 ? "kind" : "kinds",
                                        noun, withCondition(t), listedWithAnd(tallied(byCount, unnamed)));
    // "what is the most common object?": the kinds with the most of them first, then all.
    if (t.measure != "most" || byCount.empty()) return all;
    std::vector<std::string> most;
    for (const auto& [category, n] : byCount)
        if (n == byCount.front().second) most.push_back(pluralOf(model::categoryWords(category)));
    return fmt::format("{} {} the most common ({} {}): {}", capitalised(listedWithAnd(most)),
                       most.size() == 1 ? "are" : "are, alike,", byCount.front().second,
                       most.size() == 1 ? "of them" : "each", all);
}

std::string changes(const ResultSet& rs) {
    if (rs.rows.empty()) return "Nothing has changed since the scene was first captured.";
    int change = rs.columnIndex("change"), category = rs.columnIndex("category"), id = rs.columnIndex("id");
    std::vector<std::string> parts;
    for (const auto& row : rs.rows)
        parts.push_back(fmt::format("{}#{} {}", text(row[category]), text(row[id]), text(row[change])));
    return fmt::format("{} change{}: {}", rs.rows.size(), rs.rows.size() == 1 ? "" : "s", listed(parts, "; "));
}

}  // namespace

ResultSet answeredRows(const Translation& translation, ResultSet rows) {
    // None of the word asked is stored (widenedSubject): no row answers, and the count is 0.
    if (translation.kind == QuestionKind::Existence && widenedSubject(translation)) rows.rows.clear();
    if (translation.kind == QuestionKind::Count && widenedSubject(translation))
        for (auto& row : rows.rows)
            for (auto& value : row)
                if (std::holds_alternative<std::int64_t>(value)) value = std::int64_t{0};
    if (translation.kind != QuestionKind::Reverse) return rows;
    std::vector<Row> kept;
    for (std::size_t i : reverseRows(translation, rows)) kept.push_back(std::move(rows.rows[i]));
    rows.rows = std::move(kept);
    return rows;
}

std::string answer(const Translation& t, const ResultSet& rs, const std::string& scene) {
    if (t.byKind && !rs.rows.empty() && rs.columnIndex("category") >= 0 &&
        (t.kind == QuestionKind::Locate || t.kind == QuestionKind::Relational || t.kind == QuestionKind::Count))
        return kinds(t, rs);
    switch (t.kind) {
        case QuestionKind::Locate:
            return locate(t, rs, scene);
        case QuestionKind::Relational:
            return relational(t, rs);
        case QuestionKind::Count:
            return count(t, rs);
        case QuestionKind::Existence:
            return existence(t, rs);
        case QuestionKind::YesNo:
            return yesNo(t, rs);
        case QuestionKind::RelativePosition:
            if (!t.choices.empty() && !rs.message.empty()) return eitherSide(t, rs);
            if (!rs.message.empty()) return rs.message;
            if (auto absent = absentWords(t); !absent.empty())
                return fmt::format("There is no {} in scene '{}'.", absent, scene);
            return fmt::format("There is no {} or no {} in scene '{}'.", t.subject, t.object, scene);
        case QuestionKind::Guidance: {
            // The steps, one after another, as a person would be told them.
            std::string out;
            int column = rs.columnIndex("instruction");
            for (const auto& row : rs.rows)
                if (column >= 0)
                    if (const auto* text = std::get_if<std::string>(&row[column]))
                        out += (out.empty() ? "" : " ") + *text;
            // "how far do I have to walk ...?": the way's length first ("3.6 m from sofa#7 to toilet#18 in 3 steps").
            if (t.measure == "length" && !out.empty() && !rs.message.empty()) return rs.message + ": " + out;
            return out.empty() ? rs.message : out;
        }
        case QuestionKind::Distance:
            return distance(t, rs);
        case QuestionKind::Size:
            return size(t, rs);
        case QuestionKind::Superlative:
            return superlative(t, rs);
        case QuestionKind::Direction:
            return direction(t, rs);
        case QuestionKind::Affordance:
            return affordance(t, rs);
        case QuestionKind::Seating:
            return seating(t, rs);
        case QuestionKind::Attribute:
            return t.byKind ? attributeTally(t, rs) : attribute(t, rs);
        case QuestionKind::Changes:
            return changes(rs);
        case QuestionKind::Reverse:
            return reverse(t, rs);
        case QuestionKind::Comparison:
            return comparison(t, rs);
        case QuestionKind::RoomSize:
            return roomSize(t, rs);
        case QuestionKind::RoomKind:
            return roomKind(t, rs);
        case QuestionKind::RoomOf:
            return roomOf(t, rs);
        case QuestionKind::RoomPlace:
            return roomPlace(t, rs);
        case QuestionKind::Statement:
            return statement(t, rs);
        case QuestionKind::Route:
            return route(t, rs);
        case QuestionKind::Appearance:
            return appearance(t, rs);
        case QuestionKind::UnknownWord: {
            std::string out;
            for (const auto& note : t.notes) out += (out.empty() ? "" : "; ") + note;
            return out + ".";
        }
    }
    return {};
}

std::string message(const Translation& t, const std::string& answerText) {
    std::string out = t.runnable ? "SMQL: " + t.smql : "SMQL (not run): " + (t.smql.empty() ? "none" : t.smql);
    std::string words;
    for (const auto& m : t.mappings) {
        std::string to;
        for (const auto& c : m.categories) to += (to.empty() ? "" : ", ") + c;
        words += fmt::format("{}{} -> {} ({})", words.empty() ? "" : "; ", m.word, to.empty() ? "nothing" : to, m.how);
    }
    if (!words.empty()) out += "\nWords: " + words;
    // A note made twice (a phrase read twice, by two forms that tried it) is said once.
    std::set<std::string> said;
    for (const auto& note : t.notes)
        if (t.kind != QuestionKind::UnknownWord && said.insert(note).second) out += "\nNote: " + note;
    return out + "\n" + answerText;
}

std::optional<std::string> absentAnswer(const Translation& t) {
    if (const std::string absent = absentWords(t); !absent.empty()) return noneHere(t, absent);
    return std::nullopt;
}

Error failedTranslation(const Error& error, const std::string& smql, std::optional<SourceLocation> question) {
    return Error(error.kind(), fmt::format("the question's SMQL failed: {} (in: {})", error.message(), smql), question,
                 error.hint());
}

}  // namespace smql::ask

#include "engine/ask/answer.hpp"

#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include "engine/ask/lexicon.hpp"

namespace smql::ask {

namespace {

constexpr std::size_t kNamedInAnswer = 12;  // more rows than this are counted, not named

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
    if (items.size() > named) out += fmt::format("{}and {} more", separator, items.size() - named);
    return out;
}

// When every row has one category, the answer names it ("2 cushions"), else "things".
std::optional<std::string> sharedCategory(const ResultSet& rs) {
    int category = rs.columnIndex("category");
    if (category < 0 || rs.rows.empty()) return std::nullopt;
    std::string first = text(rs.rows.front()[category]);
    for (const auto& row : rs.rows)
        if (text(row[category]) != first) return std::nullopt;
    return first;
}

std::string withCondition(const Translation& t) { return t.condition.empty() ? "" : " " + t.condition; }

// The question's words the scene has none of ("piano"), for answers that found nothing to compare.
std::string absentWords(const Translation& t) {
    std::vector<std::string> words;
    for (const auto& m : t.mappings)
        if (m.categories.empty()) words.push_back(m.word);
    std::string out;
    for (std::size_t i = 0; i < words.size(); ++i) out += (i ? " or " : "") + words[i];
    return out;
}

std::string locate(const Translation& t, const ResultSet& rs, const std::string& scene) {
    if (rs.rows.empty()) return fmt::format("There is no {}{} in scene '{}'.", t.subject, withCondition(t), scene);
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
        places.push_back(parent.empty() ? names[r] : fmt::format("{} is at {} ({})", names[r], parent, p));
    }
    std::string head = rs.rows.size() == 1 ? "" : fmt::format("{} {}: ", rs.rows.size(), t.subjectPlural);
    return head + listed(places, "; ");
}

std::string relational(const Translation& t, const ResultSet& rs) {
    auto shared = sharedCategory(rs);
    std::size_t n = rs.rows.size();
    if (n == 0) {
        if (t.subject == "thing") return fmt::format("Nothing is {}.", t.condition);
        return fmt::format("No {} is {}.", t.subject, t.condition);
    }
    std::string noun = t.subject == "thing" && shared ? *shared : t.subject;
    if (n == 1) return fmt::format("1 {} is {}: {}", noun, t.condition, listed(labels(rs)));
    std::string nouns = t.subject == "thing" && shared ? pluralOf(*shared) : t.subjectPlural;
    return fmt::format("{} {} are {}: {}", n, nouns, t.condition, listed(labels(rs)));
}

std::string count(const Translation& t, const ResultSet& rs) {
    std::int64_t n = 0;
    if (!rs.rows.empty() && !rs.rows.front().empty())
        if (const auto* v = std::get_if<std::int64_t>(&rs.rows.front().front())) n = *v;
    if (t.condition.empty()) return fmt::format("{} {}.", n, n == 1 ? t.subject : t.subjectPlural);
    return fmt::format("{} {} {} {}.", n, n == 1 ? t.subject : t.subjectPlural, n == 1 ? "is" : "are", t.condition);
}

std::string existence(const Translation& t, const ResultSet& rs) {
    std::size_t n = rs.rows.size();
    if (n == 0) return fmt::format("No, there is no {}{}.", t.subject, withCondition(t));
    if (n == 1) return fmt::format("Yes, there is 1 {}{}: {}", t.subject, withCondition(t), listed(labels(rs)));
    return fmt::format("Yes, there are {} {}{}: {}", n, t.subjectPlural, withCondition(t), listed(labels(rs)));
}

std::string yesNo(const Translation& t, const ResultSet& rs) {
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

}  // namespace

std::string answer(const Translation& t, const ResultSet& rs, const std::string& scene) {
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
            return out.empty() ? rs.message : out;
        }
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
    for (const auto& note : t.notes)
        if (t.kind != QuestionKind::UnknownWord) out += "\nNote: " + note;
    return out + "\n" + answerText;
}

Error failedTranslation(const Error& error, const std::string& smql, std::optional<SourceLocation> question) {
    return Error(error.kind(), fmt::format("the question's SMQL failed: {} (in: {})", error.message(), smql), question,
                 error.hint());
}

}  // namespace smql::ask

// RELATE: every relation that holds from each subject node to each object node, as rows and as
// sentences.
#include <algorithm>

#include <fmt/format.h>

#include "engine/exec/executor.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"

namespace smql::exec {

std::string relationSentence(const model::Node& a, const model::Node& b,
                             const std::vector<relations::RelationHit>& hits) {
    const std::string la = catalog::SceneSnapshot::label(a), lb = catalog::SceneSnapshot::label(b);
    const double gap = model::distance(a.box, b.box);
    if (hits.empty()) return fmt::format("no relation holds from {} to {} ({:.1f} m apart)", la, lb, gap);
    std::string sentence;
    for (const auto& hit : hits) {
        std::string words(relations::toString(hit.predicate));
        std::replace(words.begin(), words.end(), '_', ' ');  // "left of", "in front of"
        std::string phrase = fmt::format("{} {}", words, lb);
        if (relations::spec(hit.predicate).takesDistance) phrase += fmt::format(" ({:.1f} m)", gap);
        sentence += sentence.empty() ? la + " is " : "; ";
        sentence += phrase;
    }
    return sentence;
}

ResultSet Executor::run(const binder::BoundRelate& r) {
    relations::Frame viewer = frame(r.view);
    const auto& subjects = slots(r.subject, viewer);
    const auto& objects = slots(r.object, viewer);
    double pairs = static_cast<double>(subjects.size()) * static_cast<double>(objects.size());
    if (pairs > static_cast<double>(session_.limits.maxPairs))
        throw Error(ErrorKind::Limit,
                    fmt::format("RELATE {} TO {} would compare {:.0f} pairs; the limit is {}", r.subject.description,
                                r.object.description, pairs, session_.limits.maxPairs),
                    std::nullopt, "name fewer nodes (an #id, a sub-query with LIMIT), or raise it: SET max_pairs = N");
    ResultSet rs;
    rs.columns = {{"subject", ValueType::Text},
                  {"relation", ValueType::Text},
                  {"object", ValueType::Text},
                  {"score", ValueType::Real},
                  {"distance", ValueType::Real}};
    std::vector<std::string> sentences;
    for (catalog::Slot a : subjects) {
        for (catalog::Slot b : objects) {
            poll();
            if (a == b) continue;
            const model::Node& na = scene().node(a);
            const model::Node& nb = scene().node(b);
            auto hits = relate(na, nb, viewer);
            double gap = model::distance(na.box, nb.box);
            std::string la = catalog::SceneSnapshot::label(na), lb = catalog::SceneSnapshot::label(nb);
            for (const auto& hit : hits)
                rs.rows.push_back({la, std::string(relations::toString(hit.predicate)), lb, hit.score, gap});
            sentences.push_back(relationSentence(na, nb, hits));
        }
    }
    for (std::size_t i = 0; i < sentences.size() && i < 20; ++i) rs.message += (i ? "\n" : "") + sentences[i];
    if (sentences.size() > 20) rs.message += fmt::format("\n... {} more pairs in the rows", sentences.size() - 20);
    return rs;
}

}  // namespace smql::exec

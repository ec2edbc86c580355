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
    return relationSentence(catalog::SceneSnapshot::label(a), catalog::SceneSnapshot::label(b),
                            model::distance(a.box, b.box), hits);
}

std::string relationSentence(std::string_view la, std::string_view lb, double gap,
                             const std::vector<relations::RelationHit>& hits) {
    if (hits.empty()) return fmt::format("no relation holds from {} to {} ({:.1f} m apart)", la, lb, gap);
    std::string sentence(la);
    sentence += " is ";
    for (std::size_t i = 0; i < hits.size(); ++i) {
        if (i > 0) sentence += "; ";
        const std::size_t words = sentence.size();
        sentence += relations::toString(hits[i].predicate);
        std::replace(sentence.begin() + static_cast<std::ptrdiff_t>(words), sentence.end(), '_',
                     ' ');  // "left of", "in front of"
        sentence += ' ';
        sentence += lb;
        if (relations::spec(hits[i].predicate).takesDistance) sentence += fmt::format(" ({:.1f} m)", gap);
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
    // The message words the first pairs; the rows hold them all, so the others' sentences are not made.
    constexpr std::size_t kPairsInWords = 20;
    std::vector<std::string> sentences;
    std::size_t pairsCompared = 0;
    for (catalog::Slot a : subjects) {
        for (catalog::Slot b : objects) {
            poll();
            if (a == b) continue;
            const model::Node& na = scene().node(a);
            const model::Node& nb = scene().node(b);
            auto hits = relate(na, nb, viewer);
            double gap = model::distance(na.box, nb.box);
            std::string la = catalog::SceneSnapshot::label(na), lb = catalog::SceneSnapshot::label(nb);
            if (++pairsCompared <= kPairsInWords) sentences.push_back(relationSentence(la, lb, gap, hits));
            for (const auto& hit : hits)
                rs.rows.push_back({la, std::string(relations::toString(hit.predicate)), lb, hit.score, gap});
        }
    }
    for (std::size_t i = 0; i < sentences.size(); ++i) rs.message += (i ? "\n" : "") + sentences[i];
    if (pairsCompared > kPairsInWords)
        rs.message += fmt::format("\n... {} more pairs in the rows", pairsCompared - kPairsInWords);
    return rs;
}

}  // namespace smql::exec

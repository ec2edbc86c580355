// CHECK: whether one predicate holds over single nodes, as one row (yes or no) and RELATE's sentence
// for the pair as its evidence.
#include <algorithm>

#include <fmt/format.h>

#include "engine/exec/executor.hpp"
#include "model/geometry.hpp"

namespace smql::exec {

ResultSet Executor::run(const binder::BoundCheck& c) {
    relations::Frame viewer = frame(c.view);
    const model::Node& subject = scene().node(slots(c.subject, viewer).front());
    std::vector<const model::Node*> args;
    for (const auto& arg : c.args) args.push_back(&scene().node(slots(arg, viewer).front()));
    const model::Node& object = *args.front();
    const model::Node* third = args.size() > 1 ? args[1] : nullptr;
    const bool same = &subject == &object || (third && (&subject == third || &object == third));
    const double answer = same ? 0.0 : score(c.predicate, subject, object, viewer, third, c.nearDistance);
    const bool holds = answer > 0;

    std::string predicate(relations::toString(c.predicate));
    std::string objects = catalog::SceneSnapshot::label(object);
    if (third) objects += " and " + catalog::SceneSnapshot::label(*third);
    ResultSet rs;
    rs.columns = {{"answer", ValueType::Text}, {"subject", ValueType::Text}, {"relation", ValueType::Text},
                  {"object", ValueType::Text}, {"score", ValueType::Real},   {"distance", ValueType::Real}};
    rs.rows.push_back({std::string(holds ? "yes" : "no"), catalog::SceneSnapshot::label(subject), predicate, objects,
                       answer, model::distance(subject.box, object.box)});
    std::string words = predicate;
    std::replace(words.begin(), words.end(), '_', ' ');
    rs.message = fmt::format("{}: {} is {}{} {}", holds ? "yes" : "no", catalog::SceneSnapshot::label(subject),
                             holds ? "" : "not ", words, objects);
    if (c.nearDistance) rs.message += fmt::format(" (within {} m)", *c.nearDistance);
    if (same) rs.message += " (the same node)";
    // What does hold between the two: the evidence, in RELATE's words.
    rs.message += "\n" + relationSentence(subject, object, relate(subject, object, viewer));
    return rs;
}

}  // namespace smql::exec

// SET name = value: a threshold of the predicates, checked for its unit and range, or a limit of
// the session (a whole number, of at least 1 but for the shape cache's size, which 0 turns off).
#include <cmath>

#include <fmt/format.h>

#include "engine/ask/model_translator.hpp"
#include "engine/binder/binder.hpp"
#include "model/error.hpp"
#include "model/names.hpp"

namespace smql::binder {

namespace {

BoundSet bindLimit(const catalog::LimitSetting& limit, const ast::SetStmt& set) {
    const auto* number = std::get_if<double>(&set.value);
    if (!number || !std::isfinite(*number) || *number < static_cast<double>(limit.least) ||
        *number != std::floor(*number) || *number > 1e15)
        throw Error(ErrorKind::Binding, fmt::format("{} takes a whole number of at least {}", limit.name, limit.least),
                    set.where, fmt::format("SET {} = 5000000", limit.name));
    BoundSet out;
    out.limit = &limit;
    out.value = *number;
    return out;
}

}  // namespace

void Binder::bindStatement(const ast::SetStmt& set, BoundStatement& out) {
    if (set.name == "translator") {
        // ASK's translator: a language model's OpenAI-compatible endpoint, or the built-in reader.
        const auto* url = std::get_if<std::string>(&set.value);
        if (!url)
            throw Error(ErrorKind::Binding, "translator takes a URL in quotes, or 'built-in'", set.where,
                        "SET translator = 'http://127.0.0.1:8080/v1'");
        BoundSet bound;
        bound.setsTranslator = true;
        bound.translatorUrl = *url;
        if (*url != "built-in" && *url != "builtin" && !url->empty()) {
            try {
                bound.translator = ask::modelTranslator(*url);
            } catch (const Error& e) {
                throw Error(e.kind(), e.message(), set.where, e.hint());
            }
        }
        out.body = std::move(bound);
        return;
    }
    if (const auto* limit = catalog::findLimit(set.name)) {
        out.body = bindLimit(*limit, set);
        return;
    }
    const auto* setting = relations::findSetting(set.name);
    if (!setting) {
        std::vector<std::string> names;
        for (const auto& s : relations::settingsCatalogue()) names.push_back(s.name);
        for (const auto& s : catalog::limitSettings()) names.emplace_back(s.name);
        names.emplace_back("translator");
        auto close = model::nearestNames(set.name, names);
        throw Error(
            ErrorKind::Binding, fmt::format("unknown setting '{}'", set.name), set.where,
            close.empty() ? "SHOW SETTINGS lists them" : "did you mean " + model::joinAlternatives(close) + "?");
    }
    const auto* distance = std::get_if<ast::Distance>(&set.value);
    const auto* number = std::get_if<double>(&set.value);
    const double value = relations::settingValue(*setting, distance ? std::optional(distance->metres) : std::nullopt,
                                                 number ? std::optional(*number) : std::nullopt, set.where);
    BoundSet bound;
    bound.threshold = setting;
    bound.value = value;
    out.body = bound;
}

}  // namespace smql::binder

#include "ingest/pipeline/object_finder.hpp"

#include <fmt/format.h>

#include "model/error.hpp"
#include "model/names.hpp"

// Every object source, in the order `auto` tries them: the most specific evidence first. Adding a
// source is its file (an ObjectFinder and a k<Name>Source) and one line here.
#define SMQL_OBJECT_SOURCES(X) \
    X(kMasksSource)            \
    X(kDetectionsSource)       \
    X(kDetectSource)           \
    X(kClusterSource)

namespace smql::ingest {

#define SMQL_DECLARE_SOURCE(source) extern const ObjectSourceSpec source;
SMQL_OBJECT_SOURCES(SMQL_DECLARE_SOURCE)
#undef SMQL_DECLARE_SOURCE

const std::vector<const ObjectSourceSpec*>& objectSources() {
#define SMQL_LIST_SOURCE(source) &source,
    static const std::vector<const ObjectSourceSpec*> sources{SMQL_OBJECT_SOURCES(SMQL_LIST_SOURCE)};
#undef SMQL_LIST_SOURCE
    return sources;
}

std::vector<std::string> objectSourceNames() {
    std::vector<std::string> names;
    for (const auto* source : objectSources()) names.emplace_back(source->name);
    names.emplace_back("auto");
    return names;
}

std::string objectSourcesHelp() {
    std::string out;
    for (const auto* source : objectSources()) out += fmt::format("{} ({}), ", source->name, source->does);
    return out + "or auto (default: the first of these the capture can feed)";
}

std::unique_ptr<ObjectFinder> makeObjectFinder(const Capture& capture, const IngestOptions& options) {
    const bool automatic = options.objects == "auto";
    for (const auto* source : objectSources())
        if (automatic ? source->usable(capture, options) : options.objects == source->name)
            return source->make(capture, options);
    if (automatic)
        throw Error(ErrorKind::Input, "no object source can read this capture", std::nullopt,
                    "--objects names one: " + objectSourcesHelp());
    std::string hint = "--objects takes " + objectSourcesHelp();
    if (auto close = model::nearestNames(options.objects, objectSourceNames(), 1); !close.empty())
        hint = fmt::format("did you mean {}? {}", close.front(), hint);
    throw Error(ErrorKind::Usage, fmt::format("unknown object source '{}'", options.objects), std::nullopt, hint);
}

}  // namespace smql::ingest

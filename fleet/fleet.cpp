#include "fleet/fleet.hpp"

#include <chrono>
#include <set>

#include <fmt/format.h>

#include "fleet/predicates_sql.hpp"
#include "fleet/schema.hpp"
#include "fleet/store.hpp"
#include "model/error.hpp"

namespace smql::fleet {

InitReport init(const std::string& url) {
    Store store(url);
    InitReport report;
    report.before = migrate(store.connection());
    report.after = schemaVersion(store.connection());
    report.predicates = installPredicates(store.connection(), report.predicatesMissing);
    return report;
}

PushReport push(const LocalSource& local, const std::string& url) {
    auto started = std::chrono::steady_clock::now();
    Store store(url);
    requireCurrentSchema(store.connection());
    store.requireWriteAccess();
    PushReport report;
    report.device = local.device;
    const auto held = store.versionsOf(local.device);
    for (const LocalScene& scene : local.scenes) {
        std::uint64_t lacking = 0;
        for (std::uint64_t v = 1; v <= scene.versions; ++v) lacking += !held.contains({scene.name, v});
        report.present += scene.versions - lacking;
        if (lacking == 0) continue;
        // Oldest first: a push cut short leaves a prefix of the history, never a gap before the newest.
        for (const SceneVersionData& version : local.read(scene.name)) {
            if (held.contains({scene.name, version.version})) continue;
            if (store.put(local.device, version)) {
                ++report.sent;
                report.nodes += version.data.nodes.size();
            } else {
                ++report.present;  // another push of this device stored it meanwhile
            }
        }
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return report;
}

PushReport push(storage::Database& database, const std::string& url) { return push(localSource(database), url); }

Pulled fetch(const std::string& url, const PullRequest& request) {
    Store store(url);
    requireCurrentSchema(store.connection());
    std::vector<StoredVersion> versions = store.versionsNamed(request.scene, request.device);
    if (versions.empty())
        throw Error(ErrorKind::Binding,
                    request.device.empty() ? fmt::format("the fleet store has no scene named '{}'", request.scene)
                                           : fmt::format("the fleet store has no scene named '{}' of a device {}...",
                                                         request.scene, request.device),
                    std::nullopt, "smql URL -c 'SHOW SCENES' lists them");
    std::set<std::string> devices;
    for (const auto& v : versions) devices.insert(v.device);
    if (devices.size() > 1)
        throw Error(ErrorKind::Binding,
                    fmt::format("{} devices hold a scene named '{}': {}", devices.size(), request.scene,
                                fmt::join(devices, ", ")),
                    std::nullopt, "say whose with --device ID (the start of the id is enough)");
    const StoredVersion* chosen = &versions.back();
    if (request.version != 0) {
        chosen = nullptr;
        for (const auto& v : versions)
            if (v.version == request.version) chosen = &v;
        if (!chosen)
            throw Error(ErrorKind::Binding, fmt::format("the fleet store holds versions 1 to {} of scene '{}', not {}",
                                                        versions.back().version, request.scene, request.version));
    }
    return {chosen->device, store.get(*chosen)};
}

Pulled pull(const std::string& url, const PullRequest& request, storage::Database& database) {
    Pulled pulled = fetch(url, request);
    storePulled(database, pulled.version);
    return pulled;
}

}  // namespace smql::fleet

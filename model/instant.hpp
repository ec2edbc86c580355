// Points in time as the memory writes them: ISO 8601 in UTC, "2026-11-21T10:00:00Z". Capture
// times, first/last-seen times and the times of AS OF and SINCE are compared in this form, so
// text order is time order.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace smql::model {

// "2026-11-21", "2026-11-21 10:00", "2026-11-21T10:00:00.5Z", "2026-11-21T12:00:00+02:00" ->
// "2026-11-21T10:00:00Z" (a date alone is its first second; no zone is UTC; fractions of a
// second are dropped). nullopt for anything else, or a date that does not exist.
std::optional<std::string> utcInstant(std::string_view text);

// Now, in that form: the capture time of a capture that does not say when it was taken.
std::string utcNow();

// The instant, or the text itself when it is not one (an importer's own time format), so that
// comparing two of them is at worst a comparison of the texts.
std::string comparableInstant(std::string_view text);

}  // namespace smql::model

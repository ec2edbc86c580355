#include "model/instant.hpp"

#include <cstdio>
#include <ctime>

#include <fmt/format.h>

namespace smql::model {

namespace {

// Seconds since the epoch as the memory writes them.
std::string written(std::time_t seconds) {
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}Z", utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday,
                       utc.tm_hour, utc.tm_min, utc.tm_sec);
}

bool digits(std::string_view text, std::size_t at, std::size_t count) {
    if (at + count > text.size()) return false;
    for (std::size_t i = at; i < at + count; ++i)
        if (text[i] < '0' || text[i] > '9') return false;
    return true;
}

int number(std::string_view text, std::size_t at, std::size_t count) {
    int value = 0;
    for (std::size_t i = at; i < at + count; ++i) value = value * 10 + (text[i] - '0');
    return value;
}

}  // namespace

std::optional<std::string> utcInstant(std::string_view text) {
    // YYYY-MM-DD
    if (!digits(text, 0, 4) || text.size() < 10 || text[4] != '-' || !digits(text, 5, 2) || text[7] != '-' ||
        !digits(text, 8, 2))
        return std::nullopt;
    std::tm t{};
    t.tm_year = number(text, 0, 4) - 1900;
    t.tm_mon = number(text, 5, 2) - 1;
    t.tm_mday = number(text, 8, 2);
    std::size_t at = 10;
    long offsetSeconds = 0;
    if (at < text.size()) {
        // [T ]HH:MM[:SS[.fff]]
        if ((text[at] != 'T' && text[at] != 't' && text[at] != ' ') || !digits(text, at + 1, 2) ||
            at + 3 >= text.size() || text[at + 3] != ':' || !digits(text, at + 4, 2))
            return std::nullopt;
        t.tm_hour = number(text, at + 1, 2);
        t.tm_min = number(text, at + 4, 2);
        at += 6;
        if (at < text.size() && text[at] == ':') {
            if (!digits(text, at + 1, 2)) return std::nullopt;
            t.tm_sec = number(text, at + 1, 2);
            at += 3;
            if (at < text.size() && text[at] == '.') {
                ++at;
                if (!digits(text, at, 1)) return std::nullopt;
                while (digits(text, at, 1)) ++at;
            }
        }
        // Z | +HH:MM | -HH:MM | nothing
        if (at < text.size() && (text[at] == 'Z' || text[at] == 'z')) {
            ++at;
        } else if (at < text.size() && (text[at] == '+' || text[at] == '-')) {
            if (!digits(text, at + 1, 2) || at + 3 >= text.size() || text[at + 3] != ':' || !digits(text, at + 4, 2))
                return std::nullopt;
            long sign = text[at] == '+' ? 1 : -1;
            offsetSeconds = sign * (number(text, at + 1, 2) * 3600L + number(text, at + 4, 2) * 60L);
            at += 6;
        }
        if (at != text.size()) return std::nullopt;
    }
    if (t.tm_mon > 11 || t.tm_mday < 1 || t.tm_hour > 23 || t.tm_min > 59 || t.tm_sec > 60) return std::nullopt;
    const std::tm asWritten = t;
    std::time_t seconds = timegm(&t);
    // timegm normalises 2026-02-30 to March 2nd: a date that changed does not exist.
    if (t.tm_mday != asWritten.tm_mday || t.tm_mon != asWritten.tm_mon) return std::nullopt;
    return written(seconds - offsetSeconds);
}

std::string utcNow() { return written(std::time(nullptr)); }

std::string comparableInstant(std::string_view text) {
    if (auto instant = utcInstant(text)) return *instant;
    return std::string(text);
}

}  // namespace smql::model

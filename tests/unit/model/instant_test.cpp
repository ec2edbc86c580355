#include <catch2/catch.hpp>

#include "model/instant.hpp"

using smql::model::comparableInstant;
using smql::model::utcInstant;

TEST_CASE("times in the forms people write become one UTC form", "[model][instant]") {
    CHECK(utcInstant("2026-11-21") == "2026-11-21T00:00:00Z");
    CHECK(utcInstant("2026-11-21 10:05") == "2026-11-21T10:05:00Z");
    CHECK(utcInstant("2026-11-21T10:05:07Z") == "2026-11-21T10:05:07Z");
    CHECK(utcInstant("2026-11-21t10:05:07.250z") == "2026-11-21T10:05:07Z");
    CHECK(utcInstant("2026-11-21T01:00:00+02:00") == "2026-11-20T23:00:00Z");
    CHECK(utcInstant("2026-12-31T23:30:00-01:00") == "2027-01-01T00:30:00Z");
}

TEST_CASE("what is not a time, or not a day that exists, is refused", "[model][instant]") {
    for (const char* text : {"", "yesterday", "2026-11", "2026-13-01", "2026-02-30", "2026-11-21T25:00",
                             "2026-11-21T10", "2026-11-21T10:00:00+2", "2026-11-21 10:00 UTC", "20261121"})
        CHECK_FALSE(utcInstant(text));
    CHECK(comparableInstant("frame 12") == "frame 12");
    CHECK(comparableInstant("2026-11-21") == "2026-11-21T00:00:00Z");
}

TEST_CASE("now is written as every instant is", "[model][instant]") {
    const std::string now = smql::model::utcNow();
    CHECK(smql::model::utcInstant(now) == now);
    CHECK(now > "2026-01-01T00:00:00Z");
}

// Every import costs what its bounds allow (docs/formats.md, "Bounds"): a file read stops at
// kMaxFileBytes (a device such as /dev/zero included), an object of more than kMaxObjectMembers
// members is refused, and both are errors that say so.
#include <catch2/catch.hpp>

#include <string>

#include "import_support.hpp"
#include "ingest/import/common.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/json_field.hpp"

using smql::import::readReplica;
using smql::import::readSpatialLm;
using smql::import::test::requireInputError;
using smql::import::test::TempDir;

TEST_CASE("an import reads at most kMaxFileBytes, and a device is no exception", "[import][bounds]") {
    requireInputError([] { readReplica("/dev/zero", "z"); }, {"/dev/zero", "more than 256 MiB"});
    requireInputError([] { readSpatialLm("/dev/zero", "z"); }, {"/dev/zero", "more than 256 MiB"});
}

TEST_CASE("a JSON object of more than kMaxObjectMembers members is refused, one at the bound is read",
          "[import][bounds]") {
    TempDir dir;
    auto fileWith = [&](std::size_t members) {
        std::string text =
            R"({"objects": [{"id": 1, "class_name": "chair", "oriented_bbox": {"abb": {"center": [0, 0, 0],
            "sizes": [1, 1, 1]}, "orientation": {"rotation": [0, 0, 0, 1], "translation": [0, 0, 0.5]}}}], "extra": {)";
        for (std::size_t i = 0; i < members; ++i) text += (i ? ", \"k" : "\"k") + std::to_string(i) + "\": 0";
        return dir.write("keys" + std::to_string(members) + ".json", text + "}}");
    };
    CHECK(readReplica(fileWith(smql::import::detail::kMaxObjectMembers), "ok").nodes.size() == 1);
    const std::string over = fileWith(smql::import::detail::kMaxObjectMembers + 1);
    requireInputError([&] { readReplica(over, "no"); }, {over, "extra.k10000", "more than 10000 members"});
}

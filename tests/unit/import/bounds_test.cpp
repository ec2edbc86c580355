// Every import costs what its bounds allow (docs/formats.md, "Bounds"): a file read stops at
// kMaxFileBytes (a device such as /dev/zero included), an object of more than kMaxObjectMembers
// members is refused, and both are errors that say so.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <sys/stat.h>

#include "import_support.hpp"
#include "ingest/import/common.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/json_field.hpp"

using smql::import::readReplica;
using smql::import::readSpatialLm;
using smql::import::test::requireInputError;
using smql::import::test::TempDir;

TEST_CASE("an import reads at most kMaxFileBytes, and a device is no file", "[import][bounds]") {
    requireInputError([] { readReplica("/dev/zero", "z"); }, {"/dev/zero", "it is a device, not a file"});
    requireInputError([] { readSpatialLm("/dev/null", "z"); }, {"/dev/null", "it is a device, not a file"});
    // A sparse file one byte over the bound: refused from its size, so no byte of it is read
    // (reading it would take 256 MiB of memory first).
    TempDir dir;
    const std::string huge = dir.write("huge.json", "");
    std::filesystem::resize_file(huge, smql::import::detail::kMaxFileBytes + 1);
    requireInputError([&] { readReplica(huge, "z"); }, {huge, "more than 256 MiB"});
    // A pipe has no size: it is read, and stopped at the bound.
    const std::string fifo = dir.path("layout.fifo");
    REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
    std::thread writer([&] {
        std::ofstream out(fifo, std::ios::binary);
        out << "wall_0=Wall(0,0,0,4,0,0,2.5,0)\n";
    });
    CHECK(readSpatialLm(fifo, "piped").nodes.size() == 1);
    writer.join();
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

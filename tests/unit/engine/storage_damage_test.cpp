// A query over a damaged record fails with the damaged scene named; it never
// answers from the damaged bytes.
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

#include "engine_support.hpp"
#include "ingest/import/importers.hpp"
#include "storage/codec.hpp"
#include "storage/database.hpp"

using namespace smql;
using namespace smql::testing;

TEST_CASE("a query over a record with a flipped byte reports the corrupt record and its scene") {
    TempDir dir;
    const std::string path = dir.path.string();
    model::Node victim;
    std::vector<Row> objectCount;
    {
        auto engine = Engine::open(path);
        engine->importScene(import::readReplica(replicaRoom0(), "room0"));
        objectCount = run(*engine, "COUNT object").rows;
        auto rows = run(*engine, "FIND sofa").rows;
        REQUIRE_FALSE(rows.empty());
        auto txn = engine->database().beginRead();
        victim = *txn.node(static_cast<model::NodeId>(std::get<std::int64_t>(rows[0][0])));
    }
    std::string record;
    storage::codec::encodeNode(victim, record);

    // Flip a bit of the sofa's box (the centre's x, after the header and source id) in data.mdb.
    const auto data = dir.path / "data.mdb";
    std::string file;
    {
        std::ifstream in(data, std::ios::binary);
        file.assign(std::istreambuf_iterator<char>(in), {});
    }
    const auto at = file.find(record);
    REQUIRE(at != std::string::npos);
    const std::size_t offset = 24 + (victim.sourceId ? 8 : 0) + 6;
    {
        std::fstream out(data, std::ios::binary | std::ios::in | std::ios::out);
        out.seekp(static_cast<std::streamoff>(at + offset));
        out.put(static_cast<char>(record[offset] ^ 0x10));
    }

    auto engine = Engine::open(path);
    // A statement reads the records of the nodes it visits: the sofa's, or every object's.
    for (const char* query : {"FIND sofa", "FIND cushion WHERE on(sofa)", "FIND object"}) {
        INFO(query);
        try {
            run(*engine, query);
            FAIL("the query answered from a damaged record");
        } catch (const Error& e) {
            REQUIRE(e.kind() == ErrorKind::Storage);
            REQUIRE_THAT(e.message(), Catch::StartsWith("corrupt record in scene 'room0'"));
            REQUIRE_THAT(e.message(), Catch::Contains("node record for id " + std::to_string(victim.id)));
            REQUIRE_THAT(e.hint(), Catch::Contains("backup"));
        }
    }
    // One that reads no record answers: the count of objects comes from the scene's index.
    REQUIRE(run(*engine, "COUNT object").rows == objectCount);
}

// The fleet tests need a PostgreSQL server with PostGIS: one private cluster for the run, started
// here in a temporary folder and removed at the end. Where PostgreSQL or PostGIS is not installed
// the run prints why and exits with 77, which ctest reports as skipped (never silently passed).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <iostream>
#include <memory>

#include "fleet_support.hpp"

namespace {
std::unique_ptr<smql::fleet::pg::LocalCluster> theCluster;
}

namespace smql::testing {
fleet::pg::LocalCluster& cluster() { return *theCluster; }
}  // namespace smql::testing

int main(int argc, char** argv) {
    std::string whyNot;
    // No fsync: the tests kill clients, not the server, and run on a shared machine.
    std::string settings = "-c fsync=off -c max_connections=200";
#ifdef SMQL_PG_MODULE_DIR
    // The predicates' module from the build folder (extensions name their own library folder in full).
    settings += " -c dynamic_library_path=" SMQL_PG_MODULE_DIR;
#endif
    theCluster = smql::fleet::pg::LocalCluster::start({.settings = settings, .prefix = "smql-fleet-test"}, whyNot);
    if (!theCluster) {
        std::cout << "fleet tests skipped: " << whyNot << "\n";
        return 77;
    }
    std::cout << "fleet tests on " << theCluster->version() << " in " << theCluster->directory().string() << "\n";
    int status = Catch::Session().run(argc, argv);
    theCluster.reset();
    return status;
}

// Command-line parsing shared by `smql` and `smql-ingest`.
#pragma once

#include <optional>

#include <CLI/CLI.hpp>

namespace smql::shell {

// Parses argv into `app`. Returns the exit status when the command should not run: 0 after --help
// or --version, 1 after a usage error (CLI11 prints the message; its own exit codes, 100 and up,
// would break the documented 0-or-1 contract). std::nullopt when the command should run.
inline std::optional<int> parseArguments(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
        return std::nullopt;
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 1;
    }
}

}  // namespace smql::shell

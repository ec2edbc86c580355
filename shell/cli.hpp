// Command-line parsing shared by `smql` and `smql-ingest`.
#pragma once

#include <exception>
#include <iostream>
#include <optional>

#include <CLI/CLI.hpp>

#include "model/error.hpp"
#include "shell/output_file.hpp"

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

// Runs a program's body; an error that escapes it is printed (with its hint) and is exit status 1,
// and so is standard output that could not be written (a full disk, /dev/full), unless the body
// failed already (and said why: a write error is then said once).
template <typename Body>
int runReportingErrors(Body&& body) {
    try {
        const int status = body();
        if (status == 0) checkWritten(std::cout, "standard output");
        return status;
    } catch (const Error& e) {
        std::cerr << e.render() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "smql: " << e.what() << "\n";
        return 1;
    }
}

}  // namespace smql::shell

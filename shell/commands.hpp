// The sub-commands of `smql` besides the shell itself.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace smql::shell {

// `smql import replica|spatiallm|json FILE --db DIR [--scene NAME]`
int importCommand(const std::string& format, const std::string& file, const std::string& dbDir,
                  const std::string& sceneName);
// `smql export json --db DIR [--scene NAME] [-o FILE]`
int exportCommand(const std::string& format, const std::string& dbDir, const std::string& sceneName,
                  const std::string& outFile);
// `smql demo [--db DIR]`: a generated room, its tree, example queries with answers and timings.
int demoCommand(const std::string& dbDir);
// `smql test FILE...`: runs declarative query suites (*.smqlt); see docs/testing.md.
int testCommand(const std::vector<std::string>& files);
// `smql check DB`: verifies a database (records, checksums, trees, indexes, lock file);
// prints each problem, exit status 1 when there is one (docs/storage.md, "Checking a database").
int checkCommand(const std::string& dbDir);
// `smql synth --out DIR [--seed N] [--frames K] [--objects N] [--force]`: a synthetic RGB-D capture
// of a generated room with ground truth (docs/ingest.md, "Synthetic captures").
int synthCommand(const std::string& outDir, std::uint64_t seed, int frames, int objects, bool force);

}  // namespace smql::shell

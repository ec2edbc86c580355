// The sub-commands of `smql` besides the shell itself.
#pragma once

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

}  // namespace smql::shell

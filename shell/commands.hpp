// The sub-commands of `smql` besides the shell itself that need no capture libraries.
#pragma once

#include <string>
#include <vector>

namespace smql::shell {

// `smql import FORMAT FILE --db DIR [--scene NAME | --update SCENE | --all]`: --all imports every
// scene of a file that holds several, all read and checked before the first is stored.
int importCommand(const std::string& format, const std::string& file, const std::string& dbDir,
                  const std::string& sceneName, const std::string& update, bool all);
// `smql export FORMAT --db DIR [--scene NAME] [-o FILE] [--points]`
int exportCommand(const std::string& format, const std::string& dbDir, const std::string& sceneName,
                  const std::string& outFile, bool points = false);
// `smql export evidence '#id' DIR --db DB`: writes a node's evidence crops into DIR.
int exportEvidenceCommand(const std::string& dbDir, const std::string& node, const std::string& outDir);
// `smql test FILE...`: runs declarative query suites (*.smqlt); see docs/testing.md.
int testCommand(const std::vector<std::string>& files);
// `smql check DB [--salvage OUT]`: verifies a database (records, checksums, trees, indexes, lock
// file); prints each problem, exit status 1 when there is one (docs/storage.md, "Checking a
// database"). With OUT, every scene that verifies is copied into the new database OUT.
int checkCommand(const std::string& dbDir, const std::string& salvageInto);

}  // namespace smql::shell

#!/usr/bin/env bash
# The project's own C and C++ sources, one path per line relative to the repository root: what
# `make format` rewrites and `make lint` checks (build trees and generated code are not ours).
set -euo pipefail
cd "$(dirname "$0")/.."
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  git ls-files --cached --others --exclude-standard -- '*.cpp' '*.hpp' '*.c' '*.h'
else
  find model relations engine storage ingest fleet shell drivers bench fuzz tests -type f \
    \( -name '*.cpp' -o -name '*.hpp' -o -name '*.c' -o -name '*.h' \) | sort
fi

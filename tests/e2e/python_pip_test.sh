#!/usr/bin/env bash
# `pip install ./python` into fresh virtual environments, offline, then README's one-liner run by the
# environment's own python from outside the repository (docs/python.md, "Installing").
#   python_pip_test.sh SMQL BUILD_DIR SHARED_DATA
set -uo pipefail
smql=$(realpath "$1") build=$(realpath "$2") data=$(realpath "$3")
repo=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if ! /usr/bin/python3 -m venv "$work/probe" >/dev/null 2>&1; then
  echo "python_pip test skipped: python3 -m venv does not work here (scripts/setup.sh installs python3-venv)"
  exit 77
fi
failed=0
check() {  # check NAME COMMAND...
  local name=$1
  shift
  if "$@" >"$work/out" 2>&1; then echo "ok   $name"; else echo "FAIL $name"; sed 's/^/  /' "$work/out" | tail -20; failed=1; fi
}

"$smql" import replica "$data/replica-room0/info_semantic.json" --db "$work/r0" >/dev/null || exit 1
/usr/bin/python3 -m venv --system-site-packages "$work/env" || exit 1
/usr/bin/python3 -m venv "$work/bare" || exit 1
cd "$work" || exit 1
unset PYTHONPATH
check "pip builds a wheel offline (no index, nothing to fetch)" \
  env SMQL_BUILD="$build" "$work/env/bin/pip" wheel --no-index --no-deps -w "$work/dist" "$repo/python"
check "pip installs it into an environment that sees Debian's numpy" \
  bash -c "'$work/env/bin/pip' install --no-index '$work'/dist/smql-*.whl"
check "README's one-liner there: the cushions on the sofa as a numpy array" bash -c "
  '$work/env/bin/python' -c \"import smql; db = smql.connect('$work/r0'); cur = db.execute('FIND ? WHERE on(?)', ('cushion', 'sofa')); print(cur.boxes())\" >'$work/boxes' &&
  '$work/env/bin/python' -c \"import smql; assert smql.__file__.startswith('$work/env/'), smql.__file__\" &&
  test \$(grep -c '^ *\[' '$work/boxes') -ge 3"
check "pip installs it into a bare environment: statements run, boxes ask for numpy by name" bash -c "
  '$work/bare/bin/pip' install --no-index '$work'/dist/smql-*.whl >/dev/null &&
  '$work/bare/bin/python' -c \"import smql; db = smql.connect('$work/r0'); assert db.execute('COUNT sofa').fetchone() == (2,)\" &&
  ! '$work/bare/bin/python' -c \"import smql; smql.connect('$work/r0').execute('FIND sofa').boxes()\" 2>'$work/e' &&
  grep -q 'boxes needs numpy' '$work/e'"
exit $failed

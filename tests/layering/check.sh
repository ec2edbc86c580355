#!/bin/sh
# Builds each layering target: TARGET:HEADER must fail because HEADER is not found; TARGET: (no
# header) must build. Usage: check.sh BUILD_DIR TARGET[:HEADER]...
build=$1
shift
failed=0
for spec in "$@"; do
  target=${spec%%:*}
  header=${spec#*:}
  output=$(cmake --build "$build" --target "$target" 2>&1)
  status=$?
  if [ -z "$header" ]; then
    if [ $status -ne 0 ]; then
      echo "FAIL $target: its own layer's header does not build"
      echo "$output" | tail -5
      failed=1
    fi
  elif [ $status -eq 0 ]; then
    echo "FAIL $target: $header, a layer above, is visible"
    failed=1
  elif ! echo "$output" | grep -q "$header: No such file"; then
    echo "FAIL $target: the build failed for another reason than $header not being found"
    echo "$output" | tail -5
    failed=1
  else
    echo "ok   $target: $header is out of reach"
  fi
done
exit $failed

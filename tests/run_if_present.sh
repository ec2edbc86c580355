#!/bin/sh
# Runs a test program where the data it reads is there, else exits with ctest's skip code (77), saying
# what is missing. Usage: run_if_present.sh FILE PROGRAM [ARGS...]
file=$1
shift
if [ ! -f "$file" ]; then
    echo "skipped: $file is not there"
    exit 77
fi
exec "$@"

#!/usr/bin/env bash
# The services the test suite needs, installed from Debian's packages when missing and started:
# a PostgreSQL server on 127.0.0.1 (.ci/postgres.sh) and chromium for the browser tests.
# Prints the line to eval: export TILEKIT_TEST_POSTGRES=URL (README's test command does so).
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v chromium >/dev/null 2>&1; then
  apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >&2
fi
url=$(bash .ci/postgres.sh)
echo "export TILEKIT_TEST_POSTGRES='$url'"

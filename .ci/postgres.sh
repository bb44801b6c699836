#!/usr/bin/env bash
# Install PostgreSQL from Debian's packages (if missing), start a server on 127.0.0.1:5432 and
# create the role the tests use; prints the server URL for TILEKIT_TEST_POSTGRES.
set -euo pipefail
if ! command -v pg_ctlcluster >/dev/null 2>&1 || [ -z "$(ls /usr/lib/postgresql 2>/dev/null)" ]; then
  apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq postgresql >&2
fi
version=$(ls /usr/lib/postgresql | sort -n | tail -1)
if ! pg_lsclusters -h | awk -v v="$version" '$1 == v && $2 == "main"' | grep -q .; then
  pg_createcluster "$version" main >&2
fi
pg_ctlcluster "$version" main start >&2 2>/dev/null || true
for _ in $(seq 1 50); do
  if su postgres -c "pg_isready -q -h 127.0.0.1 -p 5432"; then break; fi
  sleep 0.2
done
su postgres -c "psql -q -p 5432 -d postgres -tc \"SELECT 1 FROM pg_roles WHERE rolname = 'tilekit'\"" \
  | grep -q 1 \
  || su postgres -c "psql -q -p 5432 -d postgres -c \"CREATE ROLE tilekit LOGIN SUPERUSER PASSWORD 'tilekit'\"" >&2
echo "postgresql+psycopg://tilekit:tilekit@127.0.0.1:5432/postgres"

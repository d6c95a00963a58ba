#!/usr/bin/env bash
# A throwaway PostgreSQL server for the store tests: `pg_server.sh start STATE`
# runs initdb and pg_ctl in a new directory under /tmp (Unix socket only, no
# TCP, trust authentication, fsync off: a test server, never a lab's; with a
# third argument `durable`, fsync stays on, as the benchmarks need) and
# writes STATE/status: "uri postgresql:///dtlab_test?host=DIR&user=dtlab", or
# "unavailable WHY" where the server binaries are missing (the tests then skip
# their PostgreSQL half, saying so). `pg_server.sh stop STATE` stops it and
# removes its directory. initdb and postgres refuse to run as root, so as root
# they run as the `postgres` system user (or `nobody`). Safe to run twice.
set -euo pipefail

action=${1:?usage: pg_server.sh start|stop STATE_DIR [durable]}
state=${2:?usage: pg_server.sh start|stop STATE_DIR [durable]}
durability="-c fsync=off -c full_page_writes=off"
[ "${3:-}" = durable ] && durability=""
mkdir -p "$state"
status="$state/status"

find_bin() {
  local d
  for d in $(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -t/ -k5 -V -r); do
    [ -x "$d/initdb" ] && [ -x "$d/pg_ctl" ] && { echo "$d"; return; }
  done
  if command -v initdb >/dev/null && command -v pg_ctl >/dev/null; then dirname "$(command -v initdb)"; fi
}

as_user() {  # runs "$@" as the server's user
  if [ "$(id -u)" -eq 0 ]; then runuser -u "$owner" -- "$@"; else "$@"; fi
}

if [ "$action" = stop ]; then
  if [ -f "$state/dir" ]; then
    dir=$(cat "$state/dir")
    owner=$(stat -c %U "$dir" 2>/dev/null || echo root)
    bin=$(cat "$state/bin" 2>/dev/null || find_bin)
    [ -n "$bin" ] && [ -d "$dir/data" ] && as_user "$bin/pg_ctl" -D "$dir/data" -m immediate -w stop >/dev/null 2>&1 || true
    rm -rf "$dir"
  fi
  rm -f "$state/dir" "$state/bin" "$status"
  exit 0
fi

[ "$action" = start ] || { echo "pg_server.sh: unknown action $action" >&2; exit 2; }
if [ -f "$state/dir" ] && [ -f "$status" ]; then  # already running (a repeated fixture setup)
  dir=$(cat "$state/dir")
  owner=$(stat -c %U "$dir" 2>/dev/null || echo root)
  bin=$(cat "$state/bin")
  if as_user "$bin/pg_ctl" -D "$dir/data" status >/dev/null 2>&1; then exit 0; fi
  "$0" stop "$state"
fi

bin=$(find_bin)
if [ -z "$bin" ]; then
  echo "unavailable PostgreSQL server binaries (initdb, pg_ctl) not found; scripts/setup installs Debian's postgresql" >"$status"
  echo "pg_server.sh: $(cut -d' ' -f2- "$status")" >&2
  exit 0
fi
owner=$(id -un)
if [ "$(id -u)" -eq 0 ]; then
  owner=postgres
  id postgres >/dev/null 2>&1 || owner=nobody
fi
dir=$(mktemp -d /tmp/dtlab-pg.XXXXXX)
chown "$owner" "$dir"
echo "$dir" >"$state/dir"
echo "$bin" >"$state/bin"
as_user "$bin/initdb" -D "$dir/data" -U dtlab --auth=trust -E UTF8 --no-locale --no-sync >"$dir/initdb.log" 2>&1 ||
  { cat "$dir/initdb.log" >&2; exit 1; }
as_user "$bin/pg_ctl" -D "$dir/data" -l "$dir/server.log" -w -t 60 \
  -o "-c listen_addresses='' -c unix_socket_directories=$dir $durability -c max_connections=200" \
  start >/dev/null || { cat "$dir/server.log" >&2; exit 1; }
as_user "$bin/psql" -q -h "$dir" -U dtlab -d postgres -c "CREATE DATABASE dtlab_test" >/dev/null
echo "uri postgresql:///dtlab_test?host=$dir&user=dtlab" >"$status"
echo "pg_server.sh: PostgreSQL $("$bin/pg_ctl" --version | awk '{print $3}') on $dir" >&2

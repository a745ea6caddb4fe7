#!/usr/bin/env bash
# A throwaway PostgreSQL cluster for the tests of the model database on a server.
#
#   pg_cluster.sh start STATE_FILE   initdb in a new directory under /tmp, a server on 127.0.0.1 at a free
#                                    port (its unix socket in that directory), trust authentication for
#                                    the user "feedplan"; writes PG_DIR=… and PG_URL=postgresql://… to
#                                    STATE_FILE
#   pg_cluster.sh stop STATE_FILE    stops that server and removes the directory and STATE_FILE
#
# initdb and the server refuse to run as root: as root they run as the "postgres" system user (made by
# Debian's postgresql package), in a directory that user owns.
set -euo pipefail

action=${1:?usage: pg_cluster.sh start|stop STATE_FILE}
state=${2:?usage: pg_cluster.sh start|stop STATE_FILE}

bindir=$(pg_config --bindir 2>/dev/null || true)
if [[ ! -x "$bindir/initdb" ]]; then
  for candidate in /usr/lib/postgresql/*/bin; do
    [[ -x "$candidate/initdb" ]] && bindir=$candidate
  done
fi
if [[ ! -x "$bindir/initdb" ]]; then
  echo "pg_cluster: no PostgreSQL server binaries (initdb) found: install the postgresql package" >&2
  exit 1
fi

as_owner=()
if [[ $(id -u) -eq 0 ]]; then as_owner=(runuser -u postgres --); fi

stop() {
  [[ -f "$state" ]] || return 0
  local dir
  dir=$(sed -n 's/^PG_DIR=//p' "$state")
  if [[ -n "$dir" && -d "$dir/data" ]]; then
    "${as_owner[@]}" "$bindir/pg_ctl" -D "$dir/data" -m immediate -w stop >/dev/null 2>&1 || true
  fi
  [[ -n "$dir" && "$dir" == /tmp/feedplan-pg-* ]] && rm -rf "$dir"
  rm -f "$state"
}

port_in_use() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }

start() {
  stop  # a cluster left by an interrupted run
  local dir
  dir=$(mktemp -d /tmp/feedplan-pg-XXXXXX)
  chmod 755 "$dir"
  [[ $(id -u) -eq 0 ]] && chown postgres: "$dir"
  echo "PG_DIR=$dir" >"$state"
  "${as_owner[@]}" "$bindir/initdb" -D "$dir/data" -A trust -U feedplan -E UTF8 --locale=C --no-sync >"$dir/initdb.log" 2>&1 ||
    { cat "$dir/initdb.log" >&2; exit 1; }
  for attempt in 1 2 3 4 5 6 7 8; do
    local port=$((20000 + (RANDOM * 32768 + RANDOM) % 40000))
    port_in_use "$port" && continue
    if "${as_owner[@]}" "$bindir/pg_ctl" -D "$dir/data" -l "$dir/server.log" -w -t 30 \
        -o "-p $port -k $dir -c listen_addresses=127.0.0.1 -c fsync=off -c full_page_writes=off -c max_connections=50" \
        start >/dev/null; then
      echo "PG_URL=postgresql://feedplan@127.0.0.1:$port/postgres" >>"$state"
      echo "pg_cluster: server at 127.0.0.1:$port, data in $dir/data"
      return 0
    fi
    echo "pg_cluster: start on port $port failed (attempt $attempt)" >&2
  done
  tail -20 "$dir/server.log" >&2 || true
  exit 1
}

case "$action" in
  start) start ;;
  stop) stop ;;
  *) echo "pg_cluster: unknown action '$action' (start or stop)" >&2; exit 2 ;;
esac

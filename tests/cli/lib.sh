# The one library of the CLI test scripts (tests/cli, tests/analysis): usage `script.sh PIERCE ...`;
# each script reads its further arguments itself (a samples directory, a model builder).
set -u
PIERCE=${1:?usage: $0 PIERCE_BINARY ...}
PY=/usr/bin/python3
WORK=$(mktemp -d "${TMPDIR:-/tmp}/pierce_cli.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
FAILURES=0

fail() {
  echo "FAIL: $*" >&2
  FAILURES=$((FAILURES + 1))
}

# expect_error DESCRIPTION EXPECTED_TEXT -- COMMAND...: non-zero exit and EXPECTED_TEXT on stderr.
expect_error() {
  local what=$1 text=$2
  shift 3
  local rc=0
  "$@" >"$WORK/stdout" 2>"$WORK/stderr" || rc=$?
  if [ "$rc" -eq 0 ]; then
    fail "$what: exit code 0, expected an error"
  elif ! grep -qF -- "$text" "$WORK/stderr"; then
    fail "$what: stderr lacks '$text': $(cat "$WORK/stderr")"
  fi
}

# run DESCRIPTION COMMAND...: must exit 0.
run() {
  local what=$1
  shift
  "$@" >"$WORK/stdout" 2>"$WORK/stderr" || fail "$what: exit code $?: $(cat "$WORK/stderr")"
}

# box_obj NAME X0 Y0 Z0 X1 Y1 Z1 BASE: an OBJ object, closed, outward winding; BASE = vertices
# already written to the file.
box_obj() {
  local name=$1 x0=$2 y0=$3 z0=$4 x1=$5 y1=$6 z1=$7 b=$8
  echo "o $name"
  for i in 0 1 2 3 4 5 6 7; do
    local x=$x0 y=$y0 z=$z0
    [ $((i & 1)) -ne 0 ] && x=$x1
    [ $((i & 2)) -ne 0 ] && y=$y1
    [ $((i & 4)) -ne 0 ] && z=$z1
    echo "v $x $y $z"
  done
  # -x, +x, -y, +y, -z, +z (two triangles each), as pierce::gen::box.
  for t in "0 4 6" "0 6 2" "1 3 7" "1 7 5" "0 1 5" "0 5 4" "2 6 7" "2 7 3" "0 2 3" "0 3 1" "4 5 7" "4 7 6"; do
    set -- $t
    echo "f $((b + $1 + 1)) $((b + $2 + 1)) $((b + $3 + 1))"
  done
}

# png_size FILE: "WIDTH HEIGHT" from the IHDR chunk, or nothing if the PNG signature is wrong.
png_size() {
  [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || return 0
  od -An -tu1 -j16 -N8 "$1" | awk '{ print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4, $5 * 16777216 + $6 * 65536 + $7 * 256 + $8 }'
}

# expect_clean_interrupt PID STARTED_TEXT OUTPUT: waits until STARTED_TEXT shows on
# $WORK/stderr (the run's progress bar: the work has started), sends Ctrl-C (SIGINT) to PID, and
# checks that pierce says "cancelled", exits 130 and leaves neither OUTPUT nor a temporary file.
expect_clean_interrupt() {
  local pid=$1 started=$2 output=$3
  for _ in $(seq 1 600); do
    grep -q "$started" "$WORK/stderr" 2>/dev/null && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.05
  done
  kill -INT "$pid" 2>/dev/null || fail "pierce finished before it could be interrupted"
  local rc=0
  wait "$pid" || rc=$?
  [ "$rc" -eq 130 ] || fail "exit code $rc, expected 130"
  grep -q cancelled "$WORK/stderr" || fail "no 'cancelled' message: $(cat "$WORK/stderr")"
  [ ! -e "$output" ] || fail "a partial output file was left"
  [ "$(find "$WORK" -name '*pierce-tmp*' | wc -l)" -eq 0 ] || fail "temporary file left behind"
}

finish() {
  if [ "$FAILURES" -ne 0 ]; then
    echo "$FAILURES check(s) failed" >&2
    exit 1
  fi
  echo "all checks passed"
}

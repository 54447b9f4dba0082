# Shared by the CLI test scripts: usage `script.sh PIERCE SAMPLES_DIR`.
set -u
PIERCE=${1:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
SAMPLES=${2:?usage: $0 PIERCE_BINARY SAMPLES_DIR}
WORK=$(mktemp -d "${TMPDIR:-/tmp}/pierce_cli.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
FAILURES=0

fail() {
  echo "FAIL: $*" >&2
  FAILURES=$((FAILURES + 1))
}

# expect_error DESCRIPTION EXPECTED_TEXT -- COMMAND...: the command must exit non-zero and print
# EXPECTED_TEXT on stderr.
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

finish() {
  if [ "$FAILURES" -ne 0 ]; then
    echo "$FAILURES check(s) failed" >&2
    exit 1
  fi
  echo "all checks passed"
}

#!/usr/bin/env bash
# packaging/install-freecad-addon.sh: installs, refuses to replace a different install without
# --force (non-interactive), replaces it with --force, links with --link. Args: MODULE_DIR WORK_DIR.
set -uo pipefail
module_dir=$1 work=$2
script="$(cd "$(dirname "$0")/../.." && pwd)/packaging/install-freecad-addon.sh"
rm -rf "$work" && mkdir -p "$work"
dest="$work/Mod/Pierce"
fail=0
check() { if eval "$2"; then echo "[ok  ] $1"; else echo "[FAIL] $1"; fail=1; fi; }

bash "$script" --dest "$dest" --module-dir "$module_dir" </dev/null >/dev/null 2>&1
check "fresh install succeeds" "[ -f '$dest/InitGui.py' ] && [ -f '$dest/package.xml' ]"
check "path file names the module" "grep -qx '$module_dir' '$dest/pierce_path.txt'"

bash "$script" --dest "$dest" --module-dir "$module_dir" </dev/null >/dev/null 2>&1
rc=$?
check "reinstalling the same add-on needs no --force (rc $rc)" "[ $rc -eq 0 ]"

echo "# user edit" >> "$dest/Init.py"
bash "$script" --dest "$dest" --module-dir "$module_dir" </dev/null >"$work/out.txt" 2>&1
rc=$?
check "a different install is not replaced without asking (rc $rc)" "[ $rc -ne 0 ] && grep -q '# user edit' '$dest/Init.py'"
check "the refusal says how to proceed" "grep -q -- '--force' '$work/out.txt'"

bash "$script" --force --dest "$dest" --module-dir "$module_dir" </dev/null >/dev/null 2>&1
check "--force replaces it" "! grep -q '# user edit' '$dest/Init.py'"

bash "$script" --link --force --dest "$dest" </dev/null >/dev/null 2>&1
check "--link makes a symbolic link to the checkout" "[ -L '$dest' ] && [ -f '$dest/pierce_fc/locate.py' ]"

bash "$script" --dest "$dest" --module-dir "$work/nowhere" </dev/null >"$work/out.txt" 2>&1
rc=$?
check "a missing module directory is an error (rc $rc)" "[ $rc -ne 0 ] && grep -q 'build Pierce first' '$work/out.txt'"
check "...and leaves the existing install alone" "[ -L '$dest' ]"
exit $fail

# What every command-line test shares. A test script sources it first, with its own arguments:
#   source "$(dirname "$0")/harness.sh" "$@"    (arguments: PATH_TO_PENUMBRA SOURCE_DIR)
# It sets $penumbra, $source_dir and $scratch (a directory removed at exit), and counts the
# outcomes of pass, fail and check; the script ends with finish.
set -uo pipefail

penumbra=$1
source_dir=$2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

passed=0
failed=0

pass() {
  echo "ok   $1"
  passed=$((passed + 1))
}

# fail NAME [DETAILS]: the details (an output, a log) are printed indented under the name.
fail() {
  echo "FAIL $1"
  if [[ $# -gt 1 && -n $2 ]]; then
    sed 's/^/     | /' <<<"$2"
  fi
  failed=$((failed + 1))
}

# check NAME COMMAND...: passes when the command succeeds.
check() {
  local name=$1
  shift
  if "$@"; then
    pass "$name"
  else
    fail "$name"
  fi
}

# The counts, and the script's exit status.
finish() {
  echo "$passed passed, $failed failed"
  [[ $failed -eq 0 ]]
}

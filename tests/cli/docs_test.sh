#!/usr/bin/env bash
# The user documentation (README.md, docs/*.md, bench/README.md) stands on the repository alone:
# every relative link resolves to a file inside it, and no page points at files beside it (the
# project's own spec and assets, which users do not have). Usage: docs_test.sh PENUMBRA SOURCE_DIR
source "$(dirname "$0")/harness.sh" "$@"

repository=$(realpath "$source_dir")
pages=("$repository/README.md" "$repository"/docs/*.md "$repository/bench/README.md")

broken=$(/usr/bin/python3 - "$repository" "${pages[@]}" <<'PYTHON'
import os, re, sys
repository = sys.argv[1]
for page in sys.argv[2:]:
    text = open(page, encoding="utf-8").read()
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        path = os.path.realpath(os.path.join(os.path.dirname(page), target.split("#")[0]))
        if not path.startswith(repository + os.sep) or not os.path.exists(path):
            print(f"{os.path.relpath(page, repository)}: {target}")
PYTHON
)
if [[ -z $broken ]]; then
  pass "every relative link resolves inside the repository"
else
  fail "every relative link resolves inside the repository" "$broken"
fi

# The spec and the shared assets are named only where bench/README.md says how to get the dragon.
outside=$(grep -n -E "/work/|shared/spec|shared/assets" "$repository/README.md" "$repository"/docs/*.md)
if [[ -z $outside ]]; then
  pass "no page names files outside the repository"
else
  fail "no page names files outside the repository" "$outside"
fi

finish

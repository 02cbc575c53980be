#!/usr/bin/env bash
# Every study of tools/studies into a temporary directory (ctest label study: long, not in the default suite
# nor in CI; the committed figures come from `tools/study --all`). Fails if a study cannot run or a case of
# it gives bad input. Usage: run_studies.sh LOOM
set -euo pipefail
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
tools/study tools/studies/*.toml --loom "$1" --out "$out" --no-pictures

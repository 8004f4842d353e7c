#!/usr/bin/env bash
# Every C++ file of the project is formatted as .clang-format says; prints the offending lines.
set -euo pipefail
cd "$1"
mapfile -t files < <(find common server client proto tests -name '*.cpp' -o -name '*.hpp' | sort)
[ ${#files[@]} -gt 0 ] || { echo "no C++ files found under $1"; exit 1; }
clang-format --dry-run -Werror "${files[@]}"
echo "${#files[@]} files formatted as .clang-format says"

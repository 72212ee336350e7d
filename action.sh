#!/usr/bin/env bash
# The GitHub Action's check (action.yml): `action.sh FORMAT [OUTPUT]` runs
# `urdftool check ARGS --no-env --format FORMAT [--output OUTPUT] -- PATHS...`.
#
# The inputs come through the environment (PATHS, ARGS), never pasted into a script. Each is
# split into words at white space by `read` (no glob, no quotes, no other shell syntax); a
# path word holding a wildcard is then matched against file names, each match staying one
# word whatever it holds (spaces, a leading '-'). Every path comes after `--`, so a file a
# pull request names `--output=report.urdf` is a file to check, never an option.
set -euo pipefail
format=$1
output=${2:-}
read -r -d '' -a args <<< "${ARGS:-}" || true
read -r -d '' -a words <<< "${PATHS:-.}" || true
paths=()
for word in "${words[@]}"; do
    if [[ $word == *[\*\?\[]* ]]; then
        matches=()
        IFS= ; shopt -s nullglob
        # shellcheck disable=SC2206  # the wildcard is matched on purpose; IFS= splits nothing
        matches=( $word )
        shopt -u nullglob; unset IFS
        if (( ${#matches[@]} )); then paths+=("${matches[@]}"); else paths+=("$word"); fi
    else
        paths+=("$word")
    fi
done
options=(--no-env --format "$format")
if [[ -n $output ]]; then options+=(--output "$output"); fi
exec urdftool check "${args[@]}" "${options[@]}" -- "${paths[@]}"

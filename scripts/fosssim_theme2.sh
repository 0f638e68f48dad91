#!/usr/bin/env bash
# Runs every FOSSSim Theme-2 scene (../shared/scenes/fosssim/t2m1..t2m3) and VortexExample with
# massspring-simulate, each with its own integrator, dt and duration, and prints a Markdown table:
# scene, collision response, steps done of steps asked (ceil(duration / dt)), wall seconds of the
# whole process (best of REPEAT runs; the default DivergenceGuard energy check on), and the exit
# status (0: finished with a finite state, 2: diverged).
#   scripts/fosssim_theme2.sh [build/tools/massspring-simulate] [REPEAT]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
sim="${1:-$here/build/tools/massspring-simulate}"
repeat="${2:-1}"
scenes="${MASSSPRING_SHARED_DIR:-$here/../shared}/scenes/fosssim"
echo "| scene | collision | steps | wall [s] | exit |"
echo "|---|---|---|---|---|"
for f in $(cd "$scenes" && ls t2m1/*/*.xml t2m2/*/*.xml t2m3/*/*.xml t1m3/VortexExample.xml); do
  type=$(grep -o '<collision type="[^"]*"' "$scenes/$f" | sed 's/.*="//; s/"//' || true)
  best=""
  status=0
  for ((k = 0; k < repeat; ++k)); do
    start=$(date +%s.%N)
    out=$("$sim" "$scenes/$f" 2>&1) || status=$?
    end=$(date +%s.%N)
    t=$(echo "$end - $start" | bc)
    if [[ -z "$best" ]] || (($(echo "$t < $best" | bc))); then best=$t; fi
  done
  # "<n> steps, ..." counts the steps done; the first line "<scene>: ..., <N> steps (<T> s)" the
  # steps asked for
  steps=$(echo "$out" | sed -n 's/^\([0-9]*\) steps, .*/\1/p')
  asked=$(echo "$out" | head -1 | sed -n 's/.*, \([0-9]*\) steps (.*/\1/p')
  steps="$steps of $asked"
  printf '| %s | %s | %s | %.3f | %s |\n' "$f" "${type:--}" "${steps:-?}" "$best" "$status"
done

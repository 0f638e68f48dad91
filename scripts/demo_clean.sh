#!/usr/bin/env bash
# Removes what an earlier scripts/demo.sh wrote in its output folder, and nothing else: the files
# it names (trajectory.csv, drape.html, drape.png, drape.gif, the .tmp a killed run may leave of
# the first two) and the frame files frames/frame_NNNNN.obj (and .obj.tmp); the folder frames/
# only when that leaves it empty. Says what it removes (nothing when there is nothing to remove);
# any other file stays where it is.
# Usage: scripts/demo_clean.sh FOLDER
set -euo pipefail
if [ $# -ne 1 ]; then
  echo "usage: scripts/demo_clean.sh FOLDER" >&2
  exit 1
fi
out=$1
[ -d "$out" ] || exit 0
files=()
for name in trajectory.csv trajectory.csv.tmp drape.html drape.html.tmp drape.png drape.gif; do
  if [ -f "$out/$name" ] || [ -L "$out/$name" ]; then files+=("$name"); fi
done
frames=()
if [ -d "$out/frames" ]; then
  while IFS= read -r -d '' frame; do frames+=("$frame"); done < <(
    find "$out/frames" -maxdepth 1 \( -type f -o -type l \) -regextype posix-extended \
      -regex '.*/frame_[0-9]{5,}\.obj(\.tmp)?' -print0 | sort -z)
fi
[ ${#files[@]} -gt 0 ] || [ ${#frames[@]} -gt 0 ] || exit 0
what=${files[*]:-}
if [ ${#frames[@]} -gt 0 ]; then
  plural=s
  [ ${#frames[@]} -gt 1 ] || plural=
  what="${what:+$what, }${#frames[@]} frame file$plural frames/frame_NNNNN.obj"
fi
echo "demo: removing the previous demo's outputs in $out: $what (other files stay)"
for name in "${files[@]}"; do rm -f -- "$out/$name"; done
for frame in "${frames[@]}"; do rm -f -- "$frame"; done
rmdir -- "$out/frames" 2>/dev/null || true

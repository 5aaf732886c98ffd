#!/usr/bin/env bash
# Gathers real textured glTF 2.0 assets into a folder, for `vs-khronos.sh FOLDER`: every
# textured asset under ../shared/real-world/gltf2 (with its resources) and each textured glTF
# 1.0 sample model there upgraded to a GLB (real geometry and images, in 2.0).
#   scripts/bench/textured-corpus.sh OUT_FOLDER
source "$(dirname "$0")/common.sh"
out=${1:?usage: textured-corpus.sh OUT_FOLDER}
mkdir -p "$out"
n=0
while IFS= read -r -d '' asset; do
  grep -aq '"images"' "$asset" || continue
  dest="$out/$(echo "${asset#../shared/real-world/gltf2/}" | tr '/' '_')"
  mkdir -p "$dest.d" && cp "$asset" "$dest.d/"
  # Its resources: the other files beside it that are not assets themselves.
  find "$(dirname "$asset")" -maxdepth 1 -type f ! -name '*.gltf' ! -name '*.glb' ! -name '*.json' -exec cp {} "$dest.d/" \;
  n=$((n + 1))
done < <(find ../shared/real-world/gltf2 -type f \( -name '*.gltf' -o -name '*.glb' \) -print0 | sort -z)
while IFS= read -r -d '' asset; do
  grep -aq '"images"' "$asset" || continue
  ./target/release/gltfmat upgrade "$asset" -o "$out/$(basename "$(dirname "$(dirname "$asset")")")-$n.glb" >/dev/null 2>&1 && n=$((n + 1))
done < <(find ../shared/real-world/gltf1/sample-models -path '*glTF/*.gltf' -print0 | sort -z)
echo "$n textured assets in $out"

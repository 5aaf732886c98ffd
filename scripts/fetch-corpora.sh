#!/usr/bin/env bash
# Fetches the external test corpora at pinned upstream commits into the layout the corpus
# tests read (`../shared` beside the checkout by default, or the folder named here; point
# GLTFMAT_SHARED at it when it is elsewhere):
#
#   DEST/conformance/khronos-glTF-Validator   the Khronos validator's test cases and reports
#   DEST/conformance/gltf-1.0-assets          glTF 1.0 boxes (gltf-pipeline's specs)
#   DEST/real-world/gltf2                     Blender exporter and Microsoft glTF SDK files,
#                                             each with the released validator's report
#   DEST/real-world/gltf1                     COLLADA2GLTF sample models, the PBR-draft hammer
#
#   scripts/fetch-corpora.sh [DEST]
#
# A corpus whose folder already exists is left alone. Needs git, and node + npm for the
# real-world reports (made with the npm Khronos validator 2.0.0-dev.3.10, the release the
# Khronos-profile tests compare with). GLTFMAT_CORPUS_GIT replaces https://github.com
# (a mirror holding OWNER/NAME repositories).
set -euo pipefail
checkout="$(cd "$(dirname "$0")/.." && pwd)"
dest="$(mkdir -p "${1:-$checkout/../shared}" && cd "${1:-$checkout/../shared}" && pwd)"
git_base="${GLTFMAT_CORPUS_GIT:-https://github.com}"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# `fetch OWNER/NAME COMMIT`: the repository's tree at COMMIT, in $scratch/NAME.
fetch() {
  local repo=$1 commit=$2 dir="$scratch/${1#*/}"
  [ -d "$dir" ] && return
  git init -q "$dir"
  git -C "$dir" fetch -q --depth 1 "$git_base/$repo" "$commit"
  git -C "$dir" -c advice.detachedHead=false checkout -q FETCH_HEAD
}

# `find … -print0 | copy_to FOLDER`: the listed files, with their relative paths, into FOLDER.
copy_to() {
  tar --null -T - -cf - | tar -xf - -C "$1"
}

# `place FOLDER`: true when DEST/FOLDER is still to be made (and says so).
place() {
  if [ -e "$dest/$1" ]; then
    echo "kept $dest/$1 (already there)"
    return 1
  fi
  echo "fetching $dest/$1"
  mkdir -p "$dest/$1"
}

if place conformance/khronos-glTF-Validator; then
  fetch KhronosGroup/glTF-Validator cc804e39e2a9403c61836a4fcb279765e80f7e4c
  src="$scratch/glTF-Validator"
  cp "$src/ISSUES.md" "$src/LICENSE" "$src/docs/validation.schema.json" "$dest/conformance/khronos-glTF-Validator/"
  # The cases and their expected reports; the Dart test drivers are not needed.
  (cd "$src" && find test -type f ! -name '*.dart' -print0 | copy_to "$dest/conformance/khronos-glTF-Validator")
fi

if place conformance/gltf-1.0-assets; then
  fetch CesiumGS/gltf-pipeline 46fa8dc4650e3a3e6cd8bc5d18e87ff4a5a265a8
  src="$scratch/gltf-pipeline"
  cp "$src/LICENSE.md" "$dest/conformance/gltf-1.0-assets/"
  (cd "$src/specs/data/1.0" && find . -type f ! -name '*.glsl' -print0 | copy_to "$dest/conformance/gltf-1.0-assets")
fi

if place real-world/gltf2; then
  fetch KhronosGroup/glTF-Blender-IO 7551a35b146ab62ebc503ec661f88a74dc611392
  fetch microsoft/glTF-SDK 004a5cecf3768fa944240592ca8dd39f3b0ca862
  # The exported assets, without the .blend sources and the exporter's option files.
  (cd "$scratch/glTF-Blender-IO/tests/roundtrip" &&
    find . -type f \( -iname '*.gltf' -o -iname '*.glb' -o -iname '*.bin' -o -iname '*.png' -o -iname '*.jpg' -o -iname '*.jpeg' -o -iname '*.webp' -o -iname '*.ktx2' \) -print0 |
    copy_to "$dest/real-world/gltf2/blender-io")
  (cd "$scratch/glTF-SDK/GLTFSDK.Test/Resources" && find . -type f -print0 | copy_to "$dest/real-world/gltf2/gltf-sdk")
  (cd "$dest/real-world/gltf2" && find . -type f \( -iname '*.gltf' -o -iname '*.glb' \) | sed 's|^\./||' | LC_ALL=C sort >list.txt)
  npm install --prefix "$scratch/npm" --no-save --silent gltf-validator@2.0.0-dev.3.10 >/dev/null
  (cd "$dest/real-world/gltf2" && NODE_PATH="$scratch/npm/node_modules" node - <list.txt <<'JS'
// Writes X.report.json beside each listed file X: every issue, resources from X's folder.
const v = require('gltf-validator'); const fs = require('fs'); const path = require('path');
(async () => {
  for (const f of fs.readFileSync(0, 'utf8').split('\n').filter(Boolean)) {
    const dir = path.dirname(f);
    const read = (u) => new Promise((ok, no) =>
      fs.readFile(path.join(dir, decodeURIComponent(u)), (e, d) => (e ? no(e) : ok(new Uint8Array(d)))));
    const report = await v.validateBytes(new Uint8Array(fs.readFileSync(f)),
      { uri: path.basename(f), maxIssues: 0, externalResourceFunction: read });
    delete report.validatedAt;
    fs.writeFileSync(`${f}.report.json`, JSON.stringify(report, null, 4));
  }
})();
JS
  )
fi

if place real-world/gltf1; then
  fetch KhronosGroup/glTF de6f79617c61ade232bf0302b3da247fafeb0419
  src="$scratch/glTF"
  # The COLLADA2GLTF variants of these models (not the COLLADA sources or screenshots).
  for model in 2CylinderEngine Box BoxAnimated BoxSemantics BoxTextured BoxWithoutIndices CesiumMan \
    CesiumMilkTruck Duck Monster ReciprocatingSaw RiggedFigure RiggedSimple VC; do
    (cd "$src/sampleModels" && find "$model" -path "$model/glTF*" -type f \
      ! -path 'ReciprocatingSaw/glTF-Embedded/*' ! -path 'VC/glTF-Embedded/*' -print0 |
      copy_to "$dest/real-world/gltf1/sample-models")
  done
  mkdir -p "$dest/real-world/gltf1/fraunhofer-hammer"
  for file in hammer.gltf buffer_0.bin diffuse.jpeg specular.jpg gloss.jpg; do
    cp "$src/extensions/Vendor/FRAUNHOFER_materials_pbr/example/simple-pbr/assets/hammer/$file" "$dest/real-world/gltf1/fraunhofer-hammer/"
  done
fi
echo "done: run the tests with GLTFMAT_SHARED=$dest if it is not ../shared beside the checkout"

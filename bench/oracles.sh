# Sourced by the bench scripts: installs the npm oracles (never dependencies of the crate)
# into bench/node_modules, all at once, since `npm install --no-save` removes packages it was
# not asked for.
oracles_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [ ! -d "$oracles_dir/node_modules/gltf-validator" ] || [ ! -d "$oracles_dir/node_modules/gltf-pipeline" ]; then
  npm install --prefix "$oracles_dir" --no-save --silent gltf-validator gltf-pipeline >/dev/null
fi

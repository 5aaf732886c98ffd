# Sourced by the bench scripts: a fresh release build, a scratch folder `$work` (removed at
# exit unless KEEP=1), and the npm oracles (never dependencies of the crate) installed into
# bench/node_modules all at once, since `npm install --no-save` removes what it was not asked.
set -euo pipefail
bench_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$bench_dir/.."
cargo build --release -q
if [ ! -d "$bench_dir/node_modules/gltf-validator" ] || [ ! -d "$bench_dir/node_modules/gltf-pipeline" ]; then
  npm install --prefix "$bench_dir" --no-save --silent gltf-validator gltf-pipeline >/dev/null
fi
work=$(mktemp -d)
if [ -n "${KEEP:-}" ]; then echo "work: $work"; else trap 'rm -rf "$work"' EXIT; fi

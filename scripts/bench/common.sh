# Sourced by the bench scripts: a fresh release build, a scratch folder `$work` (removed at
# exit unless KEEP=1), and the npm oracles (never dependencies of the crate) installed into
# scripts/bench/node_modules all at once, since `npm install --no-save` removes what it was not asked.
set -euo pipefail
bench_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$bench_dir/../.."
cargo build --release -q
if [ ! -d "$bench_dir/node_modules/gltf-validator" ] || [ ! -d "$bench_dir/node_modules/gltf-pipeline" ]; then
  npm install --prefix "$bench_dir" --no-save --silent gltf-validator gltf-pipeline >/dev/null
fi
work=$(mktemp -d)
if [ -n "${KEEP:-}" ]; then echo "work: $work"; else trap 'rm -rf "$work"' EXIT; fi

# `best_of 3 cmd…`: runs a command N times (output discarded) and prints the fastest run's
# wall time in seconds, that run's peak memory in KB and its CPU time (user + system, all
# threads and child processes) in seconds. Best-of-N keeps page-cache writeback and other
# machine noise out of the ratios, for both tools alike. `RUN` in an argument becomes the
# run's number, so that each run writes a new file (replacing a large file makes ext4 flush
# it, which would time the disk rather than the tool); files named `$work/out-…` are removed
# after each run.
best_of() {
  local runs=$1 best_s="" best_kb="" best_cpu="" t0 t1 s kb cpu
  shift
  for run in $(seq "$runs"); do
    sync # earlier runs' writeback must not be timed in this one
    t0=$(date +%s.%N)
    /usr/bin/time -f '%M %U %S' -o "$work/.mem" "${@//RUN/$run}" >/dev/null 2>&1 || true
    t1=$(date +%s.%N)
    rm -f "$work"/out-* # outputs of timed runs are named out-…: none accumulates
    s=$(echo "$t1 - $t0" | bc -l)
    read -r kb user system < <(tail -1 "$work/.mem")
    cpu=$(echo "$user + $system" | bc -l)
    if [ -z "$best_s" ] || [ "$(echo "$s < $best_s" | bc -l)" = 1 ]; then best_s=$s; best_kb=$kb; best_cpu=$cpu; fi
  done
  echo "$best_s $best_kb $best_cpu"
}

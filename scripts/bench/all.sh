#!/usr/bin/env bash
# The speed ratios against the npm oracles, each peer run in the same invocation:
# corpus vs the Khronos validator (target ≥ 5x), the large GLB vs the Khronos validator
# (≥ 10x, ≤ 1/3 of its peak memory), upgrade vs gltf-pipeline (≥ 10x), and the 2.0 spec-gloss
# conversion vs glTF-Transform's metalRough() (ΔE of both outputs and time).
set -euo pipefail
cd "$(dirname "$0")"
./vs-khronos.sh | tail -1
./large-glb.sh | tail -1
./vs-pipeline.sh | tail -1
./vs-gltf-transform.sh

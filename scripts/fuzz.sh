#!/usr/bin/env bash
# Builds the libFuzzer targets with clang and runs each over its corpus in
# tests/fuzz/corpus/<target> (kept in the repository; new inputs go to a fresh
# folder under build-fuzz/, so the run never edits the tree).
#   bash scripts/fuzz.sh [runs per target, default 600000] [seed, default 1]
# A fixed seed, run count and starting corpus make a run repeatable: CI
# replays exactly what passed here. That also needs the corpus never reloaded
# by the clock (-reload=0), the same addresses (libFuzzer feeds compared
# values, pointers too, back into its mutations: setarch -R turns address
# randomization off where the kernel lets it; elsewhere runs may differ), and
# TBB on one thread (tests/fuzz/one_thread.h). A different seed explores further.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-600000}
seed=${2:-1}
command -v clang++-14 >/dev/null || { echo "fuzz: needs clang-14 and libclang-rt-14-dev" >&2; exit 1; }
cmake -S tests/fuzz -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz
same_addresses=(setarch "$(uname -m)" -R)
"${same_addresses[@]}" true 2>/dev/null || { same_addresses=(); echo "fuzz: address randomization stays on (setarch -R refused): runs may differ"; }
for target in fuzz_octree_file fuzz_off_reader fuzz_off_binary_reader fuzz_obj_reader fuzz_ply_reader fuzz_stl_reader fuzz_gltf_reader fuzz_vdb_reader; do
  rm -rf "build-fuzz/corpus/$target" && mkdir -p "build-fuzz/corpus/$target"
  # The .vdb target runs about 1,000 inputs a second (OpenVDB parses each), the
  # others 20,000 to 40,000: it gets a sixth of the runs to keep CI's time.
  # The glTF target runs about 1,500 (tinygltf parses JSON): a quarter.
  n=$runs
  [ "$target" = fuzz_vdb_reader ] && n=$(( runs / 6 > 0 ? runs / 6 : 1 ))
  [ "$target" = fuzz_gltf_reader ] && n=$(( runs / 4 > 0 ? runs / 4 : 1 ))
  echo "fuzz: $target, $n runs, seed $seed"
  log="build-fuzz/$target.log"
  if ! "${same_addresses[@]}" "build-fuzz/$target" -seed="$seed" -runs="$n" -reload=0 -max_total_time=600 -max_len=8192 -timeout=10 -print_final_stats=1 \
      -artifact_prefix=build-fuzz/ "build-fuzz/corpus/$target" "tests/fuzz/corpus/$target" >"$log" 2>&1; then
    tail -40 "$log"
    echo "fuzz: $target failed; the input is in build-fuzz/" >&2
    exit 1
  fi
  grep -E "stat::number_of_executed_units|stat::new_units_added" "$log" || true
done

#!/usr/bin/env bash
# scripts/fuzz.sh [SECONDS_PER_TARGET]: builds the libFuzzer targets of the loaders and the scene
# parser (fuzz/, in build-asan/ with ASan and UBSan), writes their seed corpora (fuzz/make_corpus.py:
# tiny files made from the formats' descriptions, and the shipped scenes) and runs each of the five
# targets for SECONDS_PER_TARGET (default 60; CI passes 12, a minute in all).
# A crash, a hang (an input taking over 10 s), an allocation over 256 MiB or a result breaking its
# contract fails the run; the input is kept as build-asan/fuzz-runs/TARGET/crash-*
# (timeout-*, oom-*), to become a test in tests/ with the fix. New inputs found along the way
# stay in build-asan/fuzz-runs/TARGET/corpus, so later runs start from them.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${WISP_ASAN_BUILD_DIR:-$root/build-asan}"
seconds="${1:-60}"
targets=(fuzz_tfx2 fuzz_tfx fuzz_cyhair fuzz_obj fuzz_scene)
"$root/scripts/build_asan.sh" "${targets[@]}"
work="$build/fuzz-runs"
rm -rf "$work/seeds"
python3 "$root/fuzz/make_corpus.py" "$work/seeds"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
failed=()
for t in "${targets[@]}"; do
  mkdir -p "$work/$t/corpus"
  dict=()
  [ -f "$work/seeds/$t.dict" ] && dict=("-dict=$work/seeds/$t.dict")
  echo "fuzz: $t for ${seconds}s"
  if "$build/fuzz/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=1024 -malloc_limit_mb=256 \
      -max_len=16384 -print_final_stats=1 -artifact_prefix="$work/$t/" "${dict[@]}" \
      "$work/$t/corpus" "$work/seeds/$t" >"$work/$t/log.txt" 2>&1; then
    grep -E "^Done|stat::number_of_executed_units|stat::peak_rss_mb" "$work/$t/log.txt" | tr '\n' ' ' | sed 's/^/fuzz:   /'
    echo
  else
    echo "fuzz: $t FAILED (log: $work/$t/log.txt):" >&2
    grep -E "ERROR|SUMMARY|fuzz: the result|Test unit written|==[0-9]+==" "$work/$t/log.txt" | head -20 >&2 || true
    failed+=("$t")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: failures in ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: every target ran ${seconds}s clean"

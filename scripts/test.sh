#!/usr/bin/env bash
# Sets up, builds and runs every Wisp test (GoogleTest through ctest). GPU tests run on the
# machine's Vulkan device (Mesa's lavapipe where there is no GPU) with validation on.
#   scripts/test.sh [CTEST ARGS...]  every suite, once
#   scripts/test.sh --ci             what .ci/run runs: the format check (scripts/format.sh --check),
#                                    every suite, then
#     sync       the GPU suites again with the validation layer's synchronization checks
#                (WISP_TEST_SYNC_VALIDATION=1). Left out: the suites that run the wisp binary as a
#                subprocess (BadInput, Cli, Record, Sweep, Window, BsdfCli, Scripts, Hostile*), which do not take the
#                tests' context options; Cli.EveryPassIsCleanUnderSynchronizationValidation covers
#                the binary's passes under the same checks in the first round.
#     sanitize   the CPU suites built with ASan and UBSan in build-asan/ (scripts/sanitize.sh),
#                less the physics' stability trials (EveryPhysicsSetting.*, CpuReference.Repulsion
#                AndFriction...): they run the same solver code as the other CpuReference tests for
#                minutes of simulated steps, and took 10 of the round's 11.5 minutes under ASan
#     fuzz       each fuzz target (four loaders, the scene parser) for 12 s (scripts/fuzz.sh 12)
#   and prints how long each step took.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ci=0
if [ "${1:-}" = "--ci" ]; then
  ci=1
  shift
fi
jobs="$(nproc 2>/dev/null || echo 2)"
times=()
step() {
  local name="$1" start
  shift
  start="$(date +%s)"
  echo "test.sh: $name"
  "$@"
  times+=("$name $(($(date +%s) - start))s")
}

step setup "$root/scripts/setup.sh" --test
if [ "$ci" = 1 ]; then
  step format "$root/scripts/format.sh" --check
fi
step build "$root/scripts/build.sh"
cd "${WISP_BUILD_DIR:-$root/build}"
step tests ctest --output-on-failure -j "$jobs" "$@"
if [ "$ci" = 1 ]; then
  step sync env WISP_TEST_SYNC_VALIDATION=1 ctest --output-on-failure -j "$jobs" -L gpu \
    -E '^(BadInput|Cli|Record|Sweep|Window|BsdfCli|Scripts|Hostile[A-Za-z]*)\.'
  step sanitize "$root/scripts/sanitize.sh" \
    -E '^(Table/EveryPhysicsSetting\.|CpuReference\.RepulsionAndFrictionAreStableAtEveryAllowedValue$)'
  step fuzz "$root/scripts/fuzz.sh" 12
fi
echo "test.sh: passed (${times[*]})"

#!/usr/bin/env bash
# Installs the Debian packages Wisp needs. Idempotent: packages already installed are skipped, and
# nothing is done when all are present. Uses sudo when not root.
#   scripts/setup.sh          what the wisp executable builds and runs with (scripts/demo.sh)
#   scripts/setup.sh --test   that, and what scripts/test.sh adds: GoogleTest, the validation layers,
#                             Xvfb, ffmpeg, matplotlib (the tests of `record --video` and `sweep`'s
#                             charts), clang-format, clang for the sanitizer build and the fuzz targets
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev glslang-tools libglm-dev libassimp-dev libtinyobjloader-dev
  libglfw3-dev libimgui-dev libstb-dev nlohmann-json3-dev libcli11-dev
  mesa-vulkan-drivers  # lavapipe: a Vulkan device on machines without a GPU
)
if [ "${1:-}" = "--test" ]; then
  packages+=(
    libgtest-dev vulkan-validationlayers xvfb xauth
    ffmpeg python3-matplotlib  # `wisp record --video`, `wisp sweep`'s charts
    clang-format  # the format check of scripts/test.sh --ci (scripts/format.sh)
    clang libclang-rt-dev  # the sanitizer build and the fuzz targets (scripts/sanitize.sh, scripts/fuzz.sh)
  )
elif [ $# -gt 0 ]; then
  echo "setup: unknown option '$1' (scripts/setup.sh [--test])" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
    echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1
  fi
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
if ! $sudo apt-get update -qq || ! $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"; then
  echo "setup: apt-get could not install: ${missing[*]} (check network access to the Debian mirror and 'apt-get update')" >&2
  exit 1
fi

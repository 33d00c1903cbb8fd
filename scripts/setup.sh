#!/usr/bin/env bash
# Installs what Lucid needs to build and run on a fresh Debian/Ubuntu machine, when missing:
# the Vulkan loader, Mesa's lavapipe (Vulkan on the CPU, used when no GPU driver is present),
# the Khronos validation layers (tests run with them), and glslc (compiles the shaders).
set -euo pipefail

packages=(libvulkan1 mesa-vulkan-drivers vulkan-validationlayers glslc)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: run as root or install sudo to install ${missing[*]}" >&2; exit 1; }
    sudo="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
if ! command -v cargo >/dev/null; then
  echo "setup: cargo not found; install the Rust toolchain (https://rustup.rs) and rerun" >&2
  exit 1
fi

#!/usr/bin/env bash
# Installs what Lucid needs to build and run on a fresh Debian/Ubuntu machine, when missing:
# the Vulkan loader, Mesa's lavapipe (Vulkan on the CPU, used when no GPU driver is present),
# the Khronos validation layers (tests run with them), glslc (compiles the shaders), and the X
# libraries winit loads at run time plus Xvfb (the sandbox test runs the window under it), and
# Python 3 (docs/results/tables.py, which a test runs).
set -euo pipefail

packages=(libvulkan1 mesa-vulkan-drivers vulkan-validationlayers glslc
  xvfb libxkbcommon-x11-0 libx11-xcb1 libxcursor1 libxi6 python3)
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

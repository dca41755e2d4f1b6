#!/usr/bin/env bash
# Sets Prism up on a fresh Debian 12 machine: installs the Debian packages,
# configures and builds (build/), and renders the showcase to out/showcase.png.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config
  libglm-dev nlohmann-json3-dev libcli11-dev libfmt-dev
  libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libpng-dev libjpeg62-turbo-dev libopenexr-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libegl-dev libgl-dev libgl1-mesa-dri libegl-mesa0 libglfw3-dev
  xvfb xauth x11-apps glslang-tools spirv-tools chromium
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools glslang-dev
  povray
  clang libclang-rt-14-dev
  libopenmpi-dev openmpi-bin
  pybind11-dev python3-dev python3-numpy python3-pytest
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y --no-install-recommends "${missing[@]}"
fi

# Two builds into build/: first the libraries a frame runs through,
# instrumented, for the training renders of scripts/train_profile.sh; then
# everything, those libraries compiled with the counts the renders left
# (profile-guided optimisation, PRISM_PGO in CMakeLists.txt: ~4 % fewer
# instructions a frame, images bit for bit the same; about 2 minutes more).
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPRISM_PGO=generate
cmake --build build -j"$(nproc)" --target prism_profile_training
./scripts/train_profile.sh build
cmake -S . -B build -DPRISM_PGO=use
cmake --build build -j"$(nproc)"

mkdir -p out
./build/bin/prism render scenes/showcase.json -b auto -o out/showcase.png --stats out/showcase-stats.json
echo "rendered out/showcase.png"

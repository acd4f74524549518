#!/usr/bin/env bash
# Installs dependencies, builds, and runs every test: the Release build's suite, then the same
# suite built with AddressSanitizer + UndefinedBehaviorSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
export FACESOCIAL_DATA="${FACESOCIAL_DATA:-$(cd .. && pwd)/shared/datasets}"
./scripts/build.sh
(cd build && ctest -j2 --output-on-failure --timeout 900)

cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFACESOCIAL_SANITIZE=ON \
      -DFACESOCIAL_BUILD_BENCH=OFF -DFACESOCIAL_BUILD_PYTHON=OFF
cmake --build build-asan -j2
(cd build-asan && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 ctest -j2 --output-on-failure --timeout 1800 -E package_consumer)

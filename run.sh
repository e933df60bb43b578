#!/usr/bin/env bash
# refract's one set-up script (Debian 12, as root or with sudo):
#   bash run.sh reproduce   install what is missing, build, reproduce every figure and
#                           the validation report into out/ (open out/index.html)
#   bash run.sh test        install what is missing (and chromium, for the report's browser
#                           test), build, run the test suite (ctest), then
#                           the sanitizer build, its tests and 20 s of fuzzing
#   bash run.sh build       install and build only
#   bash run.sh sanitize    the sanitizer build (clang, ASan, UBSan, the fuzzer's coverage) of
#                           geometry/, core/, their tests and the libFuzzer target in
#                           build-sanitize/, and those tests
#   bash run.sh fuzz [S]    that build, then fuzz the scene reader, a tiny render and its files
#                           for S seconds (60); `test` runs it for 20 s, so that neither the
#                           target nor its oracle can rot
#                           (REFRACT_SKIP_SANITIZE=1 leaves the sanitizer tests and the
#                           fuzzing out of `test`)
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(build-essential cmake ninja-build pkg-config libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev
          libopenimageio-dev openimageio-tools libtbb-dev nlohmann-json3-dev libcli11-dev catch2
          libxsimd-dev gnuplot-nox povray libembree-dev libassimp-dev python3-dev python3-pybind11 pybind11-dev python3-numpy python3-pytest
          python3-matplotlib openmpi-bin libopenmpi-dev libyaml-cpp-dev libboost-dev libopenvdb-dev libboost-iostreams-dev)

install_missing() {
    local missing=()
    for p in "${PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    if [ ${#missing[@]} -gt 0 ]; then
        echo "run.sh: installing ${missing[*]}"
        local sudo=""
        [ "$(id -u)" -eq 0 ] || sudo="sudo"
        $sudo apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
    fi
}

# The sanitizer tree (build-sanitize/, clang): geometry/, core/, their tests and the
# libFuzzer target, with AddressSanitizer, UndefinedBehaviorSanitizer and the fuzzer's
# coverage, at -O1 -g1 (line tables for the reports) to keep its build short. One tree
# serves the sanitizer tests, the test path's short fuzz run and `fuzz`. Clang and its
# runtime libraries are installed only here.
sanitize_build() {
    PACKAGES+=(clang libclang-rt-14-dev)
    install_missing
    CXX=clang++ cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" \
        -DCMAKE_UNITY_BUILD=ON -DREFRACT_FUZZ=ON -DCGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE=TRUE >/dev/null
    cmake --build build-sanitize -j "$(nproc)"
}

sanitize() {
    sanitize_build
    ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" -L sanitize
}

# `fuzz_run SECONDS SEEDS...`: the fuzzer of build-sanitize/ for SECONDS (the seeds are all
# run first, however long they take), its corpus in build-sanitize/corpus, a failing input
# written to build-sanitize/findings/; it fails on one.
fuzz_run() {
    local dir=build-sanitize seconds="$1"
    shift
    mkdir -p "$dir/corpus" "$dir/findings"
    # Leak checks off in fuzzing (the sanitizer tests keep them): LeakSanitizer's
    # stop-the-world tracer crashes (signal 11 in the tracer, an empty "crash" unit) on some
    # runs of the whole seed set, while checking the process's worker threads; a tool fault,
    # reproduced and left for study. Address and undefined-behaviour errors still fail it.
    ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
    "./$dir/fuzz/scene_fuzzer" -detect_leaks=0 -max_total_time="$seconds" -max_len=65536 -timeout=20 -rss_limit_mb=4096 \
        -artifact_prefix="$dir/findings/" "$dir/corpus" "$@"
}

# The test path's short run: a fresh corpus, every seed but the 1998 diamond (whose exact
# cut and polyhedron take minutes under the sanitizers), 20 s.
fuzz_check() {
    rm -rf build-sanitize/corpus build-sanitize/seeds
    mkdir -p build-sanitize/seeds
    cp scenes/examples/*.json scenes/validation/*.json fuzz/seeds/*.json build-sanitize/seeds/
    rm build-sanitize/seeds/ohtsuka1998-diamond.json
    fuzz_run 20 build-sanitize/seeds
}

# Both trees are unity builds (CMake combines a library's sources eight to a file): the headers
# and the templates every source instantiates are compiled once per eight, which roughly halves
# a fresh build. The tests are not combined (tests/CMakeLists.txt); a developer's own tree
# (plain cmake) is not either, so that one edit recompiles one file.
build() {
    cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON >/dev/null
    cmake --build build -j "$(nproc)"
}

case "${1:-}" in
    reproduce)
        install_missing
        build
        shift
        ./build/cli/refract reproduce -o out "$@"
        ;;
    test)
        # Chromium for the report's browser test only (tests/report_in_browser.py).
        PACKAGES+=(chromium)
        install_missing
        build
        ctest --test-dir build --output-on-failure -j "$(nproc)"
        if [ "${REFRACT_SKIP_SANITIZE:-0}" != 1 ]; then
            sanitize
            fuzz_check
        fi
        ;;
    sanitize)
        install_missing
        sanitize
        ;;
    build)
        install_missing
        build
        ;;
    fuzz)
        sanitize_build
        fuzz_run "${2:-60}" scenes/examples scenes/validation fuzz/seeds
        ;;
    *)
        echo "usage: bash run.sh reproduce|test|build|sanitize|fuzz [SECONDS]" >&2
        exit 2
        ;;
esac

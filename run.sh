#!/usr/bin/env bash
# refract's one set-up script (Debian 12, as root or with sudo):
#   bash run.sh reproduce   install what is missing, build, reproduce every figure and
#                           the validation report into out/ (open out/index.html)
#   bash run.sh test        install what is missing, build, run the test suite (ctest), then
#                           the sanitizer build and its tests, and the fuzzing build
#   bash run.sh build       install and build only
#   bash run.sh sanitize    the sanitizer build (gcc, ASan, UBSan) of geometry/, core/ and
#                           their tests in build-sanitize/, and those tests
#                           (part of `test`; REFRACT_SKIP_SANITIZE=1 leaves it out)
#   bash run.sh fuzz [S]    build the libFuzzer target (clang, ASan, UBSan) in build-fuzz/ and
#                           fuzz the scene reader, a tiny render and its files for S seconds
#                           (60); `test` builds it too and runs it for 20 s, so that neither
#                           the target nor its oracle can rot
#                           (REFRACT_SKIP_FUZZ_BUILD=1 leaves it out)
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(build-essential cmake ninja-build pkg-config libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev
          libopenimageio-dev openimageio-tools libtbb-dev nlohmann-json3-dev libcli11-dev catch2
          libxsimd-dev gnuplot-nox povray libembree-dev python3-dev python3-pybind11 pybind11-dev python3-numpy python3-pytest
          python3-matplotlib openmpi-bin libopenmpi-dev)

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

# The sanitizer build (build-sanitize/, gcc): geometry/, core/ and their tests with
# AddressSanitizer and UndefinedBehaviorSanitizer, at -O1 to keep its build short.
sanitize() {
    cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" \
        -DREFRACT_SANITIZE=ON >/dev/null
    cmake --build build-sanitize -j "$(nproc)"
    ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" -L sanitize
}

# The libFuzzer target (clang; geometry/ and core/ instrumented for it and built with
# AddressSanitizer and UndefinedBehaviorSanitizer): `fuzz_build DIR TYPE` builds it in DIR
# with CMAKE_BUILD_TYPE TYPE. The test path builds it unoptimised and without debug
# information in build-fuzz-check/ (that it still compiles and links with clang, quickly)
# and runs it briefly (fuzz_check); `fuzz` builds and runs it optimised. Clang and its
# runtime libraries are installed only here.
fuzz_build() {
    PACKAGES+=(clang libclang-rt-14-dev)
    install_missing
    CXX=clang++ cmake -S . -B "$1" -G Ninja -DCMAKE_BUILD_TYPE="$2" -DREFRACT_FUZZ=ON \
        -DREFRACT_BUILD_TESTS=OFF -DCMAKE_CXX_FLAGS_DEBUG=-O0 -DCGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE=TRUE >/dev/null
    cmake --build "$1" -j "$(nproc)" --target scene_fuzzer
}

# `fuzz_run DIR SECONDS SEEDS...`: the fuzzer built in DIR for SECONDS (the seeds are all
# run first, however long they take), its corpus in DIR/corpus, a failing input written to
# DIR/findings/; it fails on one.
fuzz_run() {
    local dir="$1" seconds="$2"
    shift 2
    mkdir -p "$dir/corpus" "$dir/findings"
    "./$dir/fuzz/scene_fuzzer" -max_total_time="$seconds" -max_len=65536 -timeout=20 -rss_limit_mb=4096 \
        -artifact_prefix="$dir/findings/" "$dir/corpus" "$@"
}

# The test path's short run of the unoptimised target: a fresh corpus, every seed but the
# 1998 diamond (whose exact cut and polyhedron take minutes unoptimised), 20 s.
fuzz_check() {
    fuzz_build build-fuzz-check Debug
    rm -rf build-fuzz-check/corpus build-fuzz-check/seeds
    mkdir -p build-fuzz-check/seeds
    cp scenes/examples/*.json scenes/validation/*.json fuzz/seeds/*.json build-fuzz-check/seeds/
    rm build-fuzz-check/seeds/ohtsuka1998-diamond.json
    fuzz_run build-fuzz-check 20 build-fuzz-check/seeds
}

build() {
    cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
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
        install_missing
        build
        ctest --test-dir build --output-on-failure -j "$(nproc)"
        [ "${REFRACT_SKIP_SANITIZE:-0}" = 1 ] || sanitize
        [ "${REFRACT_SKIP_FUZZ_BUILD:-0}" = 1 ] || fuzz_check
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
        fuzz_build build-fuzz RelWithDebInfo
        fuzz_run build-fuzz "${2:-60}" scenes/examples scenes/validation fuzz/seeds
        ;;
    *)
        echo "usage: bash run.sh reproduce|test|build|sanitize|fuzz [SECONDS]" >&2
        exit 2
        ;;
esac

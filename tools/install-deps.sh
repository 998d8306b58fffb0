#!/bin/sh
# Installs what cyclopion needs to build and test, and nothing when it is all there.
# Debian 12, as root: one `apt-get update`, then the missing packages; then the Python
# packages of tools/requirements.txt with pip. Without root it only reports what is missing.
# qemu-system-x86, busybox-static and can-utils serve the SocketCAN tests (tools/canvm.py).
set -eu
here=$(cd "$(dirname "$0")" && pwd)

case "${1:-}" in
-h | --help)
    echo "usage: tools/install-deps.sh"
    echo "Installs the Debian packages and the Python packages (tools/requirements.txt) that"
    echo "cyclopion needs to build and test; nothing when all is there. As root on Debian 12;"
    echo "without root it lists what is missing and exits 1. make deps, make test and make demo"
    echo "run it first."
    exit 0
    ;;
"") ;;
*)
    echo "install-deps: unknown argument \"$1\" (tools/install-deps.sh --help)" >&2
    exit 2
    ;;
esac

# libclang-rt-16-dev: libFuzzer and the sanitizers' runtimes for clang-16 (the fuzz preset)
# liblcm-java, libjchart2d-java, openjdk-17-jdk-headless: lcm-spy and the Java types it decodes
# our channels with (lcm-gen -j, compiled by javac; make lcm-spy)
debs="clang-16 lld-16 llvm-16 clang-format-16 libclang-rt-16-dev mspdebug cmake ninja-build make \
libgtest-dev libeigen3-dev liblcm-dev liblcm-bin liblcm-java libjchart2d-java openjdk-17-jdk-headless \
libjansson-dev pkg-config python3 python3-pip gdb qemu-system-x86 busybox-static can-utils iproute2"

missing=""
for p in $debs; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing="$missing $p"
    fi
done

if [ -n "$missing" ]; then
    if [ "$(id -u)" -ne 0 ]; then
        echo "install-deps: missing Debian packages:$missing" >&2
        echo "install-deps: run as root (or: sudo apt-get install$missing)" >&2
        exit 1
    fi
    echo "install-deps: installing$missing"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q
    # shellcheck disable=SC2086
    apt-get install -y -q --no-install-recommends $missing
fi

# Every pinned requirement present at its version (tools/requirements.txt), or pip runs.
if ! python3 - "$here/requirements.txt" <<'PYEOF' 2>/dev/null
import sys
from importlib.metadata import version
for line in open(sys.argv[1]):
    line = line.split("#")[0].strip()
    if line:
        name, _, want = line.partition("==")
        if version(name) != want:
            sys.exit(1)
PYEOF
then
    echo "install-deps: installing Python packages from tools/requirements.txt"
    if ! python3 -m pip install -q --disable-pip-version-check -r "$here/requirements.txt" 2>/tmp/cy-pip.log; then
        if grep -q externally-managed /tmp/cy-pip.log; then
            python3 -m pip install -q --disable-pip-version-check --break-system-packages \
                -r "$here/requirements.txt"
        else
            cat /tmp/cy-pip.log >&2
            exit 1
        fi
    fi
fi
exit 0

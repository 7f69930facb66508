#!/bin/sh
# OpenSeesPy's Linux wheel links against the system reference BLAS (libblas.so.3).
# Install it (Debian/Ubuntu package libblas3) when running as root; otherwise say what to install.
[ "$(uname -s)" = "Linux" ] || exit 0
if ldconfig -p 2>/dev/null | grep -q 'libblas\.so\.3'; then
    exit 0
fi
if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null 2>&1; then
    echo "opsrock: installing libblas3 (system BLAS needed by OpenSeesPy)"
    # apt-get update must run first on a fresh machine, or libblas3 is not found
    apt-get update -qq >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libblas3 >/dev/null \
        || { echo "opsrock: could not install libblas3 with apt-get; install the system BLAS (libblas.so.3) and retry" >&2; exit 1; }
    exit 0
fi
echo "opsrock: the system BLAS libblas.so.3 is missing; install it (Debian/Ubuntu: sudo apt-get install libblas3) and retry" >&2
exit 1

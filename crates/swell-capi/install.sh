#!/bin/sh
# Installs the swell C library: PREFIX/lib/libswell.so and libswell.a, PREFIX/include/swell.h and
# PREFIX/lib/pkgconfig/swell.pc (from swell.pc.in).
#
#   sh crates/swell-capi/install.sh PREFIX             # builds with `cargo build --release -p swell-capi` first
#   sh crates/swell-capi/install.sh PREFIX LIBDIR      # installs libraries already built in LIBDIR (no build)
#
# Then: cc app.c $(PKG_CONFIG_PATH=PREFIX/lib/pkgconfig pkg-config --cflags --libs swell)
# (add `--static` to pkg-config's arguments and link libswell.a for a static build).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
[ $# -ge 1 ] || { echo "usage: $0 PREFIX [LIBDIR]" >&2; exit 2; }
mkdir -p "$1"
prefix=$(cd "$1" && pwd)
if [ $# -ge 2 ]; then
  libdir=$2
else
  (cd "$root" && cargo build --release -p swell-capi)
  libdir="${CARGO_TARGET_DIR:-$root/target}/release"
fi
version=$(sed -n 's/^version = "\(.*\)"/\1/p' "$root/Cargo.toml" | head -n 1)
mkdir -p "$prefix/lib/pkgconfig" "$prefix/include"
cp "$libdir/libswell.so" "$libdir/libswell.a" "$prefix/lib/"
cp "$here/include/swell.h" "$prefix/include/"
sed -e "s|@PREFIX@|$prefix|" -e "s|@VERSION@|$version|" "$here/swell.pc.in" > "$prefix/lib/pkgconfig/swell.pc"
echo "installed swell $version into $prefix"

#!/bin/sh
# Fetches and unpacks Debian bookworm's source packages of urdfdom and its dependencies
# into DIR (the wasm build's cache): `apt-get source` needs a deb-src entry, added here
# (deb822 file in /etc/apt/sources.list.d) when none exists and we may write there.
# Usage: fetch_debian_sources.sh DIR PACKAGE...
set -eu
dir=$1
shift
if ! grep -rqs '^[^#]*deb-src' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  list=/etc/apt/sources.list.d/achd-deb-src.sources
  if [ ! -w /etc/apt/sources.list.d ]; then
    echo "fetch_debian_sources: no deb-src entry in /etc/apt and $list is not writable;" >&2
    echo "add 'deb-src http://deb.debian.org/debian bookworm main' and run apt-get update" >&2
    exit 1
  fi
  printf 'Types: deb-src\nURIs: http://deb.debian.org/debian\nSuites: bookworm\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' > "$list"
  apt-get update -qq
elif ! apt-get source --print-uris "$1" >/dev/null 2>&1; then
  apt-get update -qq
fi
mkdir -p "$dir"
cd "$dir"
for pkg in "$@"; do
  if [ ! -e "$pkg.stamp" ]; then
    apt-get source -qq "$pkg"
    touch "$pkg.stamp"
  fi
done

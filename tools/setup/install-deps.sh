#!/usr/bin/env bash
# TAPMC setup helper: install the Debian packages of debian-packages.txt that are missing, as
# root or through sudo (a no-op, apart from a dpkg query, when all are installed). When neither
# can install them: the optional ones are named with what is left out without them, and a missing
# required one stops the script with the apt-get line for an administrator. Prints on stdout the
# optional packages still missing (tools/setup/build.sh passes them on to CMake).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
list="$here/debian-packages.txt"
required=() optional=()
declare -A why=()
while read -r kind package reason; do
  [[ -z "$kind" || "$kind" == "#"* ]] && continue
  why[$package]=$reason
  status=$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)
  [[ "$status" == *"install ok installed"* ]] && continue
  case "$kind" in
    required) required+=("$package") ;;
    optional) optional+=("$package") ;;
    *) echo "install-deps.sh: $list: '$kind $package' is neither required nor optional" >&2
       exit 2 ;;
  esac
done < "$list"
missing=("${required[@]}" "${optional[@]}")
((${#missing[@]})) || exit 0

# Root installs everything, as does a sudo that works; a sudo that refuses is reported below.
if [ "$(id -u)" -eq 0 ] || command -v sudo > /dev/null; then
  as_root=(); [ "$(id -u)" -eq 0 ] || as_root=(sudo)
  echo "tapmc: installing missing Debian packages${as_root:+ with sudo}: ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  if "${as_root[@]}" apt-get update -qq && "${as_root[@]}" apt-get install -y -qq \
       --no-install-recommends "${missing[@]}" > /dev/null; then
    exit 0
  fi
  [ "$(id -u)" -ne 0 ] || exit 1
  echo "tapmc: sudo could not install them (the message above); going on without them" >&2
fi

# "what needs it (package ...); ..." of the packages given, one entry per reason.
needs() {
  local -A packages=()
  local order=() package reason text=
  for package; do
    reason=${why[$package]}
    [ -n "${packages[$reason]-}" ] || order+=("$reason")
    packages[$reason]+="${packages[$reason]:+ }$package"
  done
  for reason in "${order[@]}"; do text+="${text:+; }$reason (${packages[$reason]})"; done
  echo "$text"
}

if ((${#optional[@]})); then
  echo "tapmc: left out for want of optional Debian packages (not root, so not installed):" \
       "$(needs "${optional[@]}")" >&2
fi
if ((${#required[@]})); then
  echo "tapmc: required Debian packages are missing, for $(needs "${required[@]}")" >&2
  echo "tapmc: this user cannot install them (not root, and no sudo that works); an" \
       "administrator installs them${optional[*]:+, and the optional ones,} with" >&2
  echo "  apt-get install --no-install-recommends ${missing[*]}" >&2
  echo "tapmc: or build TAPMC against a LAMMPS of your own, without Debian's packages:" \
       "doc/install.rst, route 1" >&2
  exit 1
fi
echo "${optional[*]}"

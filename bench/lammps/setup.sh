#!/bin/sh
# Installs Debian's LAMMPS (package `lammps`, binary `lmp`) for the peridynamics benchmark
# (apps/cleave-bench-pd). Needs root or sudo and Debian's apt registry; nothing else is fetched.
set -e
if command -v lmp >/dev/null 2>&1; then
  echo "lammps already installed: $(command -v lmp)"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends lammps
command -v lmp

# Sourced by tests/run and sandbox/run: makes sure a Vulkan driver (and, for tests, Xvfb) is
# installed. On a machine without one, installs Mesa's software driver (lavapipe) from
# Debian/Ubuntu packages. Every path that cannot go on says why in one line on stderr and
# returns non-zero, so the calling script (under `set -euo pipefail`) stops with a message.
#
# The folders searched for Vulkan driver manifests can be overridden (space-separated) with
# POM_VULKAN_ICD_DIRS; tests/tests/ensure_vulkan.rs uses that, with a fake apt-get on PATH.

POM_VULKAN_ICD_DIRS=${POM_VULKAN_ICD_DIRS:-/usr/share/vulkan/icd.d /etc/vulkan/icd.d}

# Prints the first driver manifest matching the glob $1 in the ICD folders, or nothing.
# Never fails: no `ls | head`, whose exit status under `pipefail` ended the script silently
# when the folders were missing.
first_icd_manifest() {
    local dir file
    for dir in $POM_VULKAN_ICD_DIRS; do
        for file in "$dir"/$1; do
            if [ -f "$file" ]; then
                printf '%s\n' "$file"
                return 0
            fi
        done
    done
    return 0
}

# ldconfig lives in /sbin, which is not on a normal user's PATH on Debian.
POM_LDCONFIG_FALLBACK=${POM_LDCONFIG_FALLBACK:-/sbin/ldconfig}

has_vulkan_loader() {
    local ldconfig
    ldconfig=$(command -v ldconfig || true)
    if [ -z "$ldconfig" ] && [ -x "$POM_LDCONFIG_FALLBACK" ]; then ldconfig=$POM_LDCONFIG_FALLBACK; fi
    if [ -z "$ldconfig" ]; then return 1; fi
    # No `grep -q`: it would close the pipe early, and under `pipefail` ldconfig's SIGPIPE
    # would count as "not found".
    "$ldconfig" -p 2>/dev/null | grep 'libvulkan\.so\.1' >/dev/null
}

# Both commands build with cargo: say so when it is missing, before installing anything.
require_cargo() {
    if ! command -v cargo >/dev/null; then
        echo "error: cargo is not on PATH; install a Rust toolchain (1.95 or newer, https://rustup.rs) and run again" >&2
        return 1
    fi
}

as_root() {
    if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi
}

# install_packages WHAT PACKAGE...: installs Debian packages with apt-get (as root or with sudo),
# or says in one line which packages to install and returns 1.
install_packages() {
    local what=$1
    shift
    if ! command -v apt-get >/dev/null; then
        echo "error: $what is missing and this machine has no apt-get; install the packages $* (or your system's equivalent) and run again" >&2
        return 1
    fi
    if [ "$(id -u)" != 0 ] && ! command -v sudo >/dev/null; then
        echo "error: $what is missing and installing it needs root or sudo; as root run: apt-get install $*" >&2
        return 1
    fi
    echo "installing $what ($*)..." >&2
    if ! as_root apt-get update -qq ||
        ! as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$@" >/dev/null; then
        echo "error: apt-get could not install $* (its messages are above); install them by hand and run again" >&2
        return 1
    fi
}

install_lavapipe() {
    install_packages "a Vulkan driver" mesa-vulkan-drivers libvulkan1
}

# Ensures lavapipe is present; exports the variables that pin wgpu to it.
use_lavapipe() {
    if [ -z "$(first_icd_manifest 'lvp_icd.*.json')" ] || ! has_vulkan_loader; then
        install_lavapipe || return 1
    fi
    VK_DRIVER_FILES=$(first_icd_manifest 'lvp_icd.*.json')
    if [ -z "$VK_DRIVER_FILES" ] || ! has_vulkan_loader; then
        echo "error: lavapipe (mesa-vulkan-drivers) or the Vulkan loader (libvulkan1) is still missing after installing them" >&2
        return 1
    fi
    # Without WGPU_BACKEND a missing driver silently falls back to GL.
    export VK_DRIVER_FILES WGPU_BACKEND=vulkan NODEVICE_SELECT=1
}

# Ensures some Vulkan driver exists (a GPU's, or lavapipe as a fallback).
ensure_any_vulkan() {
    if [ -z "$(first_icd_manifest '*.json')" ] || ! has_vulkan_loader; then
        install_lavapipe || return 1
        if [ -z "$(first_icd_manifest '*.json')" ] || ! has_vulkan_loader; then
            echo "error: no Vulkan driver (mesa-vulkan-drivers) or loader (libvulkan1) after installing them" >&2
            return 1
        fi
    fi
}

# Ensures the X virtual framebuffer and xdotool exist, for the tests that start real windows.
ensure_xvfb() {
    if command -v Xvfb >/dev/null && command -v xdotool >/dev/null; then return 0; fi
    install_packages "the X virtual framebuffer" xvfb xauth xdotool || return 1
    if ! command -v Xvfb >/dev/null || ! command -v xdotool >/dev/null; then
        echo "error: Xvfb or xdotool is still missing after installing xvfb and xdotool" >&2
        return 1
    fi
}

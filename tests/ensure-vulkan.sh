# Sourced by tests/run and sandbox/run: makes sure a Vulkan driver (and, for tests, Xvfb) is
# installed.
# On a machine without one, installs Mesa's software driver (lavapipe) from Debian/Ubuntu packages.

as_root() {
    if [ "$(id -u)" = 0 ]; then "$@"; elif command -v sudo >/dev/null; then sudo "$@"; else
        echo "error: need root (or sudo) to run: $*" >&2; return 1
    fi
}

install_lavapipe() {
    echo "installing Mesa's software Vulkan driver (mesa-vulkan-drivers, libvulkan1)..." >&2
    as_root apt-get update -qq
    DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq --no-install-recommends \
        mesa-vulkan-drivers libvulkan1 >/dev/null
}

# The lavapipe ICD manifest, or nothing.
lavapipe_icd() {
    ls /usr/share/vulkan/icd.d/lvp_icd.*.json 2>/dev/null | head -n 1
}

has_vulkan_loader() {
    # No `grep -q`: it would close the pipe early, and under `pipefail` ldconfig's SIGPIPE
    # would count as "not found".
    ldconfig -p 2>/dev/null | grep 'libvulkan\.so\.1' >/dev/null
}

# Ensures lavapipe is present; exports the variables that pin wgpu to it.
use_lavapipe() {
    if [ -z "$(lavapipe_icd)" ] || ! has_vulkan_loader; then install_lavapipe; fi
    VK_DRIVER_FILES="$(lavapipe_icd)"
    if [ -z "$VK_DRIVER_FILES" ]; then
        echo "error: lavapipe's ICD manifest is still missing after installing mesa-vulkan-drivers" >&2
        return 1
    fi
    # Without WGPU_BACKEND a missing driver silently falls back to GL.
    export VK_DRIVER_FILES WGPU_BACKEND=vulkan NODEVICE_SELECT=1
}

# Ensures some Vulkan driver exists (a GPU's, or lavapipe as a fallback).
ensure_any_vulkan() {
    local manifests
    manifests=$(ls /usr/share/vulkan/icd.d/*.json /etc/vulkan/icd.d/*.json 2>/dev/null | head -n 1)
    if [ -z "$manifests" ] || ! has_vulkan_loader; then install_lavapipe; fi
}

# Ensures the X virtual framebuffer exists, for the test that starts the real sandbox window.
ensure_xvfb() {
    if command -v Xvfb >/dev/null; then return 0; fi
    echo "installing the X virtual framebuffer (xvfb, xauth)..." >&2
    as_root apt-get update -qq
    DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq --no-install-recommends \
        xvfb xauth >/dev/null
}

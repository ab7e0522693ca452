#!/bin/sh
# The image's entry point: picks the Vulkan drivers, then runs `facial` with
# the container's arguments. Where the NVIDIA container runtime gave the
# container a GPU (/dev/nvidia0 ... exist), NVIDIA's ICD comes first and the
# renderer picks that discrete GPU; lavapipe (Mesa, CPU) stays listed, so CPU
# nodes render and FACIAL_DEVICE=cpu still works. The runtime mounts the
# driver's library (NVIDIA_DRIVER_CAPABILITIES includes graphics) but not
# always its ICD file, so the image carries one naming that library.
# A VK_ICD_FILENAMES / VK_DRIVER_FILES set by the user wins.
# FACIAL_ICD_ROOT (tests only) prefixes the /dev and ICD folders looked at.
set -eu
root="${FACIAL_ICD_ROOT:-}"

nvidia_icd() {
  for f in "$root/etc/vulkan/icd.d/nvidia_icd.json" "$root/usr/share/vulkan/icd.d/nvidia_icd.json" \
           "$root/opt/facial/nvidia_icd.json"; do
    if [ -f "$f" ]; then echo "$f"; return 0; fi
  done
  return 1
}

lavapipe_icd() {
  for f in "$root"/usr/share/vulkan/icd.d/lvp_icd.*.json; do
    if [ -f "$f" ]; then echo "$f"; return 0; fi
  done
  return 1
}

if [ -z "${VK_ICD_FILENAMES:-}${VK_DRIVER_FILES:-}" ]; then
  drivers="$(lavapipe_icd || true)"
  if ls "$root"/dev/nvidia[0-9]* >/dev/null 2>&1 && gpu="$(nvidia_icd)"; then
    drivers="$gpu${drivers:+:$drivers}"
  fi
  if [ -z "$drivers" ]; then
    echo "facial-entrypoint: no Vulkan driver: neither lavapipe (mesa-vulkan-drivers) nor an NVIDIA GPU" >&2
    exit 1
  fi
  # The Vulkan loader of bookworm reads both names (VK_DRIVER_FILES is the newer).
  export VK_ICD_FILENAMES="$drivers" VK_DRIVER_FILES="$drivers"
fi
exec facial "$@"

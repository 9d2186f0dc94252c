#!/bin/sh
# psnr_at_least.sh A.png B.png MIN_DB: passes when OpenImageIO's idiff measures a peak
# signal-to-noise ratio of at least MIN_DB decibels between the two images (same size).
a=$1
b=$2
min=$3
out=$(idiff "$a" "$b" 2>&1)
printf '%s\n' "$out"
psnr=$(printf '%s\n' "$out" | sed -n 's/^ *Peak SNR = //p')
case "$out" in *PASS*) psnr=${psnr:-inf} ;; esac
if [ -z "$psnr" ]; then
  echo "psnr_at_least: idiff gave no PSNR (different sizes or unreadable images?)" >&2
  exit 1
fi
echo "PSNR $psnr dB (at least $min dB expected)"
awk -v p="$psnr" -v m="$min" 'BEGIN { exit !(p == "inf" || p + 0 >= m + 0) }'

#!/bin/sh
# bench/psnr_ceiling.sh [WANGSCAPE] [FOLDER]: how close any frame can come to the Embree
# reference. Ray traces the scene's camera of FOLDER (default out/view-bench, made by
# bench/view_bench.sh) at 1, 4, 16, 64 and 256 samples per pixel (SPP to change the list; the
# last is taken as converged) and prints the PSNR of each image, and of the LDI view's frame,
# against the 4-sample reference (what `wangscape view --compare` uses by default) and against
# the converged one. PSNR as `renders/trace/image_compare.h` defines it (8-bit RGB, all channels),
# computed here by OpenImageIO's idiff.
set -eu
bin=${1:-build/release/cli/wangscape}
dir=${2:-out/view-bench}
spp_list=${SPP:-1 4 16 64 256}
if [ ! -s "$dir/tiles.ldi" ]; then
  echo "psnr_ceiling: $dir/tiles.ldi is missing: run sh bench/view_bench.sh first (it builds $dir)" >&2
  exit 2
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# (idiff prints no PSNR for identical images)
psnr() { idiff -fail 0 -failpercent 0 -warn 0 -a "$1" "$2" 2>&1 | sed -n 's/.*Peak SNR = *//p' | grep . || echo same; }
converged=""
for n in $spp_list; do
  start=$(date +%s.%N)
  "$bin" --quiet render "$dir" --engine embree --spp "$n" --out "$work/ref$n.png"
  echo "reference at $n samples per pixel: $(awk "BEGIN { printf \"%.1f\", $(date +%s.%N) - $start }") s"
  converged=$n
done
"$bin" --quiet view "$dir" --out "$work/ldi.png"
printf '%-22s %18s %22s\n' image "PSNR vs 4 spp (dB)" "PSNR vs $converged spp (dB)"
for n in $spp_list; do
  [ "$n" = "$converged" ] && continue
  printf '%-22s %18s %22s\n' "reference, $n spp" "$(psnr "$work/ref$n.png" "$work/ref4.png")" \
    "$(psnr "$work/ref$n.png" "$work/ref$converged.png")"
done
printf '%-22s %18s %22s\n' "LDI view frame" "$(psnr "$work/ldi.png" "$work/ref4.png")" \
  "$(psnr "$work/ldi.png" "$work/ref$converged.png")"
printf '%-22s %18s %22s\n' "reference, $converged spp" "$(psnr "$work/ref$converged.png" "$work/ref4.png")" "-"

#!/bin/sh
# wind_frames_check.sh FRAME SAME_TIME OTHER_TIME MIN_DB MARGIN_DB: a windy frame of one engine
# against another engine's frames of the same camera, at the same time and at another: passes when
# the same time's PSNR (idiff) is at least MIN_DB and beats the other time's by MARGIN_DB. The
# engines then sway the plants alike in time, not only lean them alike.
psnr() {
  idiff "$1" "$2" 2>&1 | sed -n 's/^ *Peak SNR = //p'
}
same=$(psnr "$1" "$2")
other=$(psnr "$1" "$3")
echo "PSNR $same dB at the same time, $other dB at another (at least $4 dB, and $5 dB apart, expected)"
[ -n "$same" ] && [ -n "$other" ] || { echo "wind_frames_check: idiff gave no PSNR" >&2; exit 1; }
awk -v s="$same" -v o="$other" -v m="$4" -v d="$5" 'BEGIN { exit !(s + 0 >= m + 0 && s - o >= d + 0) }'

"""Checks `wangscape view --compare --json` output on stdin against floors given as arguments:
view_compare_check.py MIN_PSNR_DB MIN_SSIM MAX_HOLE_SHARE. Prints the figures, then "ok"."""
import json
import sys

figures = json.loads(sys.stdin.read())
print(figures)
min_psnr, min_ssim, max_holes = (float(a) for a in sys.argv[1:4])
assert figures["psnr_db"] > min_psnr, "PSNR %.2f dB below %.2f" % (figures["psnr_db"], min_psnr)
assert figures["ssim"] > min_ssim, "SSIM %.4f below %.4f" % (figures["ssim"], min_ssim)
assert figures["hole_share"] < max_holes, "hole share %.4f above %.4f" % (figures["hole_share"], max_holes)
print("ok")

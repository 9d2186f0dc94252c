"""Checks `wangscape view --path` figures on stdin. With "stats": one object with exactly the
keys of --stats --json with --path, the median no larger than the 95th percentile, no larger than
the slowest; prints "ok N frames". With "compare": one JSON line per compared frame with the
comparison's keys; prints "ok" and the frames compared."""
import json
import sys

if sys.argv[1] == "stats":
    stats = json.loads(sys.stdin.read())
    assert list(stats) == ["frame_ms", "frame_ms_p95", "frame_ms_max", "fresh_share", "frames"], list(stats)
    assert 0 < stats["fresh_share"] <= 1, stats
    assert 0 < stats["frame_ms"] <= stats["frame_ms_p95"] <= stats["frame_ms_max"], stats
    print("ok", stats["frames"], "frames")
else:
    lines = [json.loads(line) for line in sys.stdin]
    keys = {"frame", "frame_ms", "psnr_db", "ssim", "hole_share", "exact_psnr_db", "exact_ssim", "psnr_gap_db", "ssim_gap"}
    assert lines and all(keys <= set(line) for line in lines), lines
    print("ok", *[line["frame"] for line in lines])

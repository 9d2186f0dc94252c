"""Checks `wangscape view --stats --json` output on stdin: exactly the documented keys in their
order, levels adding up to the drawn tiles; prints "ok N" with N = drawn + culled tiles."""
import json
import sys

stats = json.loads(sys.stdin.read())
assert list(stats) == ["frame_ms", "fps", "depth_pixels", "tiles", "levels", "ray_cast"], list(stats)
assert isinstance(stats["ray_cast"], bool), stats
assert list(stats["tiles"]) == ["drawn", "culled", "steep"], list(stats["tiles"])
assert 0 <= stats["tiles"]["steep"] <= stats["tiles"]["drawn"], stats["tiles"]
assert all(isinstance(n, int) for n in stats["levels"]), stats["levels"]
assert sum(stats["levels"]) == stats["tiles"]["drawn"], stats
assert stats["frame_ms"] > 0 and stats["fps"] > 0, stats
assert stats["ray_cast"] or stats["depth_pixels"] > 0, stats
print("ok", stats["tiles"]["drawn"] + stats["tiles"]["culled"], "levels", len(stats["levels"]))

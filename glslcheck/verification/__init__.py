"""Verification: compare renders (compare), verify a CPU render against the GL and WebGL drivers
(verify), probe a pixel (probe), time against accuracy (bench) and the HTML report (report)."""

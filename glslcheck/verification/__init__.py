"""Verification: compare renders (compare), verify a CPU render against the GL and WebGL drivers
(verify; with the pixels where the two drivers differ set apart: drivers), probe a pixel
(probe), time against accuracy (bench) and the HTML report (report)."""

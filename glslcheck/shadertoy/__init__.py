"""The Shadertoy model: the tab files of a shader (sources), the program Shadertoy wraps around a
tab (wrapper), one frame's inputs (frame_inputs), and the channel bindings of a folder
(channels)."""

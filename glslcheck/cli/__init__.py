"""The `glslcheck` command line: argument parsing only (main), one module a subcommand
(commands)."""

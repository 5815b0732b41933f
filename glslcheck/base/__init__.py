"""What every stage stands on: diagnostics and their locations, records, compiled regular
expressions, image files, and the list of float precisions. Imports nothing else of glslcheck."""
